#pragma once
/// @file Our own conversion of a RobotModel chain to a KDL::Chain (no kdl_parser): one fixed
/// segment for the frames before the first movable joint, then one segment per movable joint
/// whose tip frame folds in every fixed transform up to the next movable joint.

#include <string>

#include <kdl/chain.hpp>
#include <kdl/frames.hpp>

#include "lang2manip/kinematics/kinematic_chain.hpp"
#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

KDL::Frame toKdlFrame(const Pose& pose);
Pose fromKdlFrame(const KDL::Frame& frame);

/// The KDL chain of `chain`; KDL's joint i is chain variable i. Throws InputError when the chain
/// has mimic joints or joints sharing a variable (KDL's chain solvers treat every joint as
/// independent).
KDL::Chain makeKdlChain(const RobotModel& model, const KinematicChain& chain);

/// The KDL chain from link `baseLink` to link `tipLink`; throws InputError as KinematicChain
/// and makeKdlChain(model, chain) do.
KDL::Chain makeKdlChain(const RobotModel& model, const std::string& baseLink,
                        const std::string& tipLink);

}  // namespace lang2manip
