// Actions that cannot be executed fail with a reason naming the object and the stage; the
// actions before them keep their results, the ones after are not run, and nothing throws.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <memory>

#include "execution_test_support.hpp"
#include "lang2manip/core/error.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;

struct Failed {
  GroundingFailure failure;
  ExecutionRecord record;
};

Failed executeExpectingFailure(const Scene& scene, const Plan& plan) {
  TaskExecutor executor(scene, testSettings());
  const auto failure = executor.execute(plan, StopCondition::never());
  EXPECT_TRUE(failure.has_value());
  return {failure.value_or(GroundingFailure{}), executor.lastExecution()};
}

TEST(ExecutionFailures, UnreachableObjectFailsAtTheGraspStage) {
  for (const std::string robot : {"panda", "ur5"}) {
    Scene scene = deskScene(robot);
    scene.addObject(fixedBox("pedestal", Vector3(0.2, 0.2, 0.75), Vector3(1.2, 0.0, 0.0)));
    scene.addObject(boxObject("far_block", Vector3(0.03, 0.03, 0.05), Vector3(1.2, 0.0, 0.75)));
    const Failed f = executeExpectingFailure(scene, planOf({pickAction("far_block")}));
    EXPECT_EQ(f.failure.stage, "grasp") << robot;
    EXPECT_EQ(f.failure.object, "far_block");
    EXPECT_THAT(f.failure.reason, HasSubstr("far_block")) << robot;
    EXPECT_THAT(f.failure.reason, HasSubstr("reach")) << robot;
    EXPECT_EQ(f.record.actions[0].status, ActionStatus::kFailed);
  }
}

TEST(ExecutionFailures, FullHolderFailsAtThePlacementStageAfterThePick) {
  Scene scene = deskScene("panda");
  scene.addObject(boxObject("block", Vector3(0.055, 0.055, 0.09), Vector3(0.12, 0.02, 0.755)));
  const Failed f = executeExpectingFailure(
      scene, planOf({pickAction("eraser"), placeAction("eraser", SpatialRelation::kIn, "holder"), moveHomeAction()}));
  EXPECT_EQ(f.failure.actionIndex, 1u);
  EXPECT_EQ(f.failure.stage, "placement");
  EXPECT_THAT(f.failure.reason, HasSubstr("eraser in holder"));
  EXPECT_THAT(f.failure.reason, HasSubstr("block"));
  ASSERT_EQ(f.record.actions.size(), 3u);
  EXPECT_EQ(f.record.actions[0].status, ActionStatus::kSucceeded);
  EXPECT_FALSE(f.record.actions[0].trajectory.points.empty());
  EXPECT_EQ(f.record.actions[2].status, ActionStatus::kNotRun);
  EXPECT_NE(f.record.finalScene.findAttachment("eraser"), nullptr) << "the world after the last action that succeeded";
}

TEST(ExecutionFailures, AnObjectTooLargeForTheContainerIsRefusedWithTheReason) {
  Scene scene = deskScene("panda");
  scene.addObject(boxObject("cube", Vector3(0.07, 0.07, 0.07), Vector3(0.1, -0.3, 0.75)));
  const Failed f = executeExpectingFailure(scene, planOf({pickAction("cube"), placeAction("cube", SpatialRelation::kIn, "holder")}));
  EXPECT_EQ(f.failure.actionIndex, 1u);
  EXPECT_EQ(f.failure.stage, "placement");
  EXPECT_THAT(f.failure.reason, HasSubstr("cube"));
  EXPECT_THAT(f.failure.reason, HasSubstr("too large for the cavity of holder"));
}

TEST(ExecutionFailures, BlockedPlacementNamesTheBlocker) {
  Scene scene = deskScene("panda");
  scene.addObject(fixedBox("stand", Vector3(0.08, 0.08, 0.08), Vector3(0.10, -0.25, 0.75)));
  SymbolicAction place;
  place.type = ActionType::kPlace;
  place.object = "eraser";
  place.params.position = scene.robot("panda").basePose.inverse() * Vector3(0.10, -0.25, 0.75);
  const Failed f = executeExpectingFailure(scene, planOf({pickAction("eraser"), place}));
  EXPECT_EQ(f.failure.stage, "placement");
  EXPECT_THAT(f.failure.reason, HasSubstr("blocked by stand"));
  EXPECT_EQ(f.failure.blockingObjects, std::vector<std::string>{"stand"});  // as data for the task planners
}

