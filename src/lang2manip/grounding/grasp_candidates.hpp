#pragma once
/// @file The geometric half of the heuristic grasp planner: tool poses for top, front and side
/// grasps computed from the object's shape and the gripper's geometry, before any IK.

#include <string>
#include <vector>

#include "lang2manip/grounding/grasp_planner.hpp"
#include "lang2manip/grounding/gripper_geometry.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// A grasp pose from geometry alone.
struct GeometricGrasp {
  GraspDirection direction = GraspDirection::kTop;
  std::string label;
  /// X_WG and the approach direction (world, unit).
  Pose pose = Pose::Identity();
  Vector3 approach = Vector3::UnitZ();
  /// Object width between the fingers.
  double width = 0.0;
  /// Offset of the grasp point from the object's centre along the fingers' width axis.
  double offset = 0.0;
};

struct GraspGeneration {
  std::vector<GeometricGrasp> grasps;
  std::vector<GraspRejection> rejections;
};

/// What generateGrasps() needs about the world.
struct GraspGeometryInput {
  const SceneObject* object = nullptr;
  /// X_WO (the object's current pose) and X_WB (the robot base: front = +x, left = +y).
  Pose objectPose = Pose::Identity();
  Pose robotBase = Pose::Identity();
  /// Height of the surface the object rests on (the fingers keep clear of it).
  double supportTop = 0.0;
};

/// Grasp poses of the object for `direction` (auto: top, front and side), see the file comment:
/// - top: approach straight down, closing directions every 360/topYawSteps degrees starting
///   along the object's x axis;
/// - front / side: horizontal approaches along the robot's +x / +-y and along the object's
///   horizontal face normals within sectorHalfAngle of them, closing horizontally or
///   vertically;
/// - for each, the grasp point at the centre and, for long objects, towards both ends; the TCP
///   goes as deep as the fingers allow, raised until the fingers clear the support.
/// Candidates wider than the gripper's opening, or that cannot hold the object without touching
/// the support, are returned as rejections with a reason.
GraspGeneration generateGrasps(const GraspGeometryInput& input, const GripperGeometry& gripper,
                               GraspDirection direction, const GraspSettings& settings);

/// The grasps of the widened search (none of generateGrasps()'s): top approaches at the closing
/// directions halfway between those of generateGrasps(), and at every one of the 2 * topYawSteps
/// closing directions tilted by each of settings.widenedTopTilts both ways about the closing
/// axis (the hand leans along the object) and about the axis between the fingers (it leans
/// across). Empty unless `direction` is auto or top.
GraspGeneration generateWidenedGrasps(const GraspGeometryInput& input, const GripperGeometry& gripper,
                                      GraspDirection direction, const GraspSettings& settings);

}  // namespace lang2manip
