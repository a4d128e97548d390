#pragma once
/// @file What grasp planning needs to know about a parallel gripper, derived from the robot model
/// alone (no robot is named in code): tool frame, approach and closing axes, opening range, where
/// the fingers are, and how to turn an opening width into gripper joint values.

#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

/// A two-finger parallel gripper, expressed in its tool frame G (the TCP).
///
/// Conventions (documented for every consumer of the grounding API):
/// - the approach axis is the tool frame's +z: a grasp moves the TCP along +z into the object;
/// - the closing axis is the direction the gripper joint moves a finger, expressed in G;
/// - widths are distances between the finger pads; 0 = closed, maxOpening = fully open.
struct GripperGeometry {
  std::string manipulator;
  /// Link of the tool frame (TCP).
  std::string toolFrame;
  /// Unit vectors in G.
  Vector3 approachAxis = Vector3::UnitZ();
  Vector3 closingAxis = Vector3::UnitY();
  /// Largest distance between the finger pads (m).
  double maxOpening = 0.0;
  /// Links that move with the gripper joints (the fingers); the only links a grasped object may
  /// touch.
  std::vector<std::string> fingerLinks;
  /// Bounds of the open fingers' collision geometry in G.
  AlignedBox3 fingerBounds;
  /// Gripper joints (non-mimic) and their values when open and closed.
  std::vector<std::string> gripperJoints;
  std::vector<double> openValues;
  std::vector<double> closedValues;

  /// How far the fingertips reach beyond the TCP along the approach axis.
  [[nodiscard]] double fingertipOffset() const { return fingerBounds.max().z(); }
  /// How far the fingers reach back from the TCP along the approach axis (positive).
  [[nodiscard]] double fingerReachBehind() const { return -fingerBounds.min().z(); }
};

/// The gripper of manipulator `manipulator` of `model` (the first manipulator when empty).
/// Throws InputError for an unknown manipulator (listing them) and for a manipulator without a
/// gripper joint or whose gripper does not open (open == closed).
GripperGeometry describeGripper(const RobotModel& model, const std::string& manipulator = {});

/// The manipulator named `name` (the first when empty); throws InputError listing the valid names.
const Manipulator& findManipulator(const RobotModel& model, const std::string& name);

/// `q` with the gripper joints set for a finger gap of `width` (clamped to [0, maxOpening]).
VectorX withGripperOpening(const RobotModel& model, const GripperGeometry& gripper, VectorX q,
                           double width);

}  // namespace lang2manip
