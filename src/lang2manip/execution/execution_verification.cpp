#include "lang2manip/execution/execution_verification.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "lang2manip/core/error.hpp"
#include "lang2manip/execution/motion_timing.hpp"
#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"

namespace lang2manip {
namespace {

/// An object whose position changed by more than this (m) or whose orientation by more than
/// kRotationTolerance (rad) has moved.
constexpr double kPositionTolerance = 1e-3;
constexpr double kRotationTolerance = 1e-2;

std::string firstCollision(const ArmContext& arm, const ExecutionRecord& record, ExecutionVerification& result) {
  for (const ActionExecution& action : record.actions) {
    result.segmentsChecked += static_cast<int>(action.segments.size());
    const SegmentCheck check = checkTimedAction(arm, action, arm.settings().verificationResolution);
    result.collisionChecks += check.checks;
    if (!check.collision.empty()) {
      return "step " + std::to_string(action.index + 1) + " (" + describeAction(action.action) + "): " + check.collision;
    }
  }
  return {};
}

std::vector<std::string> disturbed(const Scene& initial, const ExecutionRecord& record) {
  std::set<std::string> actedOn;
  for (const ActionExecution& action : record.actions) {
    if (!action.action.object.empty()) actedOn.insert(action.action.object);
  }
  std::vector<std::string> moved;
  for (const SceneObject& before : initial.objects()) {
    if (actedOn.count(before.name) != 0) continue;
    const SceneObject* after = record.finalScene.findObject(before.name);
    if (after == nullptr) {
      moved.push_back(before.name + " is gone");
      continue;
    }
    const double shift = (after->pose.translation() - before.pose.translation()).norm();
    const double turn = Quaternion(after->pose.linear()).angularDistance(Quaternion(before.pose.linear()));
    if (shift > kPositionTolerance || turn > kRotationTolerance || record.finalScene.findAttachment(before.name) != nullptr) {
      char text[128];
      std::snprintf(text, sizeof text, " moved by %.4f m and turned by %.3f rad", shift, turn);
      moved.push_back(before.name + text);
    }
  }
  return moved;
}

/// Held by the arm, with the tool within 2 cm of handoverToolPosition().
GoalOutcome evaluateHandover(const ArmContext& arm, const ExecutionRecord& record, const Goal& goal) {
  GoalOutcome outcome;
  outcome.goal = goal;
  const Scene& world = record.finalScene;
  const Attachment* held = world.findAttachment(goal.object);
  if (held == nullptr || held->robot != arm.robotName()) {
    outcome.explanation = describeGoal(goal) + ": does not hold (" + goal.object + " is not held)";
    return outcome;
  }
  const Pose tool = robotBaseFrame(world, arm.robotName()).inverse() * arm.toolPose(world, world.robot(arm.robotName()).configuration);
  const double off = (tool.translation() - handoverToolPosition()).norm();
  outcome.holds = off <= 0.02;
  char text[96];
  std::snprintf(text, sizeof text, ": %s (the tool is %.3f m from the handover position)", outcome.holds ? "holds" : "does not hold", off);
  outcome.explanation = describeGoal(goal) + text;
  return outcome;
}

GoalOutcome evaluate(const Scene& initial, const ExecutionRecord& record, const Goal& goal, const ArmContext& arm) {
  GoalOutcome outcome;
  outcome.goal = goal;
  GoalCheckOptions options;
  options.robot = arm.robotName();
  options.arm = arm.manipulator().name;
  options.initialScene = &initial;
  try {
    const GoalCheck check = checkGoalInScene(record.finalScene, goal, options);
    outcome.holds = check.holds;
    outcome.explanation = check.explanation;
  } catch (const InputError& error) {
    outcome.explanation = describeGoal(goal) + ": " + error.what();
  }
  return outcome;
}

}  // namespace

ExecutionVerification verifyExecution(const ArmContext& arm, const Scene& initial, const ExecutionRecord& record,
                                      const std::vector<Goal>& goals) {
  const auto began = std::chrono::steady_clock::now();
  ExecutionVerification result;
  result.collision = firstCollision(arm, record, result);
  for (const Goal& goal : goals) {
    result.goals.push_back(goal.kind == GoalKind::kHandedOver ? evaluateHandover(arm, record, goal)
                                                              : evaluate(initial, record, goal, arm));
  }
  result.disturbedObjects = disturbed(initial, record);
  bool goalsHold = !result.goals.empty();
  for (const GoalOutcome& goal : result.goals) goalsHold = goalsHold && goal.holds;
  result.success = record.succeeded() && result.collision.empty() && goalsHold && result.disturbedObjects.empty();
  result.seconds = secondsSince(began);
  return result;
}

std::vector<Goal> goalsImpliedByPlan(const Plan& plan) {
  std::map<std::string, Goal> placed;
  std::vector<std::string> order;
  std::vector<Goal> pushes;
  std::string held;
  std::string configuration;
  for (const SymbolicAction& action : plan.actions) {
    if (action.type == ActionType::kPick) held = action.object;
    if (action.type == ActionType::kPlace) {
      if (held == action.object) held.clear();
      if (!action.params.relation && !action.params.position) continue;
      Goal goal;
      goal.object = action.object;
      if (action.params.relation) {
        goal.relation = action.params.relation;
        goal.target = action.params.target;
        goal.distance = action.params.distance;
      } else {
        goal.kind = GoalKind::kAtPosition;
        goal.position = action.params.position;
      }
      if (placed.count(action.object) == 0) order.push_back(action.object);
      placed[action.object] = goal;
    }
    if (action.type == ActionType::kPush && action.params.direction && action.params.distance) {
      Goal goal;
      goal.kind = GoalKind::kDisplaced;
      goal.object = action.object;
      goal.displacement = action.params.direction->normalized() * *action.params.distance;
      pushes.push_back(goal);
    }
    if (action.type == ActionType::kMove) configuration = action.params.configuration;
    else configuration.clear();
  }
  std::vector<Goal> goals;
  for (const std::string& object : order) goals.push_back(placed[object]);
  goals.insert(goals.end(), pushes.begin(), pushes.end());
  if (!held.empty()) {
    Goal goal;
    goal.kind = GoalKind::kHolding;
    goal.object = held;
    goals.push_back(goal);
  }
  if (!configuration.empty()) {
    Goal goal;
    goal.kind = GoalKind::kAtConfiguration;
    goal.configuration = configuration;
    goals.push_back(goal);
  }
  return goals;
}

}  // namespace lang2manip
