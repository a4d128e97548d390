#pragma once
/// @file The check of arranged goals: whether objects seen from above stand in a line, a circle,
/// a triangle, a square or spread out, measured on the centres of their bounds with the
/// distance tolerance of the goal check.

#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"

namespace lang2manip {

/// How far a line's direction may be off the heading it was asked along, rad (20 degrees).
inline constexpr double kLineHeadingTolerance = 0.349065850398866;

/// The corners of a triangle (3) or a square (4); 0 for the other shapes.
std::size_t polygonCorners(ArrangementShape shape);

/// Why `members` objects make no `shape` (a triangle or square takes a multiple of its corners, a
/// circle at least three, a pyramid 3, 6 or 10, the others at least two), or empty when they do.
std::string memberCountProblem(ArrangementShape shape, std::size_t members);

/// The `corners * perSide` spots of a regular polygon's outline about `centre` (x, y) with
/// circumradius `radius`, its first corner at yaw `rotation`: each corner, then perSide - 1 more
/// evenly along the side that follows it, counter-clockwise. perSide = 1 gives its corners alone;
/// corners = n, perSide = 1 gives n spots evenly around a circle.
std::vector<Eigen::Vector2d> regularOutline(const Eigen::Vector2d& centre, double radius, double rotation, std::size_t corners,
                                            std::size_t perSide);

/// Whether boxes (the members' bounds in the base frame, in the order of goal.members) stand in
/// goal.shape, with `spatial.distanceTolerance` as tol:
/// - line: every centre within tol of the line fitted to them (principal axis), within
///   kLineHeadingTolerance of goal.heading when set; evenly spaced when asked (neighbouring
///   spacings differ by at most tol), each spacing within tol of goal.distance when set;
/// - circle: every centre within tol of the circle about their centroid, radius at least tol,
///   each angular gap between neighbours within half and one and a half of an even share;
/// - triangle, square: 3 or 4 members at the corners of a regular polygon, or a multiple of that
///   on its outline (each corner taken and as many more evenly along each side): every centre
///   within tol of its own spot of the polygon fitted to them (about their centroid, the mean
///   radius and best-fitting rotation of the members farthest from it), spots at least 2 tol apart;
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
