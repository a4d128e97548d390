#pragma once
/// @file Time-optimal parameterization of a joint-space path whose corners are blended with
/// circular arcs, under per-joint velocity and acceleration limits: Kunz and Stilman,
/// "Time-optimal trajectory generation for path following with bounded acceleration and
/// velocity", RSS 2012 (the algorithm of MoveIt's TimeOptimalTrajectoryGeneration).

#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/planning/blended_path.hpp"
#include "lang2manip/planning/planning_space.hpp"
#include "lang2manip/planning/trajectory.hpp"

namespace lang2manip {

/// Settings of timeOptimalParameterize (the names of MoveIt's TOTG where it has them).
struct TimeOptimalOptions {
  /// Largest distance (rad, Euclidean in joint space) between a corner of the path and the arc
  /// that replaces it; >= 0. With 0 the trajectory stops at every corner.
  double maxDeviation = 0.01;
  /// Fractions of the velocity and of the acceleration limits used, in (0, 1].
  double velocityScaling = 1.0;
  double accelerationScaling = 1.0;
  /// Integration time step (s), > 0; steps are shorter on tight arcs.
  double timeStep = 1e-3;
  /// Time between output points (s), > 0; the last point of the trajectory is always output.
  double sampleInterval = 0.02;
};

/// The fastest trajectory along the path through `path` with its corners blended
/// (BlendedPath(path, options.maxDeviation): build the same path to re-check it for
/// collisions), from rest to rest, within |velocity_i| <= maxVelocity_i * velocityScaling and
/// |acceleration_i| <= maxAcceleration_i * accelerationScaling for every joint i. The path stops
/// at reversals (and at every corner when maxDeviation is 0). Points every sampleInterval and at
/// the end, times strictly increasing, starting and ending exactly on the first and last
/// waypoints; velocity = x'(s) ds/dt and acceleration = x'(s) d2s/dt2 + x''(s) (ds/dt)^2 at each.
/// A path of one point (or of repeated points) gives one point at rest at time 0. Joint names
/// are "joint_0", "joint_1", ...
/// Throws InputError (naming the waypoint or joint) for an empty path, points of different
/// sizes, values that are not finite, limits of the wrong size or not positive and finite,
/// options out of range, or a trajectory needing more than a million integration steps (about
/// a thousand seconds on arcs at the default timeStep) or ten million output points (use a
/// larger timeStep or sampleInterval).
/// Thread-safe (no shared state).
JointTrajectory timeOptimalParameterize(const std::vector<VectorX>& path, const VectorX& maxVelocity,
                                        const VectorX& maxAcceleration,
                                        const TimeOptimalOptions& options = {});

/// The same for a path of points of `space`, with the limits of its trajectory joints
/// (jointVelocityLimits(), jointAccelerationLimits(), through trajectoryJacobian()); blending is
/// done in the space's coordinates, positions are trajectoryPositions() and the joint names
/// trajectoryJointNames(), as timeParameterize() gives them.
/// Throws InputError as above, and for points outside the space's bounds.
JointTrajectory timeOptimalParameterize(const PlanningSpace& space, const std::vector<VectorX>& path,
                                        const TimeOptimalOptions& options = {});

/// The same along a path already blended (for example with a deviation per corner); the
/// options' maxDeviation is not used. The path's points must be points of `space` (the caller
/// built it from such points: arcs stay within the convex hull of their corner's neighbours).
/// Throws InputError as above, and when the path's dimension is not the space's.
JointTrajectory timeOptimalParameterize(const PlanningSpace& space, const BlendedPath& path,
                                        const TimeOptimalOptions& options = {});

}  // namespace lang2manip
