#include "language/plan_check.hpp"

#include <map>

#include <gtest/gtest.h>

#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/language/sequencer.hpp"
#include "lang2manip/symbolic/task_planner.hpp"
#include "language/language_test_support.hpp"

namespace lang2manip::test {
namespace {

std::string checkPick(const SymbolicAction& action, const SymbolicState& state) {
  if (!state.held.empty()) return "gripper holds " + state.held;
  if (!state.movable.count(action.object)) return action.object + " is not movable";
  if (!state.isClear(action.object)) return action.object + " is not clear";
  return "";
}

std::string checkPlace(const SymbolicAction& action, const SymbolicState& state) {
  if (state.held != action.object) return "not holding " + action.object;
  if (!action.params.relation) return action.params.position ? "" : "neither a relation nor a position";
  const std::string& target = action.params.target;
  if (!state.hasObject(target) || target == action.object) return "bad target " + target;
  if (*action.params.relation == SpatialRelation::kIn && !state.containers.count(target)) {
    return target + " is not a container";
  }
  if (*action.params.relation == SpatialRelation::kOn && !state.supports.count(target) &&
      !state.isClear(target)) {
    return target + " is not clear";
  }
  return "";
}

std::string supportOf(const SymbolicState& state, const std::string& object) {
  std::string current = object;
  for (std::size_t i = 0; i <= state.objects.size(); ++i) {
    if (state.supports.count(current)) return current;
    const auto in = state.inside.find(current);
    const auto on = state.onTopOf.find(current);
    if (in != state.inside.end()) current = in->second;
    else if (on != state.onTopOf.end()) current = on->second;
    else break;
  }
  return "";
}

std::string firstSupport(const SymbolicState& state) {
  for (const std::string& name : state.objects) {
    if (state.supports.count(name)) return name;
  }
  return "";
}

/// Applies `action`; a place at a position records it in `positions` (and rests on the support).
void apply(const SymbolicAction& action, SymbolicState& state, std::map<std::string, Vector3>& positions) {
  if (action.type == ActionType::kPlace && !action.params.relation) {
    positions[action.object] = *action.params.position;
    state.onTopOf[action.object] = firstSupport(state);
    state.held.clear();
    return;
  }
  if (action.type == ActionType::kPick) {
    state.inside.erase(action.object);
    state.onTopOf.erase(action.object);
    state.held = action.object;
  } else if (action.type == ActionType::kPlace) {
    const SpatialRelation relation = *action.params.relation;
    if (relation == SpatialRelation::kIn) state.inside[action.object] = action.params.target;
    else if (relation == SpatialRelation::kOn) state.onTopOf[action.object] = action.params.target;
    else state.onTopOf[action.object] = supportOf(state, action.params.target);
    state.held.clear();
  }
}

bool isFinal(const TaskSpecification& specification, std::size_t index) {
  for (std::size_t later = index + 1; later < specification.goals.size(); ++later) {
    if (specification.goals[later].object == specification.goals[index].object) return false;
  }
  return true;
}

std::string checkGoal(const Goal& goal, const SymbolicState& state, const std::map<std::string, Vector3>& positions) {
  bool holds = true;
  if (goal.kind == GoalKind::kAtPosition) {
    const auto at = positions.find(goal.object);
    holds = at != positions.end() && goal.position && (at->second - *goal.position).head<2>().norm() < 0.01;
  }
  if (goal.kind == GoalKind::kHolding) holds = state.held == goal.object;
  if (goal.kind == GoalKind::kRelation && goal.relation == SpatialRelation::kIn) {
    holds = state.inside.count(goal.object) && state.inside.at(goal.object) == goal.target;
  }
  if (goal.kind == GoalKind::kRelation && goal.relation == SpatialRelation::kOn) {
    holds = state.onTopOf.count(goal.object) && state.onTopOf.at(goal.object) == goal.target;
  }
  return holds ? "" : describeGoal(goal) + " does not hold at the end";
}

}  // namespace

std::string checkPlan(const Plan& plan, SymbolicState state,
                      const TaskSpecification& specification) {
  std::map<std::string, Vector3> positions;
  for (std::size_t index = 0; index < plan.actions.size(); ++index) {
    const SymbolicAction& action = plan.actions[index];
    std::string problem;
    if (action.type == ActionType::kPick) problem = checkPick(action, state);
    if (action.type == ActionType::kPlace) problem = checkPlace(action, state);
    if (action.type == ActionType::kPush && !state.held.empty()) problem = "gripper is not free";
    if (!problem.empty()) {
      return "action " + std::to_string(index + 1) + " (" + actionTypeName(action.type) + " " +
             action.object + "): " + problem;
    }
    apply(action, state, positions);
  }
  for (std::size_t index = 0; index < specification.goals.size(); ++index) {
    if (!isFinal(specification, index)) continue;
    if (std::string problem = checkGoal(specification.goals[index], state, positions); !problem.empty()) {
      return problem;
    }
  }
  return "";
}

void expectUnderstoodAndPlanned(const Scene& scene, std::span<const std::pair<const char*, const char*>> cases) {
  const SymbolicState state = observeSymbolicState(scene);
  const std::vector<ObjectDescriptor> objects = describeObjects(scene);
  for (const auto& [instruction, expected] : cases) {
    SCOPED_TRACE(instruction);
    try {
      const TaskSpecification specification = understandInstruction(instruction, objects);
      EXPECT_EQ(summarize(specification), expected);
      const Plan plan = sequenceGoals(specification, state, sequencingOptionsFor(scene));
      EXPECT_EQ(checkPlan(plan, state, specification), "");
    } catch (const PlanningError& error) {
      ADD_FAILURE() << "refused: " << error.what();
    }
  }
}

}  // namespace lang2manip::test
