// The paper's task, "put the marker and eraser in the holder", planned offline, grounded,
// executed and verified on every built-in robot (both arms of YuMi), and with every registered
// geometric planner on the Panda.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "execution_test_support.hpp"
#include "lang2manip/execution/execution_verification.hpp"
#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/planning/planner_registry.hpp"
#include "lang2manip/symbolic/repair_loop.hpp"

namespace lang2manip::test {
namespace {

constexpr const char* kPaperTask = "put the marker and eraser in the holder";

using TaskRun = OfflineRun;

TaskRun runPaperTask(TaskExecutor& executor, const std::string& task = kPaperTask) { return runOffline(executor, task); }

struct RobotArm {
  std::string robot;
  std::string arm;
};

class PaperTask : public ::testing::TestWithParam<RobotArm> {};

/// The arm is at rest (every joint's speed below 1e-6) only where a run of motions begins or ends:
/// not inside a transit, a Cartesian move, or between the two.
void expectStopsOnlyWhereRunsEnd(const ExecutionRecord& record) {
  for (const ActionExecution& action : record.actions) {
    std::vector<double> runEnds{0.0};
    for (const TimedRun& run : action.runs) runEnds.push_back(action.segmentEndTimes[run.endSegment - 1]);
    int stops = 0;
    for (const TrajectoryPoint& point : action.trajectory.points) {
      if (point.velocities.cwiseAbs().maxCoeff() > 1e-6) continue;
      const bool atRunEnd = std::any_of(runEnds.begin(), runEnds.end(), [&](double t) { return std::abs(t - point.time) < 1e-9; });
      stops += atRunEnd ? 0 : 1;
      EXPECT_TRUE(atRunEnd) << "step " << action.index + 1 << " stops at " << point.time << " s";
    }
    EXPECT_EQ(action.quality.stopsInsideRuns, 0) << "step " << action.index + 1;
    EXPECT_EQ(stops, 0);
  }
}

TEST_P(PaperTask, SucceedsAndIsVerified) {
  TaskExecutor executor(deskScene(GetParam().robot), testSettings(GetParam().arm));
  const TaskRun run = runPaperTask(executor);
  ASSERT_TRUE(run.repair.succeeded()) << run.repair.failure;
  EXPECT_TRUE(run.verification.success);
  EXPECT_TRUE(run.verification.collision.empty()) << run.verification.collision;
  EXPECT_TRUE(run.verification.disturbedObjects.empty());
  ASSERT_EQ(run.verification.goals.size(), 2u);
  for (const GoalOutcome& goal : run.verification.goals) EXPECT_TRUE(goal.holds) << goal.explanation;
  EXPECT_GT(run.verification.segmentsChecked, 8);
  const ExecutionRecord& record = executor.lastExecution();
  ASSERT_EQ(record.actions.size(), 4u);
  for (const ActionExecution& action : record.actions) EXPECT_EQ(action.status, ActionStatus::kSucceeded);
  expectContinuousMotion(executor, record);
  expectStopsOnlyWhereRunsEnd(record);
  expectCartesianMovesStraight(executor, record);
  double duration = 0.0;
  for (const ActionExecution& action : record.actions) duration += action.trajectory.duration();
  RecordProperty("trajectory_seconds", std::to_string(duration));
  if (GetParam().robot == "panda") {
    EXPECT_LE(duration, 12.0);
  }
}

TEST_P(PaperTask, TheOtherOrderSucceedsInTheFirstRound) {
  // The eraser first: released in the middle of the holder it would block the marker, so its
  // placement leaves room for what the plan puts there next.
  for (const char* task : {"put the eraser and the marker in the holder", "put the eraser in the holder, then the marker"}) {
    SCOPED_TRACE(task);
    TaskExecutor executor(deskScene(GetParam().robot), testSettings(GetParam().arm));
    const TaskRun run = runPaperTask(executor, task);
    ASSERT_TRUE(run.repair.succeeded()) << run.repair.failure;
    EXPECT_EQ(run.repair.rounds.size(), 1u);
    EXPECT_TRUE(run.verification.success) << run.verification.collision;
  }
}

TEST(PaperTaskTiming, TimeOptimalIsFasterThanRestToRestEvenWithWideBlends) {
  ExecutionSettings restToRest = testSettings();
  restToRest.timing = TrajectoryTiming::kRestToRest;
  TaskExecutor slow(deskScene("panda"), restToRest);
  ASSERT_TRUE(runPaperTask(slow).repair.succeeded());
  double slowDuration = 0.0;
  for (const ActionExecution& action : slow.lastExecution().actions) {
    slowDuration += action.trajectory.duration();
    EXPECT_TRUE(action.runs.empty());
  }
  ExecutionSettings wide = testSettings();
  // Arcs as wide as the path allows: a corner with little room is shrunk until its arc fits,
  // however many times, and stops only where not even the smallest arc would.
  wide.blendDeviation = 100.0;
  TaskExecutor fast(deskScene("panda"), wide);
  const TaskRun run = runPaperTask(fast);
  ASSERT_TRUE(run.repair.succeeded()) << run.repair.failure;
  EXPECT_TRUE(run.verification.collision.empty()) << run.verification.collision;
  double fastDuration = 0.0;
  for (const ActionExecution& action : fast.lastExecution().actions) fastDuration += action.trajectory.duration();
  EXPECT_LT(fastDuration, 0.75 * slowDuration);
  expectContinuousMotion(fast, fast.lastExecution());
  expectStopsOnlyWhereRunsEnd(fast.lastExecution());
}

TEST(PaperTaskTiming, ScalingSlowsTheMotionWithinTheScaledLimits) {
  ExecutionSettings half = testSettings();
  half.velocityScaling = 0.5;
  half.accelerationScaling = 0.25;
  TaskExecutor executor(deskScene("panda"), half);
  ASSERT_TRUE(runPaperTask(executor).repair.succeeded());
  expectContinuousMotion(executor, executor.lastExecution());
  double duration = 0.0;
  for (const ActionExecution& action : executor.lastExecution().actions) duration += action.trajectory.duration();
  EXPECT_GT(duration, 15.0);
}

INSTANTIATE_TEST_SUITE_P(BuiltinRobots, PaperTask,
                         ::testing::Values(RobotArm{"panda", ""}, RobotArm{"ur5", ""}, RobotArm{"iiwa14", ""},
                                           RobotArm{"yumi", "right_arm"}, RobotArm{"yumi", "left_arm"}, RobotArm{"tx90", ""}),
                         [](const ::testing::TestParamInfo<RobotArm>& test) {
                           return test.param.robot + (test.param.arm.empty() ? "" : "_" + test.param.arm);
                         });

/// Planners whose every query runs to the time limit (they only stop there), or that need a
/// goal sampler a joint goal set does not give; they still run, with a shorter limit.
bool plansUntilItsLimit(const std::string& planner) {
  for (const char* name : {"PRMstar", "LazyPRMstar", "SPARS", "SPARStwo", "AITstar", "ABITstar", "BITstar"}) {
    if (planner == name) return true;
  }
  return false;
}

/// Batch planners: a query ends when its batch of samples is processed, which a loaded 2-core
/// machine may not finish in 0.5 s; they get 3 s and stop as soon as they are done.
bool plansInABatch(const std::string& planner) { return planner == "FMT" || planner == "BFMT"; }

TEST(PaperTaskPlanners, EveryRegisteredGeometricPlannerSucceedsOnThePanda) {
  std::vector<std::string> planners = plannerNames();
  if (kSanitizedBuild) planners = {"RRTConnect", "PRM"};
  for (const std::string& planner : planners) {
    ExecutionSettings settings = testSettings();
    settings.defaultPlanner = planner;
    if (plansUntilItsLimit(planner)) settings.planningTimeSeconds = 0.5;
    if (plansInABatch(planner)) settings.planningTimeSeconds = 3.0;
    TaskExecutor executor(deskScene("panda"), settings);
    const TaskRun run = runPaperTask(executor);
    EXPECT_TRUE(run.repair.succeeded() && run.verification.success) << planner << ": " << run.repair.failure;
    for (const ActionExecution& action : executor.lastExecution().actions) {
      for (const MotionSegment& segment : action.segments) {
        if (!segment.planner.empty()) {
          EXPECT_EQ(segment.planner, planner) << segment.label;
        }
      }
    }
  }
}

}  // namespace
}  // namespace lang2manip::test

