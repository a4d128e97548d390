#pragma once
/// @file SRDF (semantic robot description) reading, and inference of the same facts when a robot
/// comes without one.

#include <filesystem>
#include <string>
#include <string_view>

#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

/// Reads an SRDF file for a robot given as RobotModelData (names are checked against it), with
/// our extension <lang2manip_approach group="ARM" xyz="X Y Z"/> setting an arm's approach axis
/// in its tool frame (other SRDF readers ignore it). Throws InputError naming the file and line
/// for malformed XML, unknown link/joint/group names, non-finite values and an approach axis
/// without direction or naming a group that is no arm.
RobotSemantics readSrdfFile(const std::filesystem::path& path, const RobotModelData& robot);

/// Reads SRDF text (see readSrdfFile()).
RobotSemantics readSrdfString(const std::string& xml, const std::string& sourceName,
                              const RobotModelData& robot);

/// Most arms inferSemantics() finds before asking for an SRDF (real robots have one to four).
inline constexpr int kMaxInferredArms = 64;

/// Infers manipulators from the tree when there is no SRDF: the fingers are the short chains of
/// movable joints that share a rigid body with another finger (mimics included), and sliding
/// joints at the end of the tree; each chain of the other movable joints from the root to their
/// end is an arm (a prismatic torso or linear axis included); its last link (or a fixed child
/// named like tcp/tool/grasp/ee, or the link the fingers hang from) is the tool frame; the
/// fingers' joints below it are its gripper (open = upper limit, closed = lower; describeGripper
/// measures which end really opens); self-collision envelopes as addSelfCollisionEnvelopes().
/// Throws InputError when the tree ends in more than kMaxInferredArms arms (a robot that branched
/// needs its arms named).
RobotSemantics inferSemantics(const RobotModelData& robot);

/// The links that are a self-collision envelope of their parent, as vendors add them (Franka's
/// `*_sc`, capsules about the arm's links): attached by a fixed joint, with collision geometry and
/// no visual, whose collision bounds are larger than the parent's and cover at least half of them.
std::vector<std::string> selfCollisionEnvelopes(const RobotModelData& robot);

/// Marks the envelopes of `robot` as a MoveIt configuration of such a robot does: their default
/// collisions off (never checked against the world nor the other links), and on between two
/// envelopes whose links are three or more joints apart (the real robot's self-collision model).
void addSelfCollisionEnvelopes(const RobotModelData& robot, RobotSemantics& semantics);

/// An approach axis written "X Y Z" (any length but zero), normalized. Throws InputError at
/// `where` for anything else.
Vector3 approachAxisFromText(std::string_view text, const SourceLocation& where);

/// Resolves the groups and end effectors of `semantics` into manipulators (done by the readers).
void resolveManipulators(RobotSemantics& semantics, const RobotModelData& robot);

}  // namespace lang2manip
