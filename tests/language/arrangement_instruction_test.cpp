// Arrangements in instructions (issue 23, class 2) on the workbench scene: lines, circles,
// triangles, squares and spread-out objects, where they go, and that the places the offline
// planner chooses satisfy the arranged goal the check measures.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lang2manip/language/arrangement_layout.hpp"
#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"
#include "lang2manip/symbolic/task_planner.hpp"
#include "language/language_test_scenes.hpp"
#include "language/language_test_support.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;

TaskSpecification arrangementOf(const std::string& instruction, const Scene& scene = test::workbenchScene()) {
  return understandInstruction(instruction, describeObjects(scene));
}

std::string arrangementRefusal(const std::string& instruction) {
  try {
    return "understood: " + test::summarize(arrangementOf(instruction));
  } catch (const PlanningError& error) {
    return error.what();
  }
}

/// The workbench with the yellow cup in the middle of the table, room around it.
Scene cupInTheMiddle() {
  Scene scene = test::workbenchScene();
  scene.object("yellow_cup").pose.translation().head<2>() = Eigen::Vector2d(0.0, 0.0);
  return scene;
}

/// The scene with every object of an at_position step moved there, and the check of each
/// arranged goal on it.
void expectPlacesMakeTheArrangement(const std::string& instruction, Scene scene = test::workbenchScene()) {
  const TaskSpecification specification = arrangementOf(instruction, scene);
  for (const Goal& step : specification.steps) {
    ASSERT_EQ(step.kind, GoalKind::kAtPosition) << instruction;
    scene.object(step.object).pose.translation().head<2>() = step.position->head<2>();
  }
  ASSERT_FALSE(specification.goals.empty());
  for (const Goal& goal : specification.goals) {
    ASSERT_EQ(goal.kind, GoalKind::kArranged) << instruction;
    const GoalCheck check = checkGoalInScene(scene, goal);
    EXPECT_TRUE(check.holds) << instruction << ": " << check.explanation;
  }
}

TEST(ArrangementInstruction, ShapesAreReadInManyWordings) {
  EXPECT_EQ(test::summarize(arrangementOf("arrange the blocks in a circle")), "red_block, blue_block, green_block in a circle on table");
  EXPECT_EQ(test::summarize(arrangementOf("put the blocks and the markers in a ring")),
            "red_block, blue_block, green_block, marker_1, marker_2 in a circle on table");
  EXPECT_EQ(test::summarize(arrangementOf("make a triangle with the blocks")), "red_block, blue_block, green_block in a triangle on table");
  EXPECT_EQ(test::summarize(arrangementOf("form a triangular formation out of the three blocks")),
            "red_block, blue_block, green_block in a triangle on table");
  EXPECT_EQ(test::summarize(arrangementOf("put the blocks and the red marker in the shape of a square")),
            "red_block, blue_block, green_block, marker_1 in a square on table");
  EXPECT_EQ(test::summarize(arrangementOf("spread out the blocks")), "red_block, blue_block, green_block spread out on table");
  EXPECT_EQ(test::summarize(arrangementOf("spread the blocks out across the table")), "red_block, blue_block, green_block spread out on table");
  EXPECT_EQ(test::summarize(arrangementOf("put the blocks in an evenly spaced row")),
            "red_block, blue_block, green_block in a line along yaw 90 deg, evenly spaced on table");
  EXPECT_EQ(test::summarize(arrangementOf("line the blocks up in a vertical line 12 cm apart")),
            "red_block, blue_block, green_block in a line along yaw 0 deg, evenly spaced, 0.12 m apart on table");
}

TEST(ArrangementInstruction, ThePlacesChosenMakeTheArrangementTheCheckMeasures) {
  for (const char* instruction :
       {"put the blocks in a horizontal line", "put the blocks in a vertical line 12 cm apart", "put the blocks in a diagonal line", "line up the blocks along the far edge",
        "arrange the blocks in a circle", "put the blocks and the markers in a circle", "make a triangle with the blocks",
        "put the blocks and the red marker in a square", "make a triangle with the blocks, the markers and the yellow cup",
        "put the blocks in a triangle in the far left corner of the table", "put the blocks and the cups in a line along the near edge",
        "spread out the blocks and the markers"}) {
    expectPlacesMakeTheArrangement(instruction);
  }
  expectPlacesMakeTheArrangement("arrange the blocks in a circle around the yellow cup", cupInTheMiddle());
}

