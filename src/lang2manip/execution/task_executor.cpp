#include "lang2manip/execution/task_executor.hpp"

#include "lang2manip/core/error.hpp"
#include "lang2manip/execution/action_grounding.hpp"
#include "lang2manip/symbolic/plan_json.hpp"

namespace lang2manip {

TaskExecutor::TaskExecutor(Scene initial, ExecutionSettings settings)
    : initial_(std::move(initial)), arm_(initial_, std::move(settings)) {}

std::optional<GroundingFailure> TaskExecutor::execute(const Plan& plan, const StopCondition& stop) {
  ExecutionRecord record;
  Scene world = initial_;
  const GroundingContext context{arm_, record.counters, stop, &plan};
  for (std::size_t i = 0; i < plan.actions.size(); ++i) {
    if (record.failure) {
      ActionExecution skipped;
      skipped.index = i;
      skipped.action = plan.actions[i];
      record.actions.push_back(std::move(skipped));
      continue;
    }
    const int index = static_cast<int>(i);
    report(progress_, {ProgressStage::kActionStarted, 0, index, "", describeAction(plan.actions[i])});
    ActionExecution action = executeAction(context, world, plan.actions[i], i);
    report(progress_, {ProgressStage::kActionFinished, 0, index, actionStatusName(action.status),
                       action.status == ActionStatus::kFailed ? action.reason : action.choice});
    record.times += action.times;
    if (action.status == ActionStatus::kFailed) {
      record.failure = GroundingFailure{i, action.stage.empty() ? "motion" : action.stage, plan.actions[i].object,
                                        action.reason, action.blockingObjects};
    }
    record.actions.push_back(std::move(action));
  }
  record.finalScene = std::move(world);
  executions_.push_back(std::move(record));
  return executions_.back().failure;
}

const ExecutionRecord& TaskExecutor::lastExecution() const {
  if (executions_.empty()) throw InputError("task executor: no plan has been executed yet");
  return executions_.back();
}

}  // namespace lang2manip
