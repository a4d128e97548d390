#pragma once
/// @file The trajectory files of a run, in the shapes the users' tools read:
/// - trajectory.json (format_version 2): the robot named once; per action an "arm"
///   trajectory_msgs/JointTrajectory with the URDF's own joint names and a "gripper" one, every
///   time_from_start from the action's start and strictly increasing;
/// - trajectory.csv: one header of URDF joint names (positions, then velocities and
///   accelerations), times from the start of the run, strictly increasing;
/// - robot_trajectory.json: one moveit_msgs/RobotTrajectory of the whole run (the arm's joints,
///   as MoveIt executes a group's trajectory), for MoveIt users to replay;
/// - gripper_trajectory.json: the gripper's joints over the whole run as one
///   trajectory_msgs/JointTrajectory, and gripper_events.json: when each object is attached to and
///   detached from the hand (for a robot with a gripper).
/// Each message file holds the message and nothing else, so ROS's message loaders take it.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lang2manip/execution/arm_motion.hpp"
#include "lang2manip/execution/execution_types.hpp"

namespace lang2manip {

/// The URDF joint names of the robot that executes a run, split into its arm and its gripper.
struct TrajectoryJoints {
  std::string robot;
  /// The frame trajectories are planned in (the robot's root link): MoveIt's header.frame_id.
  std::string frame;
  std::vector<std::string> arm;
  std::vector<std::string> gripper;
  /// The link objects are attached to (the manipulator's tool frame).
  std::string toolFrame;
};

/// The arm's joints (root to tip) and the gripper's independent joints of `arm`.
TrajectoryJoints trajectoryJoints(const ArmContext& arm);

/// trajectory.json (see the file comment).
nlohmann::json runTrajectoryJson(const ExecutionRecord& execution, const TrajectoryJoints& joints);
/// trajectory.csv: `action,time,<arm and gripper joints>,<joint>_velocity...,<joint>_acceleration...`.
std::string runTrajectoryCsv(const ExecutionRecord& execution, const TrajectoryJoints& joints);
/// robot_trajectory.json: {"joint_trajectory": {"header": {"frame_id"}, "joint_names", "points"},
/// "multi_dof_joint_trajectory": {...empty}}, the arm's joints.
nlohmann::json moveItRobotTrajectory(const ExecutionRecord& execution, const TrajectoryJoints& joints);
/// gripper_trajectory.json: {"header", "joint_names", "points"} of the gripper's joints.
nlohmann::json gripperJointTrajectory(const ExecutionRecord& execution, const TrajectoryJoints& joints);
/// gripper_events.json: {"events": [{"time", "event": "attach"|"detach", "object", "link"}]}, times
/// from the start of the run.
nlohmann::json gripperEvents(const ExecutionRecord& execution, const TrajectoryJoints& joints);

}  // namespace lang2manip