TEST(ArrangementInstruction, ACircleAroundAnObjectIsCentredOnItAndClearsIt) {
  const TaskSpecification specification = arrangementOf("arrange the blocks in a circle around the yellow cup", cupInTheMiddle());
  const Vector3 cup(0.0, 0.0, 0.0);
  for (const Goal& step : specification.steps) {
    const double radius = (step.position->head<2>() - cup.head<2>()).norm();
    EXPECT_GT(radius, 0.042 + 0.03) << step.object;  // half the cup's diagonal and half a block
    EXPECT_LT(radius, 0.15) << step.object;
  }
}

TEST(ArrangementInstruction, SpreadingOutMovesOnlyTheObjectsThatAreTooClose) {
  // The blocks stand 20 cm apart already: spread out, nothing has to move.
  const TaskSpecification specification = arrangementOf("spread out the red and the green block");
  for (const Goal& step : specification.steps) {
    const Vector3 now = describeObjects(test::workbenchScene()).at(step.object == "red_block" ? 1 : 3).origin;
    EXPECT_NEAR((step.position->head<2>() - now.head<2>()).norm(), 0.0, 1e-9) << step.object;
  }
}

TEST(ArrangementInstruction, ObjectsNextToEachOtherFormOneGroup) {
  for (const char* instruction :
       {"put the blocks next to each other", "place the red and green blocks side by side", "put the blocks and the markers together",
        "gather the blocks", "group the blocks together on the table", "bring the red block and the red marker together",
        "cluster the blocks in the far right corner", "put the blocks close to each other in the middle of the table"}) {
    SCOPED_TRACE(instruction);
    const TaskSpecification specification = arrangementOf(instruction);
    ASSERT_EQ(specification.goals.size(), 1u);
    EXPECT_EQ(specification.goals.front().shape, ArrangementShape::kTogether);
    expectPlacesMakeTheArrangement(instruction);
  }
  EXPECT_EQ(test::summarize(arrangementOf("put the blocks next to each other")), "red_block, blue_block, green_block next to each other on table");
  // "Together" into a container puts them there; "line up side by side" is a line.
  EXPECT_EQ(test::summarize(arrangementOf("put the red and green blocks together in the yellow cup")), "red_block in yellow_cup; green_block in yellow_cup");
  EXPECT_EQ(test::summarize(arrangementOf("line up the blocks side by side")), "red_block, blue_block, green_block in a line on table");
  EXPECT_THAT(arrangementRefusal("put the blocks next to each other around the yellow cup"),
              HasSubstr("only a circle, triangle or square goes around something"));
}

TEST(ArrangementInstruction, ALineBetweenTwoObjectsIsEvenlySpacedAlongThem) {
  const char* instruction = "put the red and green blocks in a line between the white cup and the box";
  const TaskSpecification specification = arrangementOf(instruction);
  ASSERT_EQ(specification.goals.size(), 1u);
  const Goal& line = specification.goals.front();
  ASSERT_TRUE(line.heading.has_value());
  EXPECT_TRUE(line.evenlySpaced);
  expectPlacesMakeTheArrangement(instruction);
  // The places are a third and two thirds of the way from one end's centre to the other's.
  const std::vector<ObjectDescriptor> objects = describeObjects(test::workbenchScene());
  const auto centreOf = [&](const std::string& name) {
    for (const ObjectDescriptor& o : objects) {
      if (o.name == name) return Eigen::Vector2d(o.position.head<2>());
    }
    return Eigen::Vector2d(0.0, 0.0);
  };
  const Eigen::Vector2d a = centreOf("white_cup"), b = centreOf("box");
  std::vector<double> shares;
  for (const Goal& step : specification.steps) {
    const Eigen::Vector2d at = step.position->head<2>();  // a block's frame is under its centre
    shares.push_back((at - a).dot(b - a) / (b - a).squaredNorm());
  }
  ASSERT_EQ(shares.size(), 2u);
  std::sort(shares.begin(), shares.end());
  EXPECT_NEAR(shares[0], 1.0 / 3.0, 0.05);
  EXPECT_NEAR(shares[1], 2.0 / 3.0, 0.05);
  EXPECT_THAT(arrangementRefusal("put the blocks in a circle between the white cup and the box"), HasSubstr("only a line goes between two objects"));
  // "The blocks" between the red block and the box are the others; naming it among them is refused.
  EXPECT_EQ(test::summarize(arrangementOf("put the blocks in a line between the red block and the box")).rfind("blue_block, green_block in a line", 0), 0u);
  EXPECT_THAT(arrangementRefusal("put the red and green blocks in a line between the red block and the box"),
              HasSubstr("cannot relate red_block to itself"));
  EXPECT_THAT(arrangementRefusal("put the blocks in a line 10 cm apart between the white cup and the box"),
              HasSubstr("a line between two objects takes their direction and spacing"));
}

