#pragma once
/// @file SRDF (semantic robot description) reading, and inference of the same facts when a robot
/// comes without one.

#include <filesystem>
#include <string>

#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

/// Reads an SRDF file for a robot given as RobotModelData (names are checked against it).
/// Throws InputError naming the file and line for malformed XML, unknown link/joint/group names
/// and non-finite values.
RobotSemantics readSrdfFile(const std::filesystem::path& path, const RobotModelData& robot);

/// Reads SRDF text (see readSrdfFile()).
RobotSemantics readSrdfString(const std::string& xml, const std::string& sourceName,
                              const RobotModelData& robot);

/// Infers manipulators from the tree when there is no SRDF: each serial chain of movable joints
/// from the root to a branching point or leaf becomes an arm; its last link (or a fixed child
/// named like tcp/tool/grasp/ee) is the tool frame; prismatic or mimic-driven joints after the arm
/// are the gripper (open = upper limit, closed = lower).
RobotSemantics inferSemantics(const RobotModelData& robot);

/// Resolves the groups and end effectors of `semantics` into manipulators (done by the readers).
void resolveManipulators(RobotSemantics& semantics, const RobotModelData& robot);

}  // namespace lang2manip
