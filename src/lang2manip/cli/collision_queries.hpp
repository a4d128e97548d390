#pragma once
/// @file Collision checks of a loaded problem's query states with the exact (FCL) checker, as
/// JSON and text for `lang2manip check` and `lang2manip show`.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/collision/collision_checker.hpp"

namespace lang2manip {

/// Start and goal reports of one query.
struct QueryCollisions {
  CollisionReport start;
  CollisionReport goal;
};

/// Checks every query's start and goal (all robots at their query states and base poses) with
/// `checker`, which must have been built for `loaded.problem.scene`.
std::vector<QueryCollisions> checkQueries(const LoadedProblem& loaded, const CollisionChecker& checker);

/// The joints of every robot of `scene` that `states` puts outside their limits (each prefixed
/// with the robot's name when the scene has several robots); empty when all are within them.
std::vector<std::string> limitViolations(const Scene& scene, const RobotStates& states);

/// {"valid", "contacts": [{"first", "second", "penetration_depth"}], "minimum_distance",
/// "closest": [first, second]} (distance and closest only when known).
nlohmann::json collisionReportJson(const CollisionReport& report);

/// "collision-free" (with the clearance when known) or "in collision: a - b (0.0123 m), ...".
std::string collisionSummary(const CollisionReport& report);

}  // namespace lang2manip
