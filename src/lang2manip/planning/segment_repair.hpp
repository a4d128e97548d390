#pragma once
/// @file Internal: mending a path whose straight segments the planner checked more coarsely than
/// the final verification. Only the segments that collide at the fine resolution are planned
/// again, each between its own two (valid) ends, by RRTConnect checking motions at that
/// resolution; the rest of the path is kept.

#include <memory>
#include <optional>
#include <vector>

#include "lang2manip/core/stop_condition.hpp"
#include "lang2manip/planning/ompl_bridge.hpp"

namespace lang2manip {

/// A path with its colliding segments replaced, and how many were.
struct RepairedPath {
  std::vector<VectorX> points;
  int repairedSegments = 0;
};

/// Replaces every segment of `path` that collides at `resolution` by a path found between its ends
/// with motions checked at `resolution` and states inside `bounds`. Each segment may use half of the time `stop` leaves,
/// at least 50 ms and at most 0.5 s. nullopt when a point is in collision or a segment could not be mended
/// before `stop`; `counters` count the checks made.
std::optional<RepairedPath> repairCollidingSegments(const PlanningSpace& space, const std::vector<VectorX>& path,
                                                    const StateBounds& bounds, double resolution,
                                                    const StopCondition& stop,
                                                    const std::shared_ptr<CheckCounters>& counters);

}  // namespace lang2manip
