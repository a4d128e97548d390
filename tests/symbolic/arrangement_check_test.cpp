// Arranged goals (issue 23, class 2): the geometric predicates of lines, circles, triangles,
// squares and spread-out objects, their check on a scene, and the goal statement an LLM writes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/symbolic/arrangement_check.hpp"
#include "lang2manip/symbolic/goal_statement.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;
using nlohmann::json;

/// A 4 cm block's box centred at (x, y).
AlignedBox3 block(double x, double y) { return {Vector3(x - 0.02, y - 0.02, 0.0), Vector3(x + 0.02, y + 0.02, 0.04)}; }

Goal arranged(ArrangementShape shape, std::size_t members) {
  Goal goal;
  goal.kind = GoalKind::kArranged;
  goal.shape = shape;
  for (std::size_t i = 0; i < members; ++i) goal.members.push_back("block" + std::to_string(i));
  return goal;
}

std::vector<AlignedBox3> onCircle(std::size_t n, double radius, double firstAngle = 0.3) {
  std::vector<AlignedBox3> boxes;
  for (std::size_t k = 0; k < n; ++k) {
    const double angle = firstAngle + 2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n);
    boxes.push_back(block(0.5 + radius * std::cos(angle), 0.1 + radius * std::sin(angle)));
  }
  return boxes;
}

TEST(ArrangementCheck, ALineHoldsWithinTheToleranceOfItsFittedLineAndAlongItsHeading) {
  Goal line = arranged(ArrangementShape::kLine, 4);
  std::vector<AlignedBox3> boxes{block(0.5, -0.15), block(0.505, -0.05), block(0.495, 0.05), block(0.5, 0.15)};
  EXPECT_TRUE(checkArrangedBoxes(line, boxes, {}).holds);
  line.heading = std::numbers::pi / 2.0;  // sideways: either way along it
  EXPECT_TRUE(checkArrangedBoxes(line, boxes, {}).holds);
  line.heading = -std::numbers::pi / 2.0;
  EXPECT_TRUE(checkArrangedBoxes(line, boxes, {}).holds);
  line.heading = 0.0;
  const GoalCheck across = checkArrangedBoxes(line, boxes, {});
  EXPECT_FALSE(across.holds);
  EXPECT_THAT(across.explanation, HasSubstr("89 deg off the wanted direction"));
  line.heading.reset();
  boxes[2] = block(0.56, 0.05);  // 6 cm off the line
  const GoalCheck bent = checkArrangedBoxes(line, boxes, {});
  EXPECT_FALSE(bent.holds);
  EXPECT_THAT(bent.explanation, HasSubstr("of a line along yaw"));
}

TEST(ArrangementCheck, EvenSpacingAndAGivenSpacingAreMeasuredBetweenNeighbours) {
  Goal line = arranged(ArrangementShape::kLine, 3);
  line.evenlySpaced = true;
  EXPECT_TRUE(checkArrangedBoxes(line, {block(0.4, 0.0), block(0.5, 0.0), block(0.6, 0.0)}, {}).holds);
  const GoalCheck uneven = checkArrangedBoxes(line, {block(0.4, 0.0), block(0.45, 0.0), block(0.6, 0.0)}, {});
  EXPECT_FALSE(uneven.holds);
  EXPECT_THAT(uneven.explanation, HasSubstr("neighbours 0.050 to 0.150 m apart"));
  line.distance = 0.10;
  EXPECT_TRUE(checkArrangedBoxes(line, {block(0.4, 0.0), block(0.5, 0.0), block(0.6, 0.0)}, {}).holds);
  EXPECT_FALSE(checkArrangedBoxes(line, {block(0.4, 0.0), block(0.55, 0.0), block(0.7, 0.0)}, {}).holds);
}

TEST(ArrangementCheck, ACircleNeedsEveryCentreOnItAndTheMembersSpreadAroundIt) {
  const Goal circle = arranged(ArrangementShape::kCircle, 5);
  EXPECT_TRUE(checkArrangedBoxes(circle, onCircle(5, 0.10), {}).holds);
  std::vector<AlignedBox3> squeezed = onCircle(5, 0.10);
  squeezed[1] = onCircle(5, 0.10, 0.35)[0];  // two almost at one place, a gap elsewhere
  EXPECT_FALSE(checkArrangedBoxes(circle, squeezed, {}).holds);
  std::vector<AlignedBox3> dented = onCircle(5, 0.10);
  dented[2] = onCircle(5, 0.06)[2];
  const GoalCheck off = checkArrangedBoxes(circle, dented, {});
  EXPECT_FALSE(off.holds);
  EXPECT_THAT(off.explanation, HasSubstr("of a circle of radius"));
  EXPECT_FALSE(checkArrangedBoxes(arranged(ArrangementShape::kCircle, 2), onCircle(2, 0.1), {}).holds);
}

