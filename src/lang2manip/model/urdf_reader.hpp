#pragma once
/// @file Reads URDF (through urdfdom) into a RobotModel, with meshes, materials and the SRDF.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

struct UrdfReadOptions {
  /// Directories searched for "package://NAME/..." references: DIR/NAME/... for each DIR.
  /// ROS_PACKAGE_PATH entries are appended at read time.
  std::vector<std::filesystem::path> packagePaths;
  /// Multiplies geometry, joint-origin translations and prismatic limits (Kautham's scale).
  double scale = 1.0;
  /// SRDF file to read; when empty, "<urdf without extension>.srdf" is used if it exists, and
  /// otherwise the semantics are inferred from the tree.
  std::filesystem::path srdf;
  /// MoveIt joint_limits.yaml to apply (joint_limits_reader.hpp: accelerations, jerks, velocity,
  /// position and effort limits over the URDF's); when empty, "<urdf without extension>
  /// .joint_limits.yaml" beside the file read is applied if it exists ("robot.urdf" and
  /// "robot.urdf.xacro" -> "robot.joint_limits.yaml", "robot.xacro" -> the same), and otherwise the
  /// URDF's limits stand alone (no acceleration limits: planning's default applies).
  std::filesystem::path jointLimits;
  /// <mimic> tags are ignored, so every movable joint is its own variable (Kautham couples joints
  /// through its control files instead; the Kautham reader uses this when a control drives a
  /// joint the URDF marks as a mimic). The semantics are resolved with the mimics first, so a
  /// gripper keeps closing as its mimics say: their joints join the manipulator's gripper joints.
  bool ignoreMimic = false;
  /// Load mesh files (off: geometry references are kept but meshes are not read).
  bool loadMeshes = true;
  /// The <xacro:arg> values of a .xacro robot (see xacro.hpp).
  std::map<std::string, std::string> xacroArguments;
  /// Approach axes (tool frame; normalized when applied) by manipulator name, "" for every
  /// manipulator; over the SRDF's and the inferred ones. An unknown name is an InputError.
  std::map<std::string, Vector3> approachAxes;
};

/// Reads a URDF file, or a xacro file (name ending in .xacro) expanded first with
/// options.xacroArguments, and applies its joint limits file (UrdfReadOptions::jointLimits).
/// Throws InputError naming the file (and the line where known) for a missing or unreadable
/// file, malformed XML or URDF, a xacro error, a cycle or several roots, non-finite numbers, a
/// mesh reference that resolves nowhere / cannot be loaded, or a bad joint limits file. Logs a
/// warning for each joint variable left without a velocity limit (kDefaultJointVelocityLimit).
RobotModelPtr readUrdfFile(const std::filesystem::path& path, const UrdfReadOptions& options = {});

/// Reads URDF text; `sourceName` names it in messages and `baseDirectory` resolves relative mesh
/// paths. A joint limits file is applied only when options.jointLimits names one.
RobotModelPtr readUrdfString(const std::string& xml, const std::string& sourceName,
                             const std::filesystem::path& baseDirectory,
                             const UrdfReadOptions& options = {});

/// Resolves a mesh reference from a URDF in `urdfDirectory`: "package://p/x" through the
/// package paths, "file://x", absolute paths, and paths relative to the URDF. Throws InputError
/// listing the places tried when the file exists in none.
std::filesystem::path resolveMeshReference(const std::string& reference,
                                           const std::filesystem::path& urdfDirectory,
                                           const std::vector<std::filesystem::path>& packagePaths,
                                           const SourceLocation& where);

}  // namespace lang2manip
