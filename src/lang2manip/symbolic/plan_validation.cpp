#include "lang2manip/symbolic/plan_validation.hpp"

#include <cstdio>

#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/support_surface.hpp"
#include "lang2manip/symbolic/surface_region.hpp"

namespace lang2manip {
namespace {

std::string unknownObject(const std::string& name, const SymbolicState& state) {
  return "there is no object \"" + name + "\" (objects: " + joinedNames(state.objects) + ")";
}

std::string heldText(const SymbolicState& state) {
  return "the gripper holds " + state.held + "; place it first";
}

/// Where `object` currently is, for messages: "in holder", "on desk", "held".
std::string locationOf(const std::string& object, const SymbolicState& state) {
  if (state.held == object) return "held";
  if (auto it = state.inside.find(object); it != state.inside.end()) return "in " + it->second;
  if (auto it = state.onTopOf.find(object); it != state.onTopOf.end()) return "on " + it->second;
  return "not on anything known";
}

std::vector<std::string> pickProblems(const SymbolicAction& action, const SymbolicState& state) {
  const std::string& o = action.object;
  if (o.empty()) return {"pick needs an object"};
  if (!state.hasObject(o)) return {unknownObject(o, state)};
  if (state.held == o) return {o + " is already held"};
  std::vector<std::string> problems;
  if (!state.movable.count(o)) problems.push_back(o + " is fixed and cannot be picked");
  if (!state.held.empty()) problems.push_back("the gripper is not free: " + heldText(state));
  if (!state.isClear(o)) {
    problems.push_back(o + " is not clear: " + joinedNames(state.objectsOn(o)) + " " +
                       (state.containers.count(o) ? "is in it" : "is on it") + "; move them first");
  }
  return problems;
}

/// Whether `object` can rest on `target`: a flat top it fits on, within the footprint.
std::vector<std::string> stackingProblems(const std::string& object, const std::string& target, const SymbolicState& state) {
  if (const auto why = state.noFlatTop.find(target); why != state.noFlatTop.end()) {
    return {object + " cannot rest on " + target + ": " + why->second};
  }
  const auto top = state.flatTops.find(target);
  const auto size = state.sizes.find(object);
  if (top == state.flatTops.end() || size == state.sizes.end() || footprintFits(size->second, top->second)) return {};
  char text[160];
  std::snprintf(text, sizeof text, " (%.3f x %.3f m) does not fit on the top of %s (%.3f x %.3f m)", size->second.x(),
                size->second.y(), target.c_str(), top->second.sizes().x(), top->second.sizes().y());
  return {object + text};
}

/// Whether `object` can stand in `region` of the reachable top of `target` (regionCentres()).
std::vector<std::string> regionProblems(const std::string& object, const std::string& target, const SurfaceRegion& region,
                                        const SymbolicState& state) {
  const std::string name = surfaceRegionName(region);
  const auto area = state.reachableTops.find(target);
  if (area == state.reachableTops.end()) {
    const bool support = state.supports.count(target) > 0 && state.flatTops.count(target) > 0;
    return {target + " has no " + name + (support ? ": the robot reaches no part of its top" : ": regions are of a support's flat top")};
  }
  const auto size = state.sizes.find(object);
  if (size == state.sizes.end()) return {};
  const Vector3 turned(size->second.y(), size->second.x(), size->second.z());
  if (regionCentres(area->second, region, size->second) || regionCentres(area->second, region, turned)) return {};
  char text[200];
  std::snprintf(text, sizeof text, " (%.3f x %.3f m) does not fit in the %s of %s (the reachable top is %.3f x %.3f m)",
                size->second.x(), size->second.y(), name.c_str(), target.c_str(), area->second.sizes().x(),
                area->second.sizes().y());
  return {object + text};
}

std::vector<std::string> placeTargetProblems(const SymbolicAction& action, const SymbolicState& state) {
  const std::string& target = action.params.target;
  if (!action.params.relation) return {};
  if (target.empty()) return {"place " + spatialRelationWords(*action.params.relation) + " needs a target object"};
  if (!state.hasObject(target)) return {unknownObject(target, state)};
  if (target == action.object) return {action.object + " cannot be placed relative to itself"};
  if (target == state.held) return {"the target " + target + " is held by the gripper"};
  if (*action.params.relation == SpatialRelation::kIn && !state.containers.count(target)) {
    return {target + " is not a container" +
            (state.containers.empty() ? std::string(" (the scene has no containers)")
                                      : " (containers: " + joinedNames({state.containers.begin(), state.containers.end()}) + ")")};
  }
  if (*action.params.relation == SpatialRelation::kOn && !state.supports.count(target) &&
      !state.isClear(target)) {
    return {target + " is not clear: " + joinedNames(state.objectsOn(target)) + " is on it"};
  }
  if (*action.params.relation == SpatialRelation::kOn && action.params.region) {
    return regionProblems(action.object, target, *action.params.region, state);
  }
  if (*action.params.relation == SpatialRelation::kOn) return stackingProblems(action.object, target, state);
  return {};
}

std::vector<std::string> placeProblems(const SymbolicAction& action, const SymbolicState& state) {
  const std::string& o = action.object;
  if (o.empty()) return {"place needs an object"};
  if (!state.hasObject(o)) return {unknownObject(o, state)};
  std::vector<std::string> problems;
  if (state.held != o) {
    problems.push_back(o + " is not held" +
                       (state.held.empty() ? std::string("; pick it first")
                                           : " (the gripper holds " + state.held + "); place " +
                                                 state.held + " and pick " + o + " first"));
  }
  for (std::string& problem : placeTargetProblems(action, state)) problems.push_back(std::move(problem));
  if (!action.params.relation && !action.params.position) {
    problems.push_back("place needs a relation with a target, or a position");
  }
  return problems;
}

std::vector<std::string> moveProblems(const SymbolicAction& action, const SymbolicState& state) {
  std::vector<std::string> problems;
  const std::string& configuration = action.params.configuration;
  if (!configuration.empty() && !state.namedConfigurations.empty() &&
      !state.namedConfigurations.count(configuration)) {
    problems.push_back("the robot has no configuration \"" + configuration +
                       "\" (configurations: " + joinedNames({state.namedConfigurations.begin(), state.namedConfigurations.end()}) + ")");
  }
  if (configuration.empty() && !action.params.position) {
    problems.push_back("move needs a configuration or a position");
  }
  if (!action.object.empty() && !state.hasObject(action.object)) {
    problems.push_back(unknownObject(action.object, state));
  } else if (!action.object.empty() && state.held != action.object) {
    problems.push_back("move carries only the held object, and " + action.object + " is not held (it is " +
                       locationOf(action.object, state) + ")");
  }
  return problems;
}

std::vector<std::string> pushProblems(const SymbolicAction& action, const SymbolicState& state) {
  const std::string& o = action.object;
  if (o.empty()) return {"push needs an object"};
  if (!state.hasObject(o)) return {unknownObject(o, state)};
  std::vector<std::string> problems;
  if (state.held == o) problems.push_back(o + " is held; place it instead of pushing it");
  else if (!state.held.empty()) problems.push_back("push needs a free gripper: " + heldText(state));
  if (!state.movable.count(o)) problems.push_back(o + " is fixed and cannot be pushed");
  if (!action.params.direction) problems.push_back("push needs a direction");
  if (!action.params.distance) problems.push_back("push needs a distance");
  return problems;
}

/// What `target` rests on, for an object placed beside it.
std::string supportBeside(const std::string& target, const SymbolicState& state) {
  if (state.supports.count(target)) return target;
  if (auto it = state.onTopOf.find(target); it != state.onTopOf.end()) return it->second;
  return {};
}

void applyPlace(const SymbolicAction& action, SymbolicState& state) {
  state.held.clear();
  if (!action.params.relation) return;
  const std::string& target = action.params.target;
  switch (*action.params.relation) {
    case SpatialRelation::kIn:
      state.inside[action.object] = target;
      break;
    case SpatialRelation::kOn:
      state.onTopOf[action.object] = target;
      break;
    default:
      if (std::string support = supportBeside(target, state); !support.empty()) {
        state.onTopOf[action.object] = support;
      }
      break;
  }
}

}  // namespace

std::string PlanValidation::summary() const {
  std::string text;
  for (const std::string& problem : problems) text += (text.empty() ? "" : "\n") + problem;
  return text;
}

std::vector<std::string> actionProblems(const SymbolicAction& action, const SymbolicState& state) {
  switch (action.type) {
    case ActionType::kPick: return pickProblems(action, state);
    case ActionType::kPlace: return placeProblems(action, state);
    case ActionType::kMove: return moveProblems(action, state);
    case ActionType::kPush: return pushProblems(action, state);
  }
  return {"unknown action type"};
}

void applyAction(const SymbolicAction& action, SymbolicState& state) {
  state.atConfiguration.clear();
  switch (action.type) {
    case ActionType::kPick:
      state.inside.erase(action.object);
      state.onTopOf.erase(action.object);
      state.held = action.object;
      break;
    case ActionType::kPlace:
      applyPlace(action, state);
      break;
    case ActionType::kMove:
      state.atConfiguration = action.params.configuration;
      break;
    case ActionType::kPush:
      break;
  }
}

PlanValidation validatePlan(const Plan& plan, const SymbolicState& initial) {
  PlanValidation result;
  result.finalState = initial;
  for (std::size_t i = 0; i < plan.actions.size(); ++i) {
    const SymbolicAction& action = plan.actions[i];
    const std::vector<std::string> problems = actionProblems(action, result.finalState);
    if (!problems.empty()) {
      const std::string prefix = "step " + std::to_string(i + 1) + " (" + describeAction(action) + "): ";
      for (const std::string& problem : problems) result.problems.push_back(prefix + problem);
      result.failedStep = i;
      return result;
    }
    applyAction(action, result.finalState);
  }
  return result;
}

std::optional<bool> goalHolds(const SymbolicState& state, const Goal& goal) {
  switch (goal.kind) {
    case GoalKind::kHolding:
    case GoalKind::kHandedOver:  // symbolically: held (where the tool is is geometric)
      return state.held == goal.object;
    case GoalKind::kAtConfiguration:
      return state.atConfiguration == goal.configuration;
    case GoalKind::kDisplaced:
    case GoalKind::kAtPosition:
    case GoalKind::kTurned:
    case GoalKind::kFacing:
    case GoalKind::kArranged:
      return std::nullopt;  // geometric
    case GoalKind::kRelation:
      break;
  }
  if (!goal.relation) return std::nullopt;
  if (*goal.relation == SpatialRelation::kIn) {
    const auto it = state.inside.find(goal.object);
    return it != state.inside.end() && it->second == goal.target;
  }
  if (*goal.relation == SpatialRelation::kOn) {
    const auto it = state.onTopOf.find(goal.object);
    const bool on = it != state.onTopOf.end() && it->second == goal.target;
    if (on && goal.region) return std::nullopt;  // where on it is geometric
    return on;
  }
  return std::nullopt;
}

}  // namespace lang2manip