TEST(ArrangementCheck, TrianglesAndSquaresAreRegularPolygonsOfTheirMembers) {
  EXPECT_TRUE(checkArrangedBoxes(arranged(ArrangementShape::kTriangle, 3), onCircle(3, 0.08), {}).holds);
  EXPECT_TRUE(checkArrangedBoxes(arranged(ArrangementShape::kSquare, 4), onCircle(4, 0.08, 0.0), {}).holds);
  // Three in a row are no triangle; a rhombus is no square.
  EXPECT_FALSE(checkArrangedBoxes(arranged(ArrangementShape::kTriangle, 3), {block(0.4, 0.0), block(0.5, 0.0), block(0.6, 0.0)}, {}).holds);
  const std::vector<AlignedBox3> rhombus{block(0.5, 0.0), block(0.6, 0.06), block(0.7, 0.0), block(0.6, -0.06)};
  EXPECT_FALSE(checkArrangedBoxes(arranged(ArrangementShape::kSquare, 4), rhombus, {}).holds);
  const GoalCheck count = checkArrangedBoxes(arranged(ArrangementShape::kSquare, 3), onCircle(3, 0.08), {});
  EXPECT_FALSE(count.holds);
  EXPECT_THAT(count.explanation, HasSubstr("a square takes 4, 8, 12, ... members (its corners, and as many more evenly along each side), not 3"));
}

/// Members on the outline of a regular polygon: `perSide` from each corner along its side.
std::vector<AlignedBox3> onOutline(std::size_t corners, std::size_t perSide, double radius, double rotation) {
  std::vector<AlignedBox3> boxes;
  for (const Eigen::Vector2d& spot : regularOutline(Eigen::Vector2d(0.5, 0.1), radius, rotation, corners, perSide)) {
    boxes.push_back(block(spot.x(), spot.y()));
  }
  return boxes;
}

TEST(ArrangementCheck, MorePolygonMembersThanCornersStandEvenlyAlongItsSides) {
  // Eight in a square: its corners and the middle of each side; six and nine in a triangle.
  std::vector<AlignedBox3> square = onOutline(4, 2, 0.16, 0.4);
  std::reverse(square.begin(), square.end());  // the members' order does not matter
  EXPECT_TRUE(checkArrangedBoxes(arranged(ArrangementShape::kSquare, 8), square, {}).holds);
  EXPECT_TRUE(checkArrangedBoxes(arranged(ArrangementShape::kTriangle, 6), onOutline(3, 2, 0.14, 0.0), {}).holds);
  EXPECT_TRUE(checkArrangedBoxes(arranged(ArrangementShape::kTriangle, 9), onOutline(3, 3, 0.2, 1.0), {}).holds);
  // A side member off the middle of its side, or all eight on a circle, is no square.
  std::vector<AlignedBox3> shifted = onOutline(4, 2, 0.16, 0.4);
  shifted[1] = onOutline(4, 3, 0.16, 0.4)[1];
  const GoalCheck off = checkArrangedBoxes(arranged(ArrangementShape::kSquare, 8), shifted, {});
  EXPECT_FALSE(off.holds);
  EXPECT_THAT(off.explanation, HasSubstr("of the corners and 1 evenly spaced spots of each side of a regular polygon"));
  EXPECT_FALSE(checkArrangedBoxes(arranged(ArrangementShape::kSquare, 8), onCircle(8, 0.16), {}).holds);
  // Nine in a square or five in a triangle: not a multiple of the corners.
  EXPECT_THAT(memberCountProblem(ArrangementShape::kSquare, 9), HasSubstr("not 9"));
  EXPECT_THAT(memberCountProblem(ArrangementShape::kTriangle, 5), HasSubstr("a triangle takes 3, 6, 9, ... members"));
  EXPECT_EQ(memberCountProblem(ArrangementShape::kSquare, 12), "");
  EXPECT_THAT(memberCountProblem(ArrangementShape::kCircle, 2), HasSubstr("a circle needs at least 3 members, not 2"));
  EXPECT_THAT(memberCountProblem(ArrangementShape::kPyramid, 4), HasSubstr("3, 6 or 10"));
}