TEST(ExecutionFailures, PushIntoAnObstacleFailsAtThePushStage) {
  Scene scene = deskScene("panda");
  // The eraser's front face is at x = 0.005; the wall stands 2 cm beyond it.
  scene.addObject(fixedBox("wall", Vector3(0.02, 0.20, 0.06), Vector3(0.035, 0.17, 0.75)));
  const Failed f = executeExpectingFailure(scene, planOf({pushAction("eraser", Vector3(1, 0, 0), 0.08)}));
  EXPECT_EQ(f.failure.stage, "push");
  EXPECT_THAT(f.failure.reason, HasSubstr("eraser would hit wall"));
  EXPECT_EQ(f.record.finalScene.object("eraser").pose.translation(), scene.object("eraser").pose.translation());
}

TEST(ExecutionFailures, AnArmThatCannotReachItsDeskSaysWhatToMove) {
  Scene scene = deskScene("panda");
  // The arm stands 2.5 m behind its desk: neither the marker nor the holder is within its reach.
  scene.robot(scene.robots().front().name).basePose.translation().x() -= 2.5;
  Failed f = executeExpectingFailure(scene, planOf({pickAction("marker")}));
  EXPECT_EQ(f.failure.stage, "grasp");
  EXPECT_THAT(f.failure.reason, HasSubstr("pick marker: marker is "));
  EXPECT_THAT(f.failure.reason, HasSubstr("from the arm base of panda (link panda_link0), beyond its reach of"));
  EXPECT_THAT(f.failure.reason, HasSubstr("move the robot (its <Home> in the problem file) or marker closer"));
}

TEST(ExecutionFailures, PreconditionsNameTheObject) {
  const Scene scene = deskScene("panda");
  Failed f = executeExpectingFailure(scene, planOf({pickAction("marker"), pickAction("marker")}));
  EXPECT_EQ(f.failure.actionIndex, 1u);
  EXPECT_EQ(f.failure.stage, "precondition");
  EXPECT_THAT(f.failure.reason, HasSubstr("marker is already held"));
  f = executeExpectingFailure(scene, planOf({pickAction("marker"), pickAction("eraser")}));
  EXPECT_THAT(f.failure.reason, HasSubstr("the gripper already holds marker"));
  f = executeExpectingFailure(scene, planOf({placeAction("eraser", SpatialRelation::kIn, "holder")}));
  EXPECT_THAT(f.failure.reason, HasSubstr("cannot place eraser: it is not held"));
  f = executeExpectingFailure(scene, planOf({pickAction("stapler")}));
  EXPECT_EQ(f.failure.stage, "precondition");
  EXPECT_THAT(f.failure.reason, HasSubstr("stapler"));
  f = executeExpectingFailure(scene, planOf({pickAction("desk")}));
  EXPECT_THAT(f.failure.reason, HasSubstr("desk: not movable"));
  f = executeExpectingFailure(scene, planOf({pushAction("eraser", Vector3(0, 0, 1), 0.05)}));
  EXPECT_THAT(f.failure.reason, HasSubstr("the direction is vertical"));
  SymbolicAction badPlanner = pickAction("marker");
  badPlanner.planner = "NotAPlanner";
  f = executeExpectingFailure(scene, planOf({badPlanner}));
  EXPECT_EQ(f.failure.stage, "precondition");
  EXPECT_THAT(f.failure.reason, HasSubstr("NotAPlanner"));
  SymbolicAction unknownPlace = moveHomeAction();
  unknownPlace.params.configuration = "dance";
  f = executeExpectingFailure(scene, planOf({unknownPlace}));
  EXPECT_THAT(f.failure.reason, HasSubstr("no named state \"dance\""));
}

TEST(ExecutionFailures, BadSettingsAndRobotsAreInputErrors) {
  const Scene scene = deskScene("panda");
  ExecutionSettings settings;
  settings.planningTimeSeconds = 0.0;
  EXPECT_THROW(TaskExecutor(scene, settings), InputError);
  settings = {};
  settings.velocityScaling = 1.5;
  EXPECT_THROW(TaskExecutor(scene, settings), InputError);
  settings = {};
  settings.robot = "r2d2";
  EXPECT_THROW(TaskExecutor(scene, settings), InputError);
  settings = {};
  settings.manipulator = "tentacle";
  EXPECT_THROW(TaskExecutor(scene, settings), InputError);
  settings = {};
  settings.ikSolver = "magic";
  EXPECT_THROW(TaskExecutor(scene, settings), InputError);
  TaskExecutor executor(scene, testSettings());
  EXPECT_THROW(static_cast<void>(executor.lastExecution()), InputError);
}

TEST(ExecutionFailures, StopConditionEndsTheActionWithAReason) {
  TaskExecutor executor(deskScene("panda"), testSettings());
  const CancelFlag cancelled = std::make_shared<std::atomic<bool>>(true);
  const auto failure = executor.execute(planOf({pickAction("marker")}), StopCondition::onCancel(cancelled));
  ASSERT_TRUE(failure.has_value());
  EXPECT_THAT(failure->reason, HasSubstr("stopped"));
}

}  // namespace
}  // namespace lang2manip::test
