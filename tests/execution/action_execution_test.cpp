// Each action type executed on the desk scenes of two robots: the world is updated as the action
// says (what is held, where objects end up, where the robot is), and the motion is continuous.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "execution_test_support.hpp"
#include "lang2manip/execution/execution_verification.hpp"
#include "lang2manip/grounding/object_geometry.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"

namespace lang2manip::test {
namespace {

class ActionsOnRobot : public ::testing::TestWithParam<std::string> {
 protected:
  const ExecutionRecord& run(TaskExecutor& executor, const Plan& plan) {
    const auto failure = executor.execute(plan, StopCondition::never());
    EXPECT_FALSE(failure.has_value()) << (failure ? failure->stage + ": " + failure->reason : "");
    return executor.lastExecution();
  }
};

TEST_P(ActionsOnRobot, PickThenPlaceInTheHolder) {
  TaskExecutor executor(deskScene(GetParam()), testSettings());
  const ExecutionRecord& record =
      run(executor, planOf({pickAction("marker"), placeAction("marker", SpatialRelation::kIn, "holder")}));
  ASSERT_TRUE(record.succeeded());
  ASSERT_EQ(record.actions.size(), 2u);
  const SymbolicState state = observeSymbolicState(record.finalScene);
  EXPECT_EQ(state.inside.at("marker"), "holder");
  EXPECT_TRUE(state.held.empty());
  expectContinuousMotion(executor, record);
  std::vector<std::string> labels;
  for (const MotionSegment& segment : record.actions[0].segments) labels.push_back(segment.label);
  EXPECT_THAT(labels, ::testing::Contains(::testing::HasSubstr("transit to pre-grasp of marker")));
  EXPECT_THAT(labels, ::testing::Contains("approach marker"));
  EXPECT_THAT(labels, ::testing::Contains("close gripper on marker"));
  EXPECT_THAT(labels, ::testing::Contains("lift marker"));
  EXPECT_FALSE(record.actions[0].choice.empty());
  EXPECT_EQ(record.counters.graspPlans, 1);
  EXPECT_GE(record.counters.plannerCalls, 2);
  EXPECT_GT(record.counters.ikCalls, 0);
}

TEST(ActionsOnPanda, APlaceTheGraspLeavesNoRoomForIsPickedAgainWithAGraspThatFits) {
  // A 6 x 3.5 cm bar goes lengthwise, as it stands now, between two low walls at its ends: held
  // across its length (the grasp the planner prefers) the fingers hit the walls; held across its
  // narrow side they fit. The pick is grounded again with the grasps that leave the place room.
  Scene scene = emptyDeskScene("panda");
  const Vector3 slot(0.15, 0.0, 0.75);
  scene.addObject(boxObject("bar", Vector3(0.06, 0.035, 0.04), Vector3(0.0, -0.2, 0.75)));
  scene.addObject(fixedBox("near_wall", Vector3(0.02, 0.12, 0.025), slot + Vector3(0.0465, 0.0, 0.0)));
  scene.addObject(fixedBox("far_wall", Vector3(0.02, 0.12, 0.025), slot + Vector3(-0.0465, 0.0, 0.0)));
  TaskExecutor executor(scene, testSettings());
  SymbolicAction place;
  place.type = ActionType::kPlace;
  place.object = "bar";
  const Pose base = robotBaseFrame(scene, "");
  place.params.position = base.inverse() * slot;
  place.params.orientation = Quaternion(base.linear().transpose());  // lengthwise along the world's x, as it stands
  const auto failure = executor.execute(planOf({pickAction("bar"), place}), StopCondition::never());
  ASSERT_FALSE(failure.has_value()) << failure->stage + ": " + failure->reason;
  const ExecutionRecord& record = executor.lastExecution();
  EXPECT_EQ(record.counters.graspPlans, 2);  // the first grasp's place failed
  EXPECT_NEAR((record.finalScene.object("bar").pose.translation() - slot).head<2>().norm(), 0.0, 0.005);
  expectContinuousMotion(executor, record);
}

TEST_P(ActionsOnRobot, ReleasedObjectsComeToRestOnWhatIsUnderThem) {
  // Released a few millimetres above the holder's floor and the desk (so that nothing scrapes),
  // each object is then where it rests, not floating where the hand let go.
  const Scene scene = deskScene(GetParam());
  TaskExecutor executor(scene, testSettings());
  const Plan plan = planOf({pickAction("marker"), placeAction("marker", SpatialRelation::kIn, "holder"), pickAction("eraser"),
                            placeAction("eraser", SpatialRelation::kLeftOf, "holder")});
  const ExecutionRecord& record = run(executor, plan);
  ASSERT_TRUE(record.succeeded());
  const SceneObject& holder = scene.object("holder");
  const double floor = transformedBox(*holder.cavity, holder.pose).min().z();
  EXPECT_NEAR(record.finalScene.object("marker").worldBounds().min().z(), floor, 1e-9);
  EXPECT_NEAR(record.finalScene.object("eraser").worldBounds().min().z(), scene.object("desk").worldBounds().max().z(), 1e-9);
  EXPECT_TRUE(verifyExecution(executor.arm(), scene, record, goalsImpliedByPlan(plan)).success);
}

TEST_P(ActionsOnRobot, CartesianStepsWhoseJointsMoveFastAreHalvedNotRefused) {
  // 8 cm Cartesian steps with at most 0.12 rad per joint and step: whole steps would jump, the
  // halved ones (down to 1 cm) do not, and every waypoint keeps within the limit.
  ExecutionSettings settings = testSettings();
  settings.cartesianStep = 0.08;
  settings.maxJointStep = 0.12;
  TaskExecutor executor(deskScene(GetParam()), settings);
  const ExecutionRecord& record = run(executor, planOf({pickAction("marker")}));
  ASSERT_TRUE(record.succeeded());
  bool halved = false;
  for (const MotionSegment& segment : record.actions[0].segments) {
    if (segment.label != "approach marker" && segment.label != "lift marker") continue;
    halved = halved || segment.waypoints.size() > 3;  // a 10 cm move is 2 whole steps
    for (std::size_t i = 1; i < segment.waypoints.size(); ++i) {
      const VectorX step = segment.waypoints[i] - segment.waypoints[i - 1];
      EXPECT_LE(step.cwiseAbs().maxCoeff(), settings.maxJointStep + 1e-9) << segment.label << " waypoint " << i;
    }
  }
  EXPECT_TRUE(halved);
}

TEST_P(ActionsOnRobot, PickHoldsTheObjectAndMoveCarriesItHome) {
  TaskExecutor executor(deskScene(GetParam()), testSettings());
  const ExecutionRecord& record = run(executor, planOf({pickAction("eraser"), moveHomeAction()}));
  ASSERT_TRUE(record.succeeded());
  const SymbolicState state = observeSymbolicState(record.finalScene);
  EXPECT_EQ(state.held, "eraser");
  EXPECT_EQ(state.atConfiguration, "home");
  const Pose tool = executor.arm().toolPose(record.finalScene, record.finalScene.robot(executor.arm().robotName()).configuration);
  const Attachment* held = record.finalScene.findAttachment("eraser");
  ASSERT_NE(held, nullptr);
  const Vector3 eraser = currentObjectPose(record.finalScene, "eraser").translation();
  EXPECT_LT((eraser - (tool * held->linkToObject).translation()).norm(), 1e-9);
  EXPECT_GT(eraser.z(), 0.80);
  expectContinuousMotion(executor, record);
}

TEST_P(ActionsOnRobot, PlaceOnTheDeskBesideAnotherObject) {
  TaskExecutor executor(deskScene(GetParam()), testSettings());
  const ExecutionRecord& record =
      run(executor, planOf({pickAction("eraser"), placeAction("eraser", SpatialRelation::kRightOf, "holder")}));
  ASSERT_TRUE(record.succeeded());
  Goal goal;
  goal.object = "eraser";
  goal.relation = SpatialRelation::kRightOf;
  goal.target = "holder";
  EXPECT_TRUE(checkGoalInScene(record.finalScene, goal).holds) << checkGoalInScene(record.finalScene, goal).explanation;
  EXPECT_EQ(observeSymbolicState(record.finalScene).onTopOf.at("eraser"), "desk");
}

TEST_P(ActionsOnRobot, MoveToAToolPoseThenHome) {
  const Scene scene = deskScene(GetParam());
  TaskExecutor executor(scene, testSettings());
  const Pose X_WB = robotBaseFrame(scene, executor.arm().robotName());
  const Vector3 target(0.40, -0.10, 0.25);
  const ExecutionRecord& record = run(executor, planOf({moveToAction(target), moveHomeAction()}));
  ASSERT_TRUE(record.succeeded());
  const VectorX& reached = record.actions[0].segments.back().waypoints.back();
  const Vector3 tool = X_WB.inverse() * executor.arm().toolPose(scene, reached).translation();
  EXPECT_LT((tool - target).norm(), 1e-3);
  EXPECT_EQ(observeSymbolicState(record.finalScene).atConfiguration, "home");
  expectContinuousMotion(executor, record);
}

TEST_P(ActionsOnRobot, PushSlidesTheObjectByTheDistance) {
  const Scene scene = deskScene(GetParam());
  TaskExecutor executor(scene, testSettings());
  const ExecutionRecord& record = run(executor, planOf({pushAction("eraser", Vector3(1, 0, 0), 0.05)}));
  ASSERT_TRUE(record.succeeded());
  const Vector3 moved = record.finalScene.object("eraser").pose.translation() - scene.object("eraser").pose.translation();
  const Vector3 expected = robotBaseFrame(scene, executor.arm().robotName()).linear() * Vector3(0.05, 0, 0);
  EXPECT_LT((moved - expected).norm(), 1e-9);
  std::vector<std::string> labels;
  for (const MotionSegment& segment : record.actions[0].segments) labels.push_back(segment.label);
  EXPECT_THAT(labels, ::testing::Contains("push eraser 0.050 m"));
  Goal goal;
  goal.kind = GoalKind::kDisplaced;
  goal.object = "eraser";
  goal.displacement = Vector3(0.05, 0, 0);
  GoalCheckOptions options;
  options.initialScene = &scene;
  EXPECT_TRUE(checkGoalInScene(record.finalScene, goal, options).holds);
  const ExecutionVerification verification = verifyExecution(executor.arm(), scene, record, {goal});
  EXPECT_TRUE(verification.success) << verification.collision;
}

TEST_P(ActionsOnRobot, AnObjectWiderThanTheHandIsPushedByWhatMeetsIt) {
  // Taller than the fingers are long and wider than the hand opens: the palm meets it first.
  Scene scene = deskScene(GetParam());
  const Vector3 at = scene.object("eraser").pose.translation();
  scene.removeObject("eraser");
  scene.addObject(boxObject("crate", Vector3(0.14, 0.14, 0.06), at));
  const Pose X_WB = robotBaseFrame(scene, scene.robots().front().name);
  for (const Vector3& direction : {Vector3(0, -1, 0), Vector3(1, 0, 0), Vector3(-1, 0, 0)}) {
    SCOPED_TRACE(direction.transpose());
    TaskExecutor executor(scene, testSettings());
    const ExecutionRecord& record = run(executor, planOf({pushAction("crate", direction, 0.06)}));
    ASSERT_TRUE(record.succeeded()) << (record.failure ? record.failure->reason : "");
    const Vector3 moved = record.finalScene.object("crate").pose.translation() - at;
    EXPECT_LT((moved - X_WB.linear() * direction * 0.06).norm(), 1e-9);
    Goal goal;
    goal.kind = GoalKind::kDisplaced;
    goal.object = "crate";
    goal.displacement = direction * 0.06;
    const ExecutionVerification verification = verifyExecution(executor.arm(), scene, record, {goal});
    EXPECT_TRUE(verification.success) << verification.collision;
  }
  // Carrying it is impossible, and the failure says so as data.
  TaskExecutor executor(scene, testSettings());
  const auto failure = executor.execute(planOf({pickAction("crate")}), StopCondition::never());
  ASSERT_TRUE(failure.has_value());
  EXPECT_TRUE(failure->objectUngraspable) << failure->reason;
}

TEST_P(ActionsOnRobot, EachActionIsPlannedWithItsOwnPlanner) {
  TaskExecutor executor(deskScene(GetParam()), testSettings());
  SymbolicAction pick = pickAction("marker");
  pick.planner = "omplPRM";
  SymbolicAction place = placeAction("marker", SpatialRelation::kIn, "holder");
  place.planner = "BiTRRT";
  SymbolicAction home = moveHomeAction();
  const ExecutionRecord& record = run(executor, planOf({pick, place, home}));
  ASSERT_TRUE(record.succeeded());
  const std::vector<std::string> expected = {"PRM", "BiTRRT", "RRTConnect"};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    int transits = 0;
    for (const MotionSegment& segment : record.actions[i].segments) {
      if (segment.planner.empty()) continue;
      ++transits;
      EXPECT_EQ(segment.planner, expected[i]) << segment.label;
    }
    EXPECT_GE(transits, 1) << "step " << i + 1;
  }
}

INSTANTIATE_TEST_SUITE_P(DeskRobots, ActionsOnRobot, ::testing::Values("panda", "ur5"));

}  // namespace
}  // namespace lang2manip::test
