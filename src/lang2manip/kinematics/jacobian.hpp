#pragma once
/// @file The geometric Jacobian of any link frame of a RobotModel, from the link poses of a
/// KinematicsData (computeForwardKinematics() first). Allocation-free for inner loops.

#include <string>

#include "lang2manip/core/types.hpp"
#include "lang2manip/kinematics/forward_kinematics.hpp"
#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

/// Fills `jacobian` (6 x variableCount(), sized by the caller) with the geometric Jacobian of the
/// point `offset` (in link `link`'s frame; zero for the link origin) rigidly attached to link
/// `link`, in the root frame: rows 0-2 the linear velocity of the point, rows 3-5 the angular
/// velocity of the link, per unit velocity of each variable. A mimic joint adds its column, times
/// its multiplier, to its source variable. `data` must hold the forward kinematics of the
/// configuration. Arguments are not checked (inner-loop call); noexcept and allocation-free.
void computeLinkJacobian(const RobotModel& model, const KinematicsData& data, int link,
                         const Vector3& offset, Eigen::Ref<Eigen::MatrixXd> jacobian) noexcept;

/// Convenience: the Jacobian of link `link` at `offset` for configuration `q` (allocates).
/// Throws InputError for an unknown link (listing the links) or a configuration of the wrong
/// size or with non-finite values.
Eigen::MatrixXd computeLinkJacobian(const RobotModel& model, const VectorX& q,
                                    const std::string& link,
                                    const Vector3& offset = Vector3::Zero());

}  // namespace lang2manip
