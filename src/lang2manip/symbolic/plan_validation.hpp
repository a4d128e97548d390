#pragma once
/// @file Checking a plan against the symbolic state step by step: objects exist, preconditions
/// hold, effects applied; and checking goals against a symbolic state.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "lang2manip/symbolic/action.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"

namespace lang2manip {

/// The outcome of validatePlan().
struct PlanValidation {
  /// Messages naming the step and the objects, e.g. "step 3 (place eraser in holder): eraser
  /// is not held; pick it first". Empty when the plan is valid.
  std::vector<std::string> problems;
  /// Index (0-based) of the first step whose preconditions fail; later steps are not checked.
  std::optional<std::size_t> failedStep;
  /// The state after the last step that applied (the final state of a valid plan).
  SymbolicState finalState;

  [[nodiscard]] bool valid() const noexcept { return problems.empty(); }
  /// The problems joined by newlines.
  [[nodiscard]] std::string summary() const;
};

/// Why `action` cannot be applied in `state` (without the "step N" prefix), empty when it can:
/// - pick: the object exists and is movable, the gripper is free, the object is not held and
///   is clear (nothing on or in it);
/// - place: the object is held; the target exists and differs from it; "in" needs a container;
///   "on" needs a support or another object that is clear unless it is a support;
/// - move: a named configuration must be one of state.namedConfigurations (when known); an
///   object, if given, must be the held one;
/// - push: the object exists, is movable and not held, and the gripper is free.
std::vector<std::string> actionProblems(const SymbolicAction& action, const SymbolicState& state);

/// Applies the effects of `action` to `state` (call only when actionProblems() is empty):
/// pick holds the object (no longer in/on anything); place releases it in/on the target (for
/// the side relations: on whatever the target rests on; for a pose: nowhere known); move sets
/// or clears atConfiguration; every action except move to a configuration clears it.
void applyAction(const SymbolicAction& action, SymbolicState& state);

/// Validates `plan` from `initial`: each step's problems prefixed with "step N (action)".
PlanValidation validatePlan(const Plan& plan, const SymbolicState& initial);

/// Whether `goal` holds in `state`: in/on relations, holding and at-configuration. nullopt for
/// goals that need geometry (left_of, right_of, in_front_of, behind, next_to, displaced): see
/// checkGoalInScene() in goal_check.hpp.
std::optional<bool> goalHolds(const SymbolicState& state, const Goal& goal);

}  // namespace lang2manip
