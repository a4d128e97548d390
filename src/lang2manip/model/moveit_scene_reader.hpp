#pragma once
/// @file MoveIt PlanningScene YAML and MotionPlanRequest YAML (the MotionBenchMaker problems).

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// A start-state joint value that was outside the model's limits and was clamped to them.
struct ClampedJoint {
  std::string joint;
  /// The value in the request.
  double given = 0.0;
  /// The value used (the nearest limit).
  double used = 0.0;
};

/// A planning scene and its request, mapped onto a robot model by joint names.
struct MoveItProblem {
  /// The robot (named after the scene's robot_model_name, or the model's name) at the start
  /// state, and one fixed object per collision object (several primitives become one object).
  Scene scene;
  std::string robot;
  /// Start configuration (the model's middle configuration for joints the request omits).
  VectorX start;
  /// Goal configuration: the start with the goal joint constraints applied.
  VectorX goal;
  /// Names of the joints the goal constrains.
  std::vector<std::string> goalJoints;
  std::string group;
  std::string plannerId;
  double allowedPlanningTime = 0.0;
  /// Pairs of names the scene's allowed_collision_matrix allows to touch.
  std::vector<std::pair<std::string, std::string>> allowedCollisions;
  /// Gripper joints of the start state that were clamped to their limits (see
  /// readMoveItProblem()).
  std::vector<ClampedJoint> clampedJoints;
  std::filesystem::path sceneFile;
  std::filesystem::path requestFile;
};

/// Reads a scene and a request for `robot`.
///
/// What is read:
/// - Collision objects (`world.collision_objects`, operation ADD or absent, frame empty or
///   "world"): box [x, y, z], sphere [radius] and cylinder [height, radius] primitives (type as a
///   name or as the SolidPrimitive number). Poses are `position` + `orientation` as lists
///   ([x, y, z] and [x, y, z, w]) or maps with x, y, z(, w) keys; quaternions are normalized.
///   Each object becomes one fixed SceneObject named by its id, kind "box"/"sphere"/"cylinder"
///   (or "obstacle" when its primitives differ). Its frame is the object's top-level `pose`
///   when given (MoveIt 2: primitive poses are then relative to it); otherwise, with one
///   primitive, the primitive's pose (the shape sits at the origin), and with several, the
///   identity (shapes at their world poses). Every pose is thus kept exactly as written.
/// - The robot's base pose: the multi-DOF joint state's transform of the joint named
///   "virtual_joint" (or of the only multi-DOF joint) of the request's start_state, else of the
///   scene's robot_state, else the identity.
/// - Start configuration: the request's start_state joint positions, mapped by joint name.
///   Joints the state omits keep the model's middle configuration; values for mimic joints are
///   ignored (they follow their source joint). The scene's robot_state joint values are not used.
///   Gripper joints (the model's Manipulator::gripperJoints) outside their limits are clamped to
///   them and listed in clampedJoints (MotionBenchMaker gives the Panda fingers 0.065 for a
///   0.04 limit); other joints outside their limits are kept as given: validity is for the
///   caller to judge.
/// - Goal: the start with goal_constraints[0].joint_constraints applied by joint name.
/// - allowed_collision_matrix: entry_names + a square, symmetric entry_values of booleans; the
///   default entries are ignored.
///
/// @throws InputError naming the file, the 1-based line (where yaml-cpp knows it) and the YAML
/// path (e.g. `world.collision_objects[3].primitives[0].dimensions`) for: a missing or malformed
/// file, a missing required key, a value of the wrong type, a wrong number of values, a
/// non-finite number, a non-positive dimension, a zero quaternion, an unknown primitive type,
/// unsupported input (cone primitives, meshes, planes, operations other than ADD, other frames,
/// several goal constraints, position/orientation/visibility constraints), a primitive_poses
/// count that differs from the primitives count, a duplicate object id, a non-square or
/// asymmetric collision matrix, or joint names the robot does not have as variables (the
/// message lists the valid ones); also when `robot` is null.
///
/// Thread-safe: it only reads `robot` and the two files.
MoveItProblem readMoveItProblem(const std::filesystem::path& sceneFile,
                                const std::filesystem::path& requestFile, RobotModelPtr robot);

/// The request file that goes with a MotionBenchMaker scene file (.../sceneNNNN.yaml ->
/// .../requestNNNN.yaml). Throws InputError when the file name is not sceneNNNN.yaml (one or
/// more digits).
std::filesystem::path requestFileForScene(const std::filesystem::path& sceneFile);

}  // namespace lang2manip
