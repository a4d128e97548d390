#pragma once
/// @file What `lang2manip show` reports about a problem, as JSON and as text (the text is
/// rendered from the same JSON, so both always say the same).

#include <nlohmann/json.hpp>
#include <string>

#include "lang2manip/cli/problem_loading.hpp"

namespace lang2manip {

/// Robots (DOFs, joint names, limits, base pose, configuration, manipulators), controls,
/// objects (pose, size, kind, role) and queries (start and goal joint values, and whether both
/// are collision-free with the exact FCL checker, naming the colliding pairs).
nlohmann::json problemReport(const LoadedProblem& problem);

/// Human-readable rendering of problemReport().
std::string problemReportText(const nlohmann::json& report);

}  // namespace lang2manip
