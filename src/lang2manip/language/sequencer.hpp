#pragma once
/// @file From goals to a symbolic plan: searches for an order of the goals, and the actions
/// each needs (pick, place, push, move), that respects the preconditions of the symbolic state:
/// one free gripper, nothing on or in an object that is picked, a clear top to stack on, room
/// in a container. Objects in the way are moved to the support first. Deterministic.

#include <map>
#include <string>

#include "lang2manip/language/instruction.hpp"
#include "lang2manip/symbolic/action.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"

namespace lang2manip {

struct SequencingOptions {
  /// container -> floor area of its cavity, m^2; a container not listed has unlimited room.
  std::map<std::string, double> containerFloorArea;
  /// object -> the smallest cross-section it can be put into a container with, m^2.
  std::map<std::string, double> objectFootprint;
  /// Orders of goals tried before giving up.
  int maxOrdersTried = 5000;
};

/// A plan going through `specification.steps` (the goals when there are no steps) from `state`,
/// in the instruction's order when that
/// works, else in the first order (in lexicographic order of goal indices) that does. A goal
/// already true is skipped; a goal later undone by the instruction itself (holding the marker,
/// then putting it in the holder; going home, then moving on) only has to hold when it is
/// reached. Actions carry the requested grasps and planners. Throws PlanningError naming the
/// object for an unknown or unmovable object, and when no order achieves every goal.
Plan sequenceGoals(const TaskSpecification& specification, const SymbolicState& state,
                   const SequencingOptions& options = {});

}  // namespace lang2manip
