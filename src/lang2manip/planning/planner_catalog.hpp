#pragma once
/// @file The geometric planners lang2manip runs, by name: OMPL's class names, Kautham's names and
/// other aliases, and what each planner is like (optimizing, parallel, ...). Data only, no OMPL:
/// the language module reads planner names from it; planning/planner_registry.hpp creates them.
/// Unknown names are errors that list the valid ones (Kautham ignores them silently; lang2manip
/// does not).

#include <string>
#include <vector>

namespace lang2manip {

struct PlannerDescription {
  /// OMPL's class name, e.g. "RRTConnect", "RRTstar", "KPIECE1".
  std::string name;
  /// Other names accepted for it (Kautham's "omplRRTConnect", ...).
  std::vector<std::string> aliases;
  /// Asymptotically optimal: refines its solution until the time limit when `_Optimize` is 1.
  bool optimizing = false;
  /// Runs several threads.
  bool parallel = false;
  /// Ignores the "first solution is enough" objective and always plans until its time limit.
  bool runsUntilTimeLimit = false;
  /// Its `range` is a tree step that PlanningSpace::defaultRange() may set (false for RLRT and
  /// BiRLRT, whose range bounds random local trees and stalls them when small).
  bool takesSpaceRange = true;
  /// Accepts a single goal state only (not a set of goal states).
  bool singleGoalState = false;
};

/// Every registered planner, in a stable order.
const std::vector<PlannerDescription>& plannerDescriptions();

/// The description of a registered planner (by canonical name, alias, ...); throws as
/// canonicalPlannerName().
const PlannerDescription& plannerDescription(const std::string& name);

/// Canonical names of every registered planner.
std::vector<std::string> plannerNames();

/// The canonical name of a planner given by name or alias (case-sensitive first, then
/// case-insensitive). Throws InputError listing the valid names for an unknown name, and
/// NotSupportedError for Kautham planners that are not geometric OMPL planners (control-based,
/// constrained, physics-based) naming what they need.
std::string canonicalPlannerName(const std::string& name);

}  // namespace lang2manip
