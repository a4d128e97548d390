#pragma once
/// @file Timing an action's motions into the trajectory a controller runs, and re-checking the
/// path that trajectory follows.
///
/// Time-optimal timing joins consecutive arm motions (a transit and the Cartesian approach after
/// it, ...) into runs; a run ends where the gripper acts, where a push starts or ends, and where
/// the world's attachments change, so the arm is at rest exactly there. Each run's corners are
/// blended with circular arcs within ExecutionSettings::blendDeviation (BlendedPath); every arc
/// is re-checked with the exact checker at the verification resolution against the worlds and
/// allowed contacts of the segments it joins, and on Cartesian moves the tool must stay within
/// cartesianDeviation of the move's straight line; an arc that fails is made smaller, down to a
/// sharp corner (a stop), which is the path the planners verified. The run is then parameterized
/// time-optimally (Kunz & Stilman) within the scaled joint limits, which are re-checked on the
/// trajectory's samples.

#include <cstddef>
#include <vector>

#include "lang2manip/execution/arm_motion.hpp"
#include "lang2manip/execution/execution_types.hpp"

namespace lang2manip {

/// An action's trajectory and how it was made.
struct ActionTiming {
  /// Time from the start of the action; strictly increasing, at rest at both ends.
  JointTrajectory trajectory;
  /// See ActionExecution::segmentEndTimes.
  std::vector<double> segmentEndTimes;
  /// The runs (time-optimal timing only).
  std::vector<TimedRun> runs;
  TrajectoryQuality quality;
  /// Robot states checked on blends.
  long collisionChecks = 0;
};

/// Times `segments` (an action's motions, in order, each starting where the previous ended) with
/// arm.settings().timing, velocityScaling and accelerationScaling. Throws InputError only for
/// configurations outside the robot's space (a grounding error, not a user's).
ActionTiming timeActionMotions(const ArmContext& arm, const std::vector<MotionSegment>& segments);

/// The waypoints of a run: its segments' waypoints, repeats dropped (closer than
/// kRepeatedWaypoint, Euclidean), with the segment whose motion reaches each one (the first
/// waypoint: the run's first segment) and, per segment of the run, the index of its last waypoint.
struct RunPath {
  static constexpr double kRepeatedWaypoint = 1e-7;

  std::vector<VectorX> waypoints;
  std::vector<std::size_t> segmentOf;
  std::vector<std::size_t> lastWaypointOf;
};

/// The path of `run` over `segments`.
RunPath runPath(const std::vector<MotionSegment>& segments, const TimedRun& run);

/// Re-checks the path `action`'s trajectory follows at `resolution`: each run's blended path (not
/// its waypoints) against the world and allowed contacts of the segment each point belongs to (a
/// blend: of both segments it joins), and carried objects' sweeps. Actions timed rest to rest
/// (no runs) are checked segment by segment (checkSegment).
SegmentCheck checkTimedAction(const ArmContext& arm, const ActionExecution& action, double resolution);

}  // namespace lang2manip
