#pragma once
/// @file Every geometric planner of Debian's OMPL 1.5.2 by name, also under Kautham's names,
/// and their parameters by OMPL's and Kautham's names. Unknown names are errors that list the
/// valid ones (Kautham ignores them silently; lang2manip does not).

#include <memory>
#include <string>
#include <vector>

#include <ompl/base/Planner.h>
#include <ompl/base/SpaceInformation.h>

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

/// A new OMPL planner `canonicalName` for `si`.
ompl::base::PlannerPtr createOmplPlanner(const std::string& canonicalName,
                                         const ompl::base::SpaceInformationPtr& si);

/// Names of OMPL's parameters of a planner (its ParamSet), e.g. "range", "goal_bias".
std::vector<std::string> omplParameterNames(const std::string& canonicalName);

}  // namespace lang2manip