TEST(ArrangementInstruction, ArrangementsThatCannotBeAreRefusedSayingWhy) {
  EXPECT_THAT(arrangementRefusal("make a triangle with the blocks and the markers"), HasSubstr("a triangle takes 3, 6, 9, ... members (its corners, and as many more evenly along each side), not 5; say which of them, or a circle or line"));
  EXPECT_THAT(arrangementRefusal("put the blocks in a square"), HasSubstr("a square takes 4, 8, 12, ... members (its corners, and as many more evenly along each side), not 3"));
  EXPECT_THAT(arrangementRefusal("put the red block in a circle"), HasSubstr("an arrangement needs at least two objects"));
  EXPECT_THAT(arrangementRefusal("put the blocks in a line 3 cm apart"), HasSubstr("0.030 m apart would overlap: the widest is wider than that"));
  EXPECT_THAT(arrangementRefusal("put the blocks in a line around the yellow cup"), HasSubstr("only a circle, triangle or square goes around something"));
  // Around the box by the table's edge, a circle clear of it does not fit.
  EXPECT_THAT(arrangementRefusal("arrange the blocks in a circle around the box"), HasSubstr("around it, and the reachable top has none"));
  EXPECT_THAT(arrangementRefusal("put the blocks in a circle in a corner"), HasSubstr("say which corner the arrangement goes in"));
  // Twenty objects' worth of spacing does not fit on a 1.2 m table.
  EXPECT_THAT(arrangementRefusal("put the blocks, the cups, the box and the markers in a line 30 cm apart"), HasSubstr("objects in a line need"));
}

TEST(ArrangementInstruction, APyramidPutsEachHigherBlockOnTwoOfTheRowBelow) {
  for (const char* instruction : {"build a pyramid with the three blocks", "arrange the blocks in a pyramid", "stack the blocks into a pyramid",
                                  "put the blocks in a pyramid in the far right corner of the table"}) {
    Scene scene = test::workbenchScene();
    const TaskSpecification specification = arrangementOf(instruction, scene);
    EXPECT_THAT(test::summarize(specification), HasSubstr("red_block, blue_block, green_block in a pyramid on table")) << instruction;
    ASSERT_EQ(specification.steps.size(), 3u) << instruction;
    // The base row first, then the block that rests on both, raised by a block's height.
    EXPECT_NEAR(specification.steps[0].position->z(), specification.steps[1].position->z(), 1e-9) << instruction;
    EXPECT_GT(specification.steps[2].position->z(), specification.steps[0].position->z() + 0.03) << instruction;
    for (const Goal& step : specification.steps) scene.object(step.object).pose.translation() = *step.position;
    for (const Goal& goal : specification.goals) {
      const GoalCheck check = checkGoalInScene(scene, goal);
      EXPECT_TRUE(check.holds) << instruction << ": " << check.explanation;
    }
  }
  EXPECT_THAT(arrangementRefusal("make a pyramid with the blocks and the red marker"), HasSubstr("a pyramid has 3, 6 or 10 members (rows of k, k - 1, ..., 1), not 4"));
  EXPECT_THAT(arrangementRefusal("put the blocks in a pyramid around the yellow cup"), HasSubstr("only a circle, triangle or square goes around"));
}

TEST(ArrangementInstruction, ALayoutGoesOverMovableObjectsOnlyWhenNothingElseIsFree) {
  // A 30 cm strip with a bowl across its middle: three 4 cm blocks in a line need 20 cm.
  language_detail::ArrangementLayoutRequest request;
  request.area = AlignedBox3(Vector3(0.3, -0.15, 0.0), Vector3(0.6, 0.15, 0.0));
  request.direction = Vector3::UnitX();
  for (const double y : {-0.1, 0.0, 0.1}) {
    request.members.emplace_back(Vector3(0.05, y - 0.02, 0.0), Vector3(0.09, y + 0.02, 0.04));  // off the strip
    request.onSupport.push_back(false);
  }
  request.others = {AlignedBox3(Vector3(0.3, -0.15, 0.0), Vector3(0.6, 0.15, 0.08))};
  request.othersMovable = {true};
  std::string why;
  const auto over = language_detail::layOutArrangement(request, why);
  ASSERT_TRUE(over) << why;  // the bowl is set aside first
  request.othersMovable = {false};
  EXPECT_FALSE(language_detail::layOutArrangement(request, why));
  EXPECT_THAT(why, HasSubstr("3 objects in a line need"));
}

}  // namespace
}  // namespace lang2manip
