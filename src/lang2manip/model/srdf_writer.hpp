#pragma once
/// @file SRDF text from a robot's semantics: each manipulator as an arm group (a chain from its
/// base link to its tool frame), a gripper group with its joints, "open" and "closed" group
/// states and an end effector; the named states. Read back by srdf_reader.hpp to the same
/// manipulators. Disabled collision pairs are not written (lang2manip computes its own).

#include <string>

#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

/// The SRDF of `model` with `semantics` (usually model.semantics(), possibly corrected: e.g. the
/// gripper's open and closed values measured by describeGripper()).
std::string srdfString(const RobotModel& model, const RobotSemantics& semantics);

}  // namespace lang2manip