TEST(ArrangementCheck, SpreadOutMeansNoTwoNextToEachOther) {
  const Goal spread = arranged(ArrangementShape::kSpreadOut, 3);
  EXPECT_TRUE(checkArrangedBoxes(spread, {block(0.4, 0.0), block(0.55, 0.0), block(0.4, 0.2)}, {}).holds);
  const GoalCheck close = checkArrangedBoxes(spread, {block(0.4, 0.0), block(0.48, 0.0), block(0.4, 0.2)}, {});
  EXPECT_FALSE(close.holds);
  EXPECT_THAT(close.explanation, HasSubstr("the closest two are 0.040 m apart (spread out: at least 0.100 m)"));
}

TEST(ArrangementCheck, TogetherMeansOneGroupOfNeighbours) {
  const Goal together = arranged(ArrangementShape::kTogether, 3);
  // A chain: each within 10 cm of the next, the ends 24 cm apart.
  EXPECT_TRUE(checkArrangedBoxes(together, {block(0.4, 0.0), block(0.5, 0.0), block(0.6, 0.04)}, {}).holds);
  const GoalCheck apart = checkArrangedBoxes(together, {block(0.4, 0.0), block(0.46, 0.0), block(0.4, 0.3)}, {});
  EXPECT_FALSE(apart.holds);
  EXPECT_THAT(apart.explanation, HasSubstr("the widest gap that joins them into one group is 0.260 m (next to each other: at most 0.100 m)"));
  const json statement = {{"kind", "arranged"}, {"members", {"block0", "block1"}}, {"shape", "together"}};
  std::vector<std::string> problems;
  const std::vector<Goal> goals = readGoalStatement(json::array({statement}), "goals", {"block0", "block1"}, problems);
  EXPECT_TRUE(problems.empty()) << problems.front();
  ASSERT_EQ(goals.size(), 1u);
  EXPECT_EQ(goals.front().shape, ArrangementShape::kTogether);
  EXPECT_EQ(describeGoal(goals.front()), "block0, block1 next to each other");
}

/// A 4 cm block's box centred at (x, y) with its bottom at z.
AlignedBox3 blockAt(double x, double y, double z) { return {Vector3(x - 0.02, y - 0.02, z), Vector3(x + 0.02, y + 0.02, z + 0.04)}; }

TEST(ArrangementCheck, APyramidIsRowsEachMemberRestingOnTwoOfTheRowBelow) {
  const Goal pyramid = arranged(ArrangementShape::kPyramid, 3);
  // Two 4 cm blocks 1 cm apart, the third over the middle on both (in any order of the members).
  const GoalCheck three = checkArrangedBoxes(pyramid, {blockAt(0.5, 0.0, 0.04), blockAt(0.5, -0.025, 0.0), blockAt(0.5, 0.025, 0.0)}, {});
  EXPECT_TRUE(three.holds) << three.explanation;
  EXPECT_THAT(three.explanation, HasSubstr("a base of 2"));
  const GoalCheck offCentre = checkArrangedBoxes(pyramid, {blockAt(0.5, -0.025, 0.0), blockAt(0.5, 0.025, 0.0), blockAt(0.5, 0.02, 0.04)}, {});
  EXPECT_FALSE(offCentre.holds);  // on one block only
  EXPECT_THAT(offCentre.explanation, HasSubstr("does not rest on two members of the row below"));
  const GoalCheck floating = checkArrangedBoxes(pyramid, {blockAt(0.5, -0.025, 0.0), blockAt(0.5, 0.025, 0.0), blockAt(0.5, 0.0, 0.08)}, {});
  EXPECT_FALSE(floating.holds);
  const GoalCheck flat = checkArrangedBoxes(pyramid, {blockAt(0.5, -0.05, 0.0), blockAt(0.5, 0.0, 0.0), blockAt(0.5, 0.05, 0.0)}, {});
  EXPECT_FALSE(flat.holds);  // three in a row is no pyramid
  EXPECT_FALSE(checkArrangedBoxes(arranged(ArrangementShape::kPyramid, 4), {block(0.4, 0.0), block(0.5, 0.0), block(0.6, 0.0), block(0.7, 0.0)}, {}).holds);

  // Six: a base of three in a line, two on it, one on top.
  std::vector<AlignedBox3> six{blockAt(0.5, -0.05, 0.0), blockAt(0.5, 0.0, 0.0), blockAt(0.5, 0.05, 0.0),
                               blockAt(0.5, -0.025, 0.04), blockAt(0.5, 0.025, 0.04), blockAt(0.5, 0.0, 0.08)};
  EXPECT_TRUE(checkArrangedBoxes(arranged(ArrangementShape::kPyramid, 6), six, {}).holds);
  six[1] = blockAt(0.56, 0.0, 0.0);  // the base bent out of line
  const GoalCheck bent = checkArrangedBoxes(arranged(ArrangementShape::kPyramid, 6), six, {});
  EXPECT_FALSE(bent.holds);
  EXPECT_THAT(bent.explanation, HasSubstr("the base row"));

  std::vector<std::string> problems;
  readGoalStatement(json::array({{{"kind", "arranged"}, {"members", {"marker", "eraser"}}, {"shape", "pyramid"}}}), "goals",
                    {"marker", "eraser"}, problems);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_THAT(problems[0], HasSubstr("goals[0].members: a pyramid has 3, 6 or 10 members (rows of k, k - 1, ..., 1), not 2"));
}

