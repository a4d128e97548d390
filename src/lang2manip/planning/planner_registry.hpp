#pragma once
/// @file Every geometric planner of Debian's OMPL 1.5.2 created by name (planner_catalog.hpp
/// names them), and their parameters by OMPL's names.

#include <memory>
#include <string>
#include <vector>

#include <ompl/base/Planner.h>
#include <ompl/base/SpaceInformation.h>

#include "lang2manip/planning/planner_catalog.hpp"

namespace lang2manip {

/// A new OMPL planner `canonicalName` for `si`.
ompl::base::PlannerPtr createOmplPlanner(const std::string& canonicalName,
                                         const ompl::base::SpaceInformationPtr& si);

/// Names of OMPL's parameters of a planner (its ParamSet), e.g. "range", "goal_bias".
std::vector<std::string> omplParameterNames(const std::string& canonicalName);

}  // namespace lang2manip