namespace lang2manip::test {
namespace {

/// `task` planned by the offline planner and executed by `executor` through the repair loop.
RepairResult planOfflineWithRepair(const Scene& scene, TaskExecutor& executor, const std::string& task) {
  OfflineTaskPlanner planner;
  PlanningRequest request;
  request.task = task;
  request.scene = &scene;
  request.robot = executor.arm().robotName();
  return planWithRepair(planner, request, &executor, RepairOptions{}, StopCondition::never());
}

TEST(RepairByCarrying, APushTheHandHasNoRoomForIsCarriedInstead) {
  Scene scene = deskScene("panda");
  // A block 5 mm to the right of the eraser: the hand cannot get behind it to push it left.
  scene.addObject(fixedBox("block", Vector3(0.06, 0.03, 0.05), Vector3(-0.02, 0.14, 0.75)));
  TaskExecutor executor(scene, testSettings());
  const RepairResult repair = planOfflineWithRepair(scene, executor, "move the eraser 5 cm to the left");
  ASSERT_TRUE(repair.succeeded()) << repair.failure;
  ASSERT_GE(repair.rounds.size(), 2u);
  ASSERT_TRUE(repair.rounds[0].attempt.grounding.has_value());
  EXPECT_EQ(repair.rounds[0].attempt.plan->actions[0].type, ActionType::kPush);  // its descent behind the eraser collides
  ASSERT_EQ(repair.plan->actions.size(), 2u);
  EXPECT_EQ(repair.plan->actions[0].type, ActionType::kPick);
  const Vector3 moved = executor.lastExecution().finalScene.object("eraser").pose.translation() - scene.object("eraser").pose.translation();
  EXPECT_NEAR(moved.x(), 0.0, 0.01);
  EXPECT_NEAR(moved.y(), 0.05, 0.01);
}

}  // namespace
}  // namespace lang2manip::test

