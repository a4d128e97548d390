#pragma once
/// @file How far an arm reaches over a horizontal top, measured with the arm's own inverse
/// kinematics: along rays from its shoulder, the nearest and the farthest horizontal distance at
/// which the tool frame gets to a point with the hand pointing straight down (as an object held
/// by a top grasp is placed), at two heights
/// above the top (where a small grasped object's centre is when it stands on the top, and where
/// the approach above it passes). The answer depends only on the model's joints and limits, the
/// arm and the top's height in the base frame, so it is measured once per process for each of
/// them and shared (a few tens of milliseconds per arm).
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"

namespace lang2manip {

struct SceneRobot;

/// One arm's measured reach over one top height, in the robot's base frame.
struct ArmReach {
  std::string manipulator;
  /// The vertical axis distances are measured about: the arm's shoulder (its first joint whose
  /// axis is not vertical), moved onto the axis of a first joint that turns the arm about the
  /// vertical when there is one.
  Vector3 shoulder = Vector3::Zero();
  /// Ray directions (radians about +z from the base's +x, increasing) and, per ray, the
  /// horizontal distances from the shoulder between which every point of the ray is reached
  /// (inner > outer when the ray reaches nothing).
  std::vector<double> azimuths;
  std::vector<double> inner;
  std::vector<double> outer;
  /// Footprints (x, y, base frame) of the robot's own fixed links that stand on the top (a
  /// torso, a base on the table), widened by kBodyClearance: the hand does not come down there.
  std::vector<AlignedBox3> body;
  /// True when (x, y) of `point` (base frame) is outside `body` and lies between the inner and
  /// the outer distance of its direction, interpolated between the two nearest rays, each
  /// reaching something.
  [[nodiscard]] bool reaches(const Vector3& point) const;
};

/// Horizontal clearance kept inside the measured boundary (m): grasps at a fixed yaw and object
/// sizes need a little more than the bare tool frame does.
inline constexpr double kReachBoundaryMargin = 0.02;
/// How far the hand keeps from the robot's own body standing on a top (m).
inline constexpr double kBodyClearance = 0.05;

/// The reach of the arms of `robot` (only `manipulator` when not empty) over a top whose surface
/// is at height `topZ` of the base frame `base` (a world pose). Arms without joints or tool frame
/// are left out. Deterministic. Throws InputError for an unknown manipulator.
std::vector<ArmReach> measuredArmReaches(const SceneRobot& robot, const Pose& base, double topZ,
                                         const std::string& manipulator = {});

}  // namespace lang2manip
