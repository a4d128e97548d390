// Ways people say what they want (issue 15): more verbs ("lower", "load", "fill X with Y", "bring
// me X", "give X a quarter turn"), approximate amounts, subject-first and causative sentences,
// exceptions, participles and superlatives by side, places named by a possessive or "the spot
// where", putting something back, displacements toward or away from an object, "between", and
// the refusals that go with them. On the built-in Panda desk.

#include <gtest/gtest.h>

#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/language/sequencer.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"
#include "lang2manip/symbolic/task_planner.hpp"
#include "language/language_test_scenes.hpp"
#include "language/language_test_support.hpp"
#include "language/plan_check.hpp"

namespace lang2manip {
namespace {

// On the Panda desk (base frame): marker at (0.42, -0.18), eraser at (0.38, 0.17), holder at
// (0.52, 0.02).
const std::pair<const char*, const char*> kPhrasings[] = {
    {"lower the marker into the holder", "marker in holder"},
    {"load the marker and the eraser into the holder", "marker in holder; eraser in holder"},
    {"collect the pen and the rubber in the cup", "marker in holder; eraser in holder"},
    {"fill the holder with the marker and the eraser", "marker in holder; eraser in holder"},
    {"put away the eraser in the holder", "eraser in holder"},
    {"bring me the marker", "marker handed over"},
    {"bring the eraser over to me", "eraser handed over"},
    {"I need the marker, hand it over", "marker handed over"},
    {"give the eraser a quarter turn", "eraser turned by 90 deg"},
    {"give the marker a 30 degree turn to the right", "marker turned by -30 deg"},
    {"turn the pen a little, about 15 degrees", "marker turned by 15 deg"},
    {"rotate the eraser roughly 45 degrees clockwise", "eraser turned by -45 deg"},
    {"push the eraser about 5 cm to the left", "eraser displaced by (0, 0.05, 0)"},
    {"slide the marker a bit to the left, about 4 cm", "marker displaced by (0, 0.04, 0)"},
    {"the marker and the eraser go into the holder", "marker in holder; eraser in holder"},
    {"I want the marker inside the holder", "marker in holder"},
    {"I'd like the eraser to be next to the holder", "eraser next to holder"},
    {"the eraser should be in the holder", "eraser in holder"},
    {"make the marker point at the holder", "marker pointing at holder"},
    {"put everything except the eraser in the holder", "marker in holder"},
    {"put the object that is not the eraser in the holder", "marker in holder"},
    {"put everything movable into the holder", "marker in holder; eraser in holder"},
    {"put the objects lying on the table in the holder", "marker in holder; eraser in holder"},
    {"hand me the object that is furthest to the left", "eraser handed over"},
    {"put the long one in the holder", "marker in holder"},
    {"put the short one in the holder", "eraser in holder"},
    {"please grab the marker, lift it, and put it in the holder", "marker in holder"},
    {"pick up the eraser, carry it over and put it next to the holder", "eraser next to holder"},
    {"put every object on the desk in the holder", "marker in holder; eraser in holder"},
    {"put the marker in the holder on the desk", "marker in holder"},
    {"lift the marker and move it 10 cm to the left", "marker displaced by (0, 0.1, 0)"},
    {"put the cylindrical object in the holder", "marker in holder"},
    {"put the box-shaped thing in the holder", "eraser in holder"},
    {"put the pen-like object in the holder", "marker in holder"},
    {"put the marker in the holder and then the other one", "marker in holder; eraser in holder"},
    {"put the eraser in the holder, then the remaining object", "eraser in holder; marker in holder"},
    {"point the marker to the left", "marker pointing along yaw 90 deg"},
    {"rotate the eraser so that it points forward", "eraser pointing along yaw 0 deg"},
    {"align the marker with the eraser", "marker pointing along yaw 0 deg"},
    {"tidy up: put everything into the holder", "marker in holder; eraser in holder"},
    {"clear the desk by putting everything into the holder", "marker in holder; eraser in holder"},
    {"put the eraser in the holder instead of on top of it", "eraser in holder"},
    {"put the marker on the desk and the eraser on the desk next to it", "marker on desk; eraser next to marker"},
    {"push the eraser 5 cm left and then 3 cm forward", "eraser displaced by (0.03, 0.05, 0)"},
    {"pick up the marker and put it where the eraser is", "marker at (0.38, 0.17) where eraser stood"},
    {"swap the marker and the eraser, then rotate the eraser by 90 degrees",
     "marker at (0.38, 0.17) where eraser stood; eraser at (0.42, -0.18) where marker stood; eraser turned by 90 deg"},
};

TEST(InstructionPhrasing, MoreWaysOfSayingTheSameAreUnderstoodAndPlanned) {
  test::expectUnderstoodAndPlanned(test::deskScene(), kPhrasings);
}

Goal onlyGoal(const std::string& instruction) {
  const TaskSpecification specification = understandInstruction(instruction, describeObjects(test::deskScene()));
  EXPECT_EQ(specification.goals.size(), 1u) << test::summarize(specification);
  return specification.goals.empty() ? Goal{} : specification.goals.front();
}

TEST(InstructionPhrasing, PlacesNamedByAnotherObjectTheSpotWhereItStandsOrBetweenTwo) {
  const Scene scene = test::deskScene();
  const Pose toBase = robotBaseFrame(scene, "").inverse();
  const auto centre = [&](const std::string& name) { return Vector3(toBase * scene.object(name).worldBounds().center()); };
  for (const char* instruction : {"move the marker to the eraser's position", "put the marker in the eraser's place",
                                  "move the marker to the spot where the eraser is", "put the marker at the eraser's location"}) {
    SCOPED_TRACE(instruction);
    const Goal goal = onlyGoal(instruction);
    EXPECT_EQ(goal.kind, GoalKind::kAtPosition);
    EXPECT_EQ(goal.target, "eraser");
  }
  const Goal between = onlyGoal("put the eraser between the marker and the holder");
  ASSERT_EQ(between.kind, GoalKind::kAtPosition);
  const Vector3 origin = toBase * scene.object("eraser").pose.translation();
  const Vector3 wanted = origin + (centre("marker") + centre("holder")) / 2.0 - centre("eraser");
  EXPECT_LT((*between.position - wanted).head<2>().norm(), 1e-9);
  // Put back: where it stood before the instruction.
  const Goal back = onlyGoal("lift the marker and put it back down where it was");
  ASSERT_EQ(back.kind, GoalKind::kAtPosition);
  EXPECT_LT((*back.position - toBase * scene.object("marker").pose.translation()).norm(), 1e-9);
}

TEST(InstructionPhrasing, DisplacementsTowardOrAwayFromAnObjectFollowTheLineBetweenThem) {
  const Scene scene = test::deskScene();
  const Pose toBase = robotBaseFrame(scene, "").inverse();
  Vector3 line = toBase.linear() * (scene.object("holder").worldBounds().center() - scene.object("eraser").worldBounds().center());
  line.z() = 0.0;
  const Goal toward = onlyGoal("slide the eraser 3 cm toward the holder");
  EXPECT_TRUE(toward.displacement.isApprox(line.normalized() * 0.03, 1e-9));
  const Goal away = onlyGoal("push the eraser 2 cm away from the holder");
  EXPECT_TRUE(away.displacement.isApprox(-line.normalized() * 0.02, 1e-9));
  const Goal closer = onlyGoal("move the eraser 3 cm closer to the holder");
  EXPECT_TRUE(closer.displacement.isApprox(line.normalized() * 0.03, 1e-9));
  const Goal robot = onlyGoal("push the eraser 3 cm towards the robot");
  EXPECT_TRUE(robot.displacement.isApprox(Vector3(-0.03, 0.0, 0.0), 1e-9));
}

TEST(InstructionPhrasing, ContradictionsAndImpossibleMovesAreRefusedWithTheReason) {
  const Scene scene = test::deskScene();
  const std::pair<const char*, const char*> cases[] = {
      {"put the marker in the holder next to the eraser", "marker in holder and marker next to eraser cannot both hold"},
      {"put the marker in the holder on the eraser", "cannot both hold"},
      {"push the eraser 5 meters to the left", "it would take eraser off desk"},
      {"put the marker between the eraser", "\"between\" needs two objects"},
      {"put the marker and the eraser between the holder and the desk", "only one object fits between"},
      {"fill the holder", "say what to fill holder with"},
      {"put the marker in the holder but not the eraser", "could not ground \"but\""},
      {"tidy up the desk", "it asks for nothing the robot could do"},
      {"put 444444444444444444444 markers in the holder", "could not ground"},
  };
  for (const auto& [instruction, reason] : cases) {
    SCOPED_TRACE(instruction);
    try {
      const TaskSpecification specification = understandInstruction(instruction, describeObjects(scene));
      (void)sequenceGoals(specification, observeSymbolicState(scene), sequencingOptionsFor(scene));
      ADD_FAILURE() << "planned: " << test::summarize(specification);
    } catch (const PlanningError& error) {
      EXPECT_NE(std::string(error.what()).find(reason), std::string::npos) << error.what();
    }
  }
}

TEST(InstructionPhrasing, AHeldObjectMovedByADistanceIsCarriedThereNotDroppedAndPushed) {
  const Scene scene = test::deskScene();
  const TaskSpecification specification = understandInstruction("pick up the eraser and put it down 10 cm to the left", describeObjects(scene));
  const Plan plan = sequenceGoals(specification, observeSymbolicState(scene), sequencingOptionsFor(scene));
  ASSERT_EQ(plan.actions.size(), 2u);
  EXPECT_EQ(plan.actions[1].type, ActionType::kPlace);
  ASSERT_TRUE(plan.actions[1].params.position.has_value());
  const Vector3 start = robotBaseFrame(scene, "").inverse() * scene.object("eraser").pose.translation();
  EXPECT_TRUE(plan.actions[1].params.position->isApprox(start + Vector3(0.0, 0.1, 0.0), 1e-9));
}

}  // namespace
}  // namespace lang2manip
