#include "lang2manip/execution/task_executor.hpp"

#include <cstdio>

#include "lang2manip/core/error.hpp"
#include "lang2manip/execution/action_grounding.hpp"
#include "lang2manip/symbolic/plan_json.hpp"

namespace lang2manip {

TaskExecutor::TaskExecutor(Scene initial, ExecutionSettings settings)
    : initial_(std::move(initial)), arm_(initial_, std::move(settings)) {}

namespace {

/// The first pick of an object whose narrowest extent is wider than the gripper opens (no grasp
/// can hold it, whatever the plan does first), with why; nullopt when there is none.
std::optional<std::pair<std::size_t, std::string>> firstUnholdablePick(const Plan& plan, const Scene& scene,
                                                                       const GripperGeometry& gripper) {
  if (!gripper.hasGripper()) return std::nullopt;
  for (std::size_t i = 0; i < plan.actions.size(); ++i) {
    const SymbolicAction& action = plan.actions[i];
    const SceneObject* object = action.type == ActionType::kPick ? scene.findObject(action.object) : nullptr;
    if (object == nullptr || !object->movable || object->collisions.empty()) continue;  // others fail with their reason
    const double narrowest = object->dimensions().minCoeff();
    if (narrowest <= gripper.maxOpening) continue;
    char text[160];
    std::snprintf(text, sizeof text, ": too wide for the gripper in every direction (%.3f m at its narrowest, the gripper opens %.3f m)",
                  narrowest, gripper.maxOpening);
    return std::make_pair(i, action.object + text);
  }
  return std::nullopt;
}

/// True when action `index` of `plan` places the object that action `index - 1` picked.
bool placesWhatWasJustPicked(const Plan& plan, std::size_t index) {
  return index > 0 && plan.actions[index].type == ActionType::kPlace && plan.actions[index - 1].type == ActionType::kPick &&
         plan.actions[index].object == plan.actions[index - 1].object;
}

/// The pick before a failed place grounded again from `beforePick`, its grasps ordered for the
/// place, and the place after it: both records when the place then succeeds (and `world` the
/// world after them), none when it still fails or the same grasp came first again. The times of
/// the retry are added to `spent`, but for the place's when it succeeds.
std::optional<std::pair<ActionExecution, ActionExecution>> pickAgainForPlace(const GroundingContext& context, const Plan& plan, std::size_t place,
                                                                              const Scene& beforePick, const ActionExecution& firstPick, Scene& world,
                                                                              StageTimes& spent) {
  GroundingContext forPlace = context;
  forPlace.placeAfterPick = &plan.actions[place];
  Scene retried = beforePick;
  ActionExecution pick = executeAction(forPlace, retried, plan.actions[place - 1], place - 1);
  spent += pick.times;
  if (pick.status != ActionStatus::kSucceeded || pick.choice == firstPick.choice) return std::nullopt;
  ActionExecution placed = executeAction(context, retried, plan.actions[place], place);
  if (placed.status != ActionStatus::kSucceeded) {
    spent += placed.times;
    return std::nullopt;
  }
  world = std::move(retried);
  return std::make_pair(std::move(pick), std::move(placed));
}

}  // namespace

std::optional<GroundingFailure> TaskExecutor::execute(const Plan& plan, const StopCondition& stop) {
  ExecutionRecord record;
  Scene world = initial_;
  const GroundingContext context{arm_, record.counters, stop, &plan};
  if (const auto unholdable = firstUnholdablePick(plan, initial_, arm_.gripper())) {
    // Refused before anything moves: nothing the plan does first makes the object fit.
    const auto [index, reason] = *unholdable;
    for (std::size_t i = 0; i < plan.actions.size(); ++i) {
      ActionExecution action;
      action.index = i;
      action.action = plan.actions[i];
      if (i == index) {
        action.status = ActionStatus::kFailed;
        action.stage = "precondition";
        action.reason = reason;
      }
      record.actions.push_back(std::move(action));
    }
    record.failure = GroundingFailure{index, "precondition", plan.actions[index].object, reason, {}, true};
    record.finalScene = std::move(world);
    executions_.push_back(std::move(record));
    return executions_.back().failure;
  }
  Scene beforePick;
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
    if (plan.actions[i].type == ActionType::kPick) beforePick = world;
    ActionExecution action = executeAction(context, world, plan.actions[i], i);
    if (action.status == ActionStatus::kFailed && placesWhatWasJustPicked(plan, i)) {
      // The grasp kept from the pick may be what the place cannot do: the pick again, with the
      // grasps that leave the place a placement first.
      StageTimes spent;
      if (auto again = pickAgainForPlace(context, plan, i, beforePick, record.actions.back(), world, spent)) {
        record.times += action.times;
        record.actions.back() = std::move(again->first);
        action = std::move(again->second);  // its times are counted below
      }
      record.times += spent;
    }
    report(progress_, {ProgressStage::kActionFinished, 0, index, actionStatusName(action.status),
                       action.status == ActionStatus::kFailed ? action.reason : action.choice});
    record.times += action.times;
    if (action.status == ActionStatus::kFailed) {
      record.failure = GroundingFailure{i, action.stage.empty() ? "motion" : action.stage, plan.actions[i].object,
                                        action.reason, action.blockingObjects, action.objectUngraspable};
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