TEST(ArrangementCheck, OnASceneMembersMustStandOnTheTargetAndNotBeHeld) {
  Scene scene = readKauthamProblem(resolveProblem("panda_desk")).scene;
  Goal line;
  line.kind = GoalKind::kArranged;
  line.shape = ArrangementShape::kLine;
  line.members = {"marker", "eraser"};
  line.target = "desk";
  const GoalCheck two = checkGoalInScene(scene, line);  // any two points are on a line
  EXPECT_TRUE(two.holds) << two.explanation;
  EXPECT_THAT(two.explanation, HasSubstr("marker, eraser in a line on desk: the centres lie within 0.000 m"));
  line.target = "holder";
  EXPECT_FALSE(checkGoalInScene(scene, line).holds);
  line.target.clear();
  line.members = {"marker", "cup"};
  EXPECT_THROW(checkGoalInScene(scene, line), InputError);
}

TEST(ArrangementCheck, TheGoalStatementReadsAndWritesArrangementsAndNamesEachMistake) {
  const std::vector<std::string> objects{"desk", "marker", "eraser", "holder"};
  std::vector<std::string> problems;
  const json goals = {{{"kind", "arranged"}, {"members", {"marker", "eraser"}}, {"shape", "line"}, {"target", "desk"},
                       {"heading", 1.5707963}, {"evenly_spaced", true}, {"distance", 0.1}}};
  const std::vector<Goal> read = readGoalStatement(goals, "goals", objects, problems);
  ASSERT_TRUE(problems.empty()) << problems.front();
  EXPECT_EQ(describeGoal(read.front()), "marker, eraser in a line along yaw 90 deg, evenly spaced, 0.1 m apart on desk");
  const json written = goalStatementJson(read)[0];
  EXPECT_EQ(written["members"], json({"marker", "eraser"}));
  EXPECT_EQ(written["shape"], "line");
  EXPECT_EQ(written["evenly_spaced"], true);
  EXPECT_EQ(readGoalStatement(goalStatementJson(read), "goals", objects, problems).front().members, read.front().members);

  const json wrong = {{{"kind", "arranged"}, {"members", {"marker", "cup"}}, {"shape", "line"}},
                      {{"kind", "arranged"}, {"members", {"marker", "eraser"}}, {"shape", "hexagon"}},
                      {{"kind", "arranged"}, {"members", {"marker", "eraser"}}, {"shape", "triangle"}},
                      {{"kind", "arranged"}, {"members", {"marker", "marker", "eraser"}}, {"shape", "circle"}},
                      {{"kind", "arranged"}, {"members", {"marker", "eraser", "holder"}}, {"shape", "circle"}, {"heading", 0.0}},
                      {{"kind", "arranged"}, {"members", "marker"}, {"shape", "line"}},
                      {{"kind", "arranged"}, {"object", "marker"}, {"members", {"marker", "eraser"}}, {"shape", "line"}}};
  problems.clear();
  readGoalStatement(wrong, "goals", objects, problems);
  ASSERT_EQ(problems.size(), 8u);
  EXPECT_THAT(problems[0], HasSubstr("goals[0].members[1]: unknown object \"cup\""));
  EXPECT_THAT(problems[1], HasSubstr("goals[1].shape: unknown shape string \"hexagon\" (shapes: line, circle, triangle, square, spread_out, together, pyramid)"));
  EXPECT_THAT(problems[2], HasSubstr("goals[2].members: a triangle takes 3, 6, 9, ... members (its corners, and as many more evenly along each side), not 2"));
  EXPECT_THAT(problems[3], HasSubstr("goals[3].members[1]: \"marker\" is named twice"));
  EXPECT_THAT(problems[4], HasSubstr("goals[4]: heading, evenly_spaced and distance are of a line only"));
  EXPECT_THAT(problems[5], HasSubstr("goals[5].members: expected an array of object names"));
  EXPECT_THAT(problems[6], HasSubstr("goals[5].members: a line needs at least 2 members"));
  EXPECT_THAT(problems[7], HasSubstr("goals[6].object: must be null for an arranged goal"));
}

}  // namespace
}  // namespace lang2manip
