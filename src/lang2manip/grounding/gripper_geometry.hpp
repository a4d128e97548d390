#pragma once
/// @file What grasp planning needs to know about a robot's gripper, derived from the robot model
/// alone by forward kinematics of the finger geometry (no robot is named in code): the grasp
/// frame, approach and closing axes, the pad gap over the gripper's travel, the pads' depth and
/// the fingers' length, and how to turn a pad gap into gripper joint values.
///
/// Works for parallel grippers with sliding fingers, with rotating or linkage fingers driven
/// through <mimic> joints (Robotiq 2F, OnRobot RG2/RG6, Kautham's models), for grippers with
/// several actuated joints moved together, and for hands with three or more fingers. A tool
/// without gripper joints (suction cup, bare flange) is described too: it can move and push,
/// and hasGripper() says it cannot pick.

#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

/// A gripper, expressed in its grasp frame H.
///
/// Conventions (documented for every consumer of the grounding API):
/// - H is the manipulator's tool frame T when T's origin already lies between the finger pads
///   (a TCP); otherwise H is placed between the pads (midway across, at the middle of their
///   depth), so that an SRDF or URDF whose tool frame is the palm or the flange still grasps
///   with the pads. graspFrame is X_TH; IK targets the tool frame at X_WH * X_TH^-1.
/// - the approach axis is H's +z: a grasp moves H along +z into the object;
/// - the closing axis is the direction the fingers close along, expressed in H (H's +-y unless
///   T's own axes are kept);
/// - openings are gaps between the finger pads, measured on the pads' geometry by forward
///   kinematics at each gripper position (not joint values).
struct GripperGeometry {
  std::string manipulator;
  /// Link of the tool frame T.
  std::string toolFrame;
  /// Pose of the grasp frame H in the tool frame (X_TH).
  Pose graspFrame = Pose::Identity();
  /// Unit vectors in H.
  Vector3 approachAxis = Vector3::UnitZ();
  Vector3 closingAxis = Vector3::UnitY();
  /// Fingers found on the gripper (2 for a parallel gripper; 0 without a gripper).
  int fingerCount = 0;
  /// One jaw closing against a fixed jaw on the hand (the fixed jaw's link is the last pad link).
  bool fixedJaw = false;
  /// Pads (and fixed jaw) whose contact face was found on their collision surface; the others
  /// count whole, which places the gap less surely.
  int padsWithContactFace = 0;
  /// Gap between the pads when fully open and when closed (m).
  double maxOpening = 0.0;
  double minOpening = 0.0;
  /// Extent of the pads along the approach axis (m).
  double padDepth = 0.0;
  /// From the roots of the fingers to their tips along the approach axis (m).
  double fingerLength = 0.0;
  /// Links that move with the gripper joints (the fingers); the only links a grasped object may
  /// touch. Empty without a gripper.
  std::vector<std::string> fingerLinks;
  /// The fingertip links (the farthest-reaching link of each finger).
  std::vector<std::string> padLinks;
  /// Bounds in H of the fingers' collision geometry over the whole travel; for a tool without
  /// gripper, of the geometry rigidly attached below the last arm joint.
  AlignedBox3 fingerBounds;
  /// Bounds in H of each collision shape below the last arm joint (palm, fingers, camera, tool)
  /// with the gripper closed: what meets an object the hand pushes.
  std::vector<AlignedBox3> closedHandBounds;
  /// Bounds in H of the wrist that carries the last arm joint when that joint turns the tool
  /// about its approach axis, each shape swept about it (the wrist turns about it relative to H):
  /// what else meets an object pushed by a short flange. Empty after a last joint of another axis.
  std::vector<AlignedBox3> wristBounds;
  /// Gripper joints (the manipulator's, mimics excluded) and their values when open and closed.
  /// Open is the end of the travel where the pads are farther apart, whatever the limits say.
  std::vector<std::string> gripperJoints;
  std::vector<double> openValues;
  std::vector<double> closedValues;
  /// Pad gap (m) at evenly spaced fractions of the travel, from closed (0) to open (1).
  std::vector<double> openingCurve;
  /// At the same fractions: the fingers' bounds in H, and how far the middle of the pads has
  /// moved along the approach axis from where it is when open (linkage fingers move along it
  /// as they close; sliding fingers do not).
  std::vector<AlignedBox3> fingerBoundsCurve;
  std::vector<double> padCentreCurve;
  /// At the same fractions: the fingers as boxes in H, each finger link cut into slabs across
  /// the approach axis (a finger that narrows toward its tip is not the box of its base).
  std::vector<std::vector<AlignedBox3>> fingerSlabsCurve;

  /// Bounds in H of the fingers swept while the pad gap goes from `wide` down to `narrow`.
  [[nodiscard]] AlignedBox3 fingerBoundsBetween(double narrow, double wide) const;
  /// The finger slabs swept while the pad gap goes from `wide` down to `narrow` (each slab the
  /// union of its boxes over that part of the travel).
  [[nodiscard]] std::vector<AlignedBox3> fingerSlabsBetween(double narrow, double wide) const;
  /// How far the middle of the pads has moved along the approach axis at pad gap `width` from
  /// where it is when open.
  [[nodiscard]] double padCentreAt(double width) const;

  /// False for a tool without gripper joints: it moves and pushes but cannot pick.
  [[nodiscard]] bool hasGripper() const noexcept { return !gripperJoints.empty(); }
  /// How far the fingertips reach beyond H along the approach axis.
  [[nodiscard]] double fingertipOffset() const { return fingerBounds.max().z(); }
  /// How far the fingers reach back from H along the approach axis (positive).
  [[nodiscard]] double fingerReachBehind() const { return -fingerBounds.min().z(); }
};

/// The gripper of manipulator `manipulator` of `model` (the first manipulator when empty).
/// Throws InputError for an unknown manipulator (listing them), and for gripper joints whose
/// pads do not open (the gap stays within 1 mm over the whole travel; the message gives the gap
/// and the joints' values). A manipulator without gripper joints gets a description with
/// hasGripper() false.
GripperGeometry describeGripper(const RobotModel& model, const std::string& manipulator = {});

/// "<action>: robot R has no gripper ..." (naming the manipulator, its tool frame and how to
/// declare a gripper), or empty when `gripper` has one; `action` names what needed it ("pick X").
std::string noGripperReason(const RobotModel& model, const GripperGeometry& gripper, const std::string& action);

/// The manipulator named `name` (the first when empty); throws InputError listing the valid names.
const Manipulator& findManipulator(const RobotModel& model, const std::string& name);

/// `q` with the gripper joints at `fraction` of their travel (0 closed, 1 open; clamped).
VectorX withGripperFraction(const RobotModel& model, const GripperGeometry& gripper, VectorX q, double fraction);

/// The fraction of the travel the gripper of configuration `q` is at (0 without a gripper).
double gripperFraction(const RobotModel& model, const GripperGeometry& gripper, const VectorX& q);

/// The pad gap at `fraction` of the travel (interpolated on openingCurve).
double openingAtFraction(const GripperGeometry& gripper, double fraction);

/// The smallest fraction of the travel whose pad gap is at least `width` (1 when wider than
/// maxOpening, 0 when narrower than minOpening).
double fractionForOpening(const GripperGeometry& gripper, double width);

/// `q` with the gripper joints set for a pad gap of `width` (clamped to the gripper's range).
VectorX withGripperOpening(const RobotModel& model, const GripperGeometry& gripper, VectorX q, double width);

/// The pad gap of configuration `q` (0 without a gripper).
double gripperOpening(const RobotModel& model, const GripperGeometry& gripper, const VectorX& q);

}  // namespace lang2manip
