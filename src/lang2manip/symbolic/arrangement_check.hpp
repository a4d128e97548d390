#pragma once
/// @file The check of arranged goals: whether objects seen from above stand in a line, a circle,
/// a triangle, a square or spread out, measured on the centres of their bounds with the
/// distance tolerance of the goal check.

#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"

namespace lang2manip {

/// How far a line's direction may be off the heading it was asked along, rad (20 degrees).
inline constexpr double kLineHeadingTolerance = 0.349065850398866;

/// Whether boxes (the members' bounds in the base frame, in the order of goal.members) stand in
/// goal.shape, with `spatial.distanceTolerance` as tol:
/// - line: every centre within tol of the line fitted to them (principal axis), within
///   kLineHeadingTolerance of goal.heading when set; evenly spaced when asked (neighbouring
///   spacings differ by at most tol), each spacing within tol of goal.distance when set;
/// - circle: every centre within tol of the circle about their centroid, radius at least tol,
///   each angular gap between neighbours within half and one and a half of an even share;
/// - triangle, square: every centre within tol of its own corner of the regular polygon fitted to
///   them (about their centroid, the mean radius, the rotation that fits best);
/// - spread_out: no two boxes within spatial.nearDistance of each other.
/// - together: one group, each box within spatial.nearDistance of another and every member
///   reached from any other through such neighbours.
/// - pyramid: 3, 6, 10, ... members in rows by the height of their bottoms, the lowest k in a
///   line (within tol, their bottoms within tol of each other), each member of a higher row
///   resting on two of the row below (bridgedSupport() with tol).
/// The explanation states the measured numbers.
GoalCheck checkArrangedBoxes(const Goal& goal, const std::vector<AlignedBox3>& boxes, const SpatialOptions& spatial);

/// checkArrangedBoxes() on the members' bounds in `scene` (base frame of options.robot), after
/// each member is standing (not held), on goal.target when set (a pyramid's base row), and in its
/// goal.region when set.
GoalCheck checkArranged(const Scene& scene, const Goal& goal, const GoalCheckOptions& options);

}  // namespace lang2manip
