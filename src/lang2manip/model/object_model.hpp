#pragma once
/// @file Scene objects from URDF models and back. Object semantics that URDF cannot express are
/// carried by an element lang2manip reads and urdfdom ignores, as a child of <robot>:
/// @code
/// <lang2manip_object kind="pen_holder" movable="true" role="container">
///   <cavity min="-0.04 -0.04 0.004" max="0.04 0.04 0.1"/>
/// </lang2manip_object>
/// @endcode
/// Without it: kind = the URDF's robot name, movable = false, role = support for a wide, flat
/// object (both horizontal extents >= 0.3 m and taller than wide never), none otherwise.

#include <filesystem>
#include <string>

#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// An object named `name` from an obstacle model read from `urdf` (with `scale` applied): the
/// geometry of every link in the root frame, with movable joints at 0 clamped to their limits.
/// Throws InputError naming the file and line for a malformed <lang2manip_object> element.
SceneObject objectFromModel(const RobotModel& model, const std::string& name,
                            const std::filesystem::path& urdf, double scale);

/// A URDF (one link, fixed geometry) describing `object`, with its <lang2manip_object> element.
/// Mesh references are written as absolute paths.
std::string objectUrdfString(const SceneObject& object);

}  // namespace lang2manip
