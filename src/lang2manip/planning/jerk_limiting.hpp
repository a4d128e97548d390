#pragma once
/// @file Jerk limits for a trajectory from rest to rest, by a moving-average (FIR) filter:
/// averaging a trajectory over a window of T seconds keeps every velocity and acceleration bound
/// it met (an average of values within a bound is within it) and makes the acceleration change
/// by at most 2 a_max over T, so |jerk_i| <= 2 a_i / T. With T = max_i 2 a_i / j_i every joint
/// meets its jerk limit j_i (Biagiotti and Melchiorri, "Trajectory Planning for Automatic
/// Machines and Robots", FIR-based trajectory generation). The trajectory lasts T longer, starts
/// and ends at rest on the same positions, and leaves the path it followed by at most
/// a_i T^2 / 24 per joint (measured and returned).

#include "lang2manip/core/types.hpp"
#include "lang2manip/planning/trajectory.hpp"

namespace lang2manip {

/// Longest averaging window accepted (s): jerk limits that need more are refused as a likely
/// unit error (a real arm's is a few milliseconds to a second).
inline constexpr double kMaxJerkWindow = 30.0;

/// Most samples the filter may use (the input's duration plus the window over its first interval).
inline constexpr long long kMaxJerkSamples = 2000000;

/// The outcome of limitJerk().
struct JerkLimitedTrajectory {
  JointTrajectory trajectory;
  /// The averaging window T (s); 0 when no joint has a jerk limit (the input is returned).
  double window = 0.0;
  /// Largest distance (Euclidean over the joints) between a point of the output and the input's
  /// point T/2 earlier, which bounds how far the output leaves the input's path.
  double deviation = 0.0;
};

/// `trajectory` (from rest to rest, sampled finely and evenly: the filter's resolution is its
/// first interval) averaged over T = max_i 2 maxAcceleration_i / maxJerk_i, for the joints
/// whose maxJerk_i > 0, and output every `outputInterval` seconds and at its end.
/// maxAcceleration must bound the input's accelerations (the scaled limits it was timed with).
/// Throws InputError for vectors of the wrong size, negative or non-finite limits, a jerk limit
/// on a joint with no acceleration limit, an input of fewer than two points or not at rest at
/// its ends, a window beyond kMaxJerkWindow or more than kMaxJerkSamples samples.
JerkLimitedTrajectory limitJerk(const JointTrajectory& trajectory, const VectorX& maxAcceleration,
                                const VectorX& maxJerk, double outputInterval);

/// Empty when the acceleration of consecutive points of `trajectory` changes by at most
/// maxJerk_i (1 + tolerance) per second for every joint with maxJerk_i > 0; else which joint
/// and point exceed it.
std::string checkJerkLimits(const JointTrajectory& trajectory, const VectorX& maxJerk, double tolerance = 1e-6);

}  // namespace lang2manip
