#include "lang2manip/execution/task_executor.hpp"

#include <cmath>

#include "lang2manip/core/error.hpp"
#include "lang2manip/execution/action_grounding.hpp"

namespace lang2manip {
namespace {

void checkPositive(double value, const char* field) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw InputError(std::string("execution settings: ") + field + " must be a positive number (got " + std::to_string(value) + ")");
  }
}

void checkLength(double value, const char* field) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    throw InputError(std::string("execution settings: ") + field + " must be a finite length >= 0 (got " + std::to_string(value) + ")");
  }
}

}  // namespace

std::string actionStatusName(ActionStatus status) {
  switch (status) {
    case ActionStatus::kSucceeded: return "succeeded";
    case ActionStatus::kFailed: return "failed";
    case ActionStatus::kNotRun: return "not run";
  }
  return "unknown";
}

StageTimes& StageTimes::operator+=(const StageTimes& other) {
  grasp += other.grasp;
  placement += other.placement;
  ik += other.ik;
  motion += other.motion;
  return *this;
}

void checkExecutionSettings(const ExecutionSettings& s) {
  checkPositive(s.planningTimeSeconds, "planningTimeSeconds");
  checkPositive(s.cartesianStep, "cartesianStep");
  checkPositive(s.cartesianAngleStep, "cartesianAngleStep");
  checkPositive(s.maxJointStep, "maxJointStep");
  checkPositive(s.verificationResolution, "verificationResolution");
  checkLength(s.pushApproachHeight, "pushApproachHeight");
  checkLength(s.pushStandoff, "pushStandoff");
  checkLength(s.pushRetreat, "pushRetreat");
  checkPositive(s.reach.ikTimeoutSeconds, "reach.ikTimeoutSeconds");
  if (s.maxGraspAttempts < 1) throw InputError("execution settings: maxGraspAttempts must be >= 1");
  if (s.maxPlacementAttempts < 1) throw InputError("execution settings: maxPlacementAttempts must be >= 1");
  if (s.reach.ikSolutions < 1) throw InputError("execution settings: reach.ikSolutions must be >= 1");
  if (!(s.speedScale > 0.0 && s.speedScale <= 1.0)) {
    throw InputError("execution settings: speedScale must be in (0, 1] (got " + std::to_string(s.speedScale) + ")");
  }
  checkGraspSettings(s.grasp);
  checkPlacementSettings(s.placement);
}

TaskExecutor::TaskExecutor(Scene initial, ExecutionSettings settings)
    : initial_(std::move(initial)), arm_(initial_, std::move(settings)) {}

std::optional<GroundingFailure> TaskExecutor::execute(const Plan& plan, const StopCondition& stop) {
  ExecutionRecord record;
  Scene world = initial_;
  const GroundingContext context{arm_, record.counters, stop};
  for (std::size_t i = 0; i < plan.actions.size(); ++i) {
    if (record.failure) {
      ActionExecution skipped;
      skipped.index = i;
      skipped.action = plan.actions[i];
      record.actions.push_back(std::move(skipped));
      continue;
    }
    ActionExecution action = executeAction(context, world, plan.actions[i], i);
    record.times += action.times;
    if (action.status == ActionStatus::kFailed) {
      record.failure = GroundingFailure{i, action.stage.empty() ? "motion" : action.stage, plan.actions[i].object, action.reason};
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