namespace lang2manip::test {
namespace {

TEST(HandingOver, TheObjectIsHeldOutAtTheHandoverPositionOnEveryBuiltInRobot) {
  for (const auto& [robot, arm] : {std::pair{"panda", ""}, std::pair{"ur5", ""}, std::pair{"iiwa14", ""},
                                   std::pair{"tx90", ""}, std::pair{"yumi", "right_arm"}, std::pair{"yumi", "left_arm"}}) {
    SCOPED_TRACE(std::string(robot) + " " + arm);
    const Scene scene = deskScene(robot);
    TaskExecutor executor(scene, testSettings(arm));
    const RepairResult repair = planOfflineWithRepair(scene, executor, "hand me the eraser");
    ASSERT_TRUE(repair.succeeded()) << repair.failure;
    const std::vector<Goal> goals = understandInstruction("hand me the eraser", describeObjects(scene, executor.arm().robotName())).goals;
    const ExecutionVerification verification = verifyExecution(executor.arm(), scene, executor.lastExecution(), goals);
    EXPECT_TRUE(verification.success) << (verification.goals.empty() ? "" : verification.goals.front().explanation);
    // Dropped where it was, it is not handed over.
    Goal elsewhere = goals.front();
    elsewhere.object = "marker";
    EXPECT_FALSE(verifyExecution(executor.arm(), scene, executor.lastExecution(), {elsewhere}).goals.front().holds);
  }
}

}  // namespace
}  // namespace lang2manip::test
