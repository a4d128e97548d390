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

struct TaskRun {
  RepairResult repair;
  ExecutionVerification verification;
};

TaskRun runPaperTask(TaskExecutor& executor) {
  const Scene& scene = executor.initialScene();
  OfflineTaskPlanner planner;
  PlanningRequest request;
  request.task = kPaperTask;
  request.scene = &scene;
  request.robot = executor.arm().robotName();
  TaskRun run;
  run.repair = planWithRepair(planner, request, &executor, RepairOptions{}, StopCondition::never());
  if (!executor.executions().empty()) {
    const auto goals = understandInstruction(kPaperTask, describeObjects(scene, request.robot)).goals;
    run.verification = verifyExecution(executor.arm(), scene, executor.lastExecution(), goals);
  }
  return run;
}

struct RobotArm {
  std::string robot;
  std::string arm;
};

class PaperTask : public ::testing::TestWithParam<RobotArm> {};

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
  for (const char* name : {"PRMstar", "LazyPRMstar", "SPARS", "SPARStwo", "FMT", "BFMT", "AITstar", "ABITstar", "BITstar"}) {
    if (planner == name) return true;
  }
  return false;
}

TEST(PaperTaskPlanners, EveryRegisteredGeometricPlannerSucceedsOnThePanda) {
  std::vector<std::string> planners = plannerNames();
  if (kSanitizedBuild) planners = {"RRTConnect", "PRM"};
  for (const std::string& planner : planners) {
    ExecutionSettings settings = testSettings();
    settings.defaultPlanner = planner;
    if (plansUntilItsLimit(planner)) settings.planningTimeSeconds = 0.5;
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
