#pragma once
/// @file Time parameterization of a piecewise-linear path into a trajectory that respects each
/// joint's velocity and acceleration limits, its checks, and its files (JSON in the style of
/// trajectory_msgs/JointTrajectory, and CSV).

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/planning/planning_space.hpp"

namespace lang2manip {

struct TrajectoryPoint {
  VectorX positions;
  VectorX velocities;
  VectorX accelerations;
  /// Seconds from the start of the trajectory.
  double time = 0.0;
};

struct JointTrajectory {
  std::vector<std::string> jointNames;
  std::vector<TrajectoryPoint> points;

  [[nodiscard]] double duration() const { return points.empty() ? 0.0 : points.back().time; }
};

struct TimeParameterizationOptions {
  /// Fractions of the velocity and of the acceleration limits used, in (0, 1].
  double velocityScaling = 1.0;
  double accelerationScaling = 1.0;
  /// Time between samples inside a segment, seconds (waypoints are always samples).
  double sampleInterval = 0.02;
};

/// The smallest velocity or acceleration scaling: below it a few centimetres would take minutes.
inline constexpr double kSmallestScaling = 0.01;

/// Empty when `scaling` is a valid velocity or acceleration scaling (within [kSmallestScaling, 1]);
/// otherwise what is wrong with it ("must be in [0.01, 1] ...").
std::string scalingProblem(double scaling);

/// A trajectory through `path` (points of `space`): each segment is a synchronized trapezoidal
/// velocity profile from rest to rest, the fastest one within every trajectory joint's limits.
/// Throws InputError for an empty path, points of the wrong size, or options out of range.
JointTrajectory timeParameterize(const PlanningSpace& space, const std::vector<VectorX>& path,
                                 const TimeParameterizationOptions& options = {});

/// Empty when every point of `trajectory` is within the space's velocity and acceleration
/// limits times the scalings (with `tolerance` relative slack) and times increase; otherwise
/// says which joint, point and limit is violated.
std::string checkTrajectoryLimits(const PlanningSpace& space, const JointTrajectory& trajectory,
                                  double tolerance = 1e-6, double velocityScaling = 1.0,
                                  double accelerationScaling = 1.0);

/// A trajectory joint as files name it: the robot ("panda"; empty for a name without one), the
/// joint's own name in the robot's URDF ("panda_joint1"; Kautham's base axes "base_x", ...), and
/// the label a file uses: the URDF name, or "robot/joint" when two robots have a joint of that
/// name.
struct TrajectoryJoint {
  std::string robot;
  std::string joint;
  std::string label;
};

/// The joints named `names` ("robot/joint", as PlanningSpace::trajectoryJointNames() gives them).
std::vector<TrajectoryJoint> trajectoryJoints(const std::vector<std::string>& names);

/// {"joint_names": [labels], "points": [{"positions", "velocities", "accelerations",
/// "time_from_start": {"sec", "nanosec"}}]}: a trajectory_msgs/JointTrajectory with the URDF's
/// joint names (see TrajectoryJoint) and nothing else, so that ROS's message loaders take it.
nlohmann::json trajectoryToJson(const JointTrajectory& trajectory);

/// Each joint's robot, parallel to trajectoryToJson()'s "joint_names" (files put it beside the
/// message, as "trajectory_joint_robots").
nlohmann::json trajectoryJointRobots(const JointTrajectory& trajectory);

/// CSV with a header: time, then each joint's label (TrajectoryJoint), <label>_velocity,
/// <label>_acceleration.
std::string trajectoryToCsv(const JointTrajectory& trajectory);

}  // namespace lang2manip
