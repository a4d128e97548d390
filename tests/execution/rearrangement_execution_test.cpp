// Rearrangements and turns executed and verified on every built-in robot (issue 15, classes 5
// and 6): a swap through a free spot, an object put where another stood, a quarter turn, an
// object pointed at another; and a repair that sets an object aside elsewhere.

#include <gtest/gtest.h>

#include "execution_test_support.hpp"
#include "lang2manip/execution/execution_verification.hpp"
#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/repair_loop.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"

namespace lang2manip::test {
namespace {

using Outcome = OfflineRun;

std::string explain(const Outcome& outcome) {
  std::string text = outcome.repair.failure;
  for (const GoalOutcome& goal : outcome.verification.goals) text += " | " + goal.explanation;
  if (!outcome.verification.collision.empty()) text += " | " + outcome.verification.collision;
  return text;
}

/// A built-in robot and the arm that executes.
struct RearrangingArm {
  const char* robot;
  const char* arm;
};

class RearrangementOnRobot : public ::testing::TestWithParam<RearrangingArm> {};

// One robot per test, so that the robots run in parallel (each takes seconds under the sanitizers).
TEST_P(RearrangementOnRobot, SwapsTurnsAndPointingAreExecutedAndVerified) {
  const Scene scene = deskScene(GetParam().robot);
  for (const char* task : {"swap the marker and the eraser", "rotate the eraser by 90 degrees", "turn the marker 45 degrees clockwise",
                           "point the marker at the holder"}) {
    SCOPED_TRACE(task);
    TaskExecutor executor(scene, testSettings(GetParam().arm));
    const Outcome outcome = runOffline(executor, task);
    EXPECT_TRUE(outcome.repair.succeeded() && outcome.verification.success) << explain(outcome);
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltinRobots, RearrangementOnRobot,
                         ::testing::Values(RearrangingArm{"panda", ""}, RearrangingArm{"ur5", ""}, RearrangingArm{"iiwa14", ""},
                                           RearrangingArm{"tx90", ""}, RearrangingArm{"yumi", "right_arm"}),
                         [](const ::testing::TestParamInfo<RearrangingArm>& test) { return std::string(test.param.robot); });

TEST(RearrangementExecution, AnObjectTheGripperCannotHoldIsRefusedBeforeAnythingMoves) {
  const Scene scene = deskScene("panda");
  TaskExecutor executor(scene, testSettings());
  const Outcome outcome = runOffline(executor, "put the holder where the eraser is");  // the eraser is set aside first
  EXPECT_FALSE(outcome.repair.succeeded());
  ASSERT_FALSE(executor.executions().empty());
  for (const ExecutionRecord& record : executor.executions()) {
    ASSERT_TRUE(record.failure.has_value());
    EXPECT_EQ(record.failure->stage, "precondition");
    EXPECT_EQ(record.failure->object, "holder");
    EXPECT_NE(record.failure->reason.find("too wide for the gripper in every direction"), std::string::npos) << record.failure->reason;
    for (const ActionExecution& action : record.actions) EXPECT_NE(action.status, ActionStatus::kSucceeded) << describeAction(action.action);
  }
  EXPECT_EQ(executor.executions().size(), 1u) << "nothing new to try after a precondition";
}

/// The offline planner's next plan for `task` after `failed` could not place its action `index`.
Plan answerTo(const Scene& scene, const std::string& task, const Plan& failed, std::size_t index) {
  OfflineTaskPlanner planner;
  PlanningRequest request;
  request.task = task;
  request.scene = &scene;
  request.robot = "panda";
  PlanAttempt attempt;
  attempt.plan = failed;
  attempt.failure = "could not place";
  attempt.grounding = GroundingFailure{index, "placement", failed.actions[index].object, "no placement is reachable", {}};
  request.earlierAttempts.push_back(attempt);
  PlanningStatistics statistics;
  return planner.plan(request, StopCondition::never(), statistics);
}

TEST(RearrangementRepair, AFailedFreeSpotOrTurnIsAnsweredWithAnotherSpotOrMoreSteps) {
  const Scene scene = deskScene("panda");
  OfflineTaskPlanner planner;
  PlanningRequest request;
  request.task = "put the marker where the eraser is";
  request.scene = &scene;
  request.robot = "panda";
  PlanningStatistics statistics;
  const Plan first = planner.plan(request, StopCondition::never(), statistics);
  ASSERT_EQ(first.actions.size(), 4u);
  // Setting the eraser aside failed, or placing the marker after it: the eraser goes elsewhere.
  for (std::size_t failedAt : {1u, 3u}) {
    const Plan next = answerTo(scene, request.task, first, failedAt);
    ASSERT_EQ(next.actions.size(), 4u);
    EXPECT_GE((*next.actions[1].params.position - *first.actions[1].params.position).head<2>().norm(), 0.05);
    EXPECT_LT((*next.actions[3].params.position - *first.actions[3].params.position).norm(), 1e-9);
  }
  // A turn that failed is made in two steps, with a regrasp between them.
  const Plan turn = planner.plan(PlanningRequest{"rotate the eraser by 90 degrees", &scene, "panda", {}, {}}, StopCondition::never(), statistics);
  ASSERT_EQ(turn.actions.size(), 2u);
  const Plan inSteps = answerTo(scene, "rotate the eraser by 90 degrees", turn, 1);
  EXPECT_EQ(inSteps.actions.size(), 4u);
}

}  // namespace
}  // namespace lang2manip::test
