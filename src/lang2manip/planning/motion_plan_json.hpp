#pragma once
/// @file Motion plans as JSON, as `lang2manip solve` and the server's getPath report them.

#include <nlohmann/json.hpp>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/planning/motion_planner.hpp"

namespace lang2manip {

/// {"planning_seconds", "simplify_seconds", ..., "vertices", "edges", "length_before_simplification",
/// "length_after_simplification", "rejected_paths"}.
nlohmann::json motionPlanStatisticsToJson(const MotionPlanStatistics& statistics);

/// The points of a path as an array of arrays of numbers.
nlohmann::json pathToJson(const std::vector<VectorX>& path);

}  // namespace lang2manip
