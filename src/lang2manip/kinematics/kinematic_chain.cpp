#include "lang2manip/kinematics/kinematic_chain.hpp"

#include <algorithm>
#include <cmath>

#include "lang2manip/core/error.hpp"

namespace lang2manip {
namespace {

/// X_JJ' of a joint's motion for value `value` (the joint frame after moving, in its rest frame).
Pose jointMotion(const ChainJoint& joint, double value) noexcept {
  Pose motion = Pose::Identity();
  if (joint.type == JointType::kRevolute || joint.type == JointType::kContinuous) {
    motion.linear() = Eigen::AngleAxisd(value, joint.axis).toRotationMatrix();
  } else if (joint.type == JointType::kPrismatic) {
    motion.translation() = value * joint.axis;
  }
  return motion;
}

bool isMovable(JointType type) {
  return type == JointType::kRevolute || type == JointType::kContinuous ||
         type == JointType::kPrismatic;
}

}  // namespace

KinematicChain::KinematicChain(const RobotModel& model, const std::string& baseLink,
                               const std::string& tipLink)
    : baseLink_(baseLink), tipLink_(tipLink) {
  const int base = model.linkIndex(baseLink);
  const int tip = model.linkIndex(tipLink);
  std::vector<int> path;
  int link = tip;
  while (link != base && model.parentJoint(link) >= 0) {
    path.push_back(model.parentJoint(link));
    link = model.parentLinkOf(model.parentJoint(link));
  }
  if (link != base || base == tip) {
    throw InputError("no kinematic chain from link \"" + baseLink + "\" to link \"" + tipLink +
                     "\" in robot \"" + model.name() + "\": the base must be an ancestor of the tip");
  }
  std::reverse(path.begin(), path.end());
  for (int joint : path) addJoint(model, joint);
  if (variables_.empty()) {
    throw InputError("the chain from link \"" + baseLink + "\" to link \"" + tipLink +
                     "\" in robot \"" + model.name() + "\" has no movable joint");
  }
}

void KinematicChain::addJoint(const RobotModel& model, int joint) {
  const Joint& source = model.joints()[static_cast<std::size_t>(joint)];
  ChainJoint entry;
  entry.joint = joint;
  entry.type = source.type;
  entry.origin = source.origin;
  entry.axis = source.axis;
  reach_ += source.origin.translation().norm();
  if (isMovable(source.type)) {
    int robotVariable = model.variableOfJoint(joint);
    if (robotVariable < 0 && model.mimicSource(joint) >= 0) {
      robotVariable = model.mimicSource(joint);
      entry.multiplier = source.mimic->multiplier;
      entry.offset = source.mimic->offset;
      coupled_ = true;
    }
    if (robotVariable >= 0) {
      auto found = std::find(variables_.begin(), variables_.end(), robotVariable);
      if (found != variables_.end()) coupled_ = true;
      entry.variable = static_cast<int>(found - variables_.begin());
      if (found == variables_.end()) variables_.push_back(robotVariable);
    }
    if (source.type == JointType::kPrismatic) {
      reach_ += std::max(std::abs(source.limits.lower), std::abs(source.limits.upper)) *
                std::abs(entry.multiplier) + std::abs(entry.offset);
    }
  }
  joints_.push_back(entry);
}

Pose KinematicChain::pose(const VectorX& qc) const noexcept {
  Pose X_BT = Pose::Identity();
  for (const ChainJoint& joint : joints_) {
    X_BT = X_BT * joint.origin;
    if (joint.variable >= 0) {
      X_BT = X_BT * jointMotion(joint, joint.multiplier * qc[joint.variable] + joint.offset);
    }
  }
  return X_BT;
}

void KinematicChain::poseAndJacobian(const VectorX& qc, Pose& X_BT,
                                     Jacobian6& jacobian) const noexcept {
  // Columns are accumulated as (-axis x p_joint; axis) and corrected with axis x p_tip at the end,
  // once the tip position is known (linear in the columns, so mimic sums stay exact).
  jacobian.setZero();
  X_BT.setIdentity();
  for (const ChainJoint& joint : joints_) {
    X_BT = X_BT * joint.origin;
    if (joint.variable < 0) continue;
    const Vector3 axis = X_BT.linear() * joint.axis;
    auto column = jacobian.col(joint.variable);
    if (joint.type == JointType::kPrismatic) {
      column.head<3>() += joint.multiplier * axis;
    } else if (joint.type != JointType::kFixed) {
      column.head<3>() -= joint.multiplier * axis.cross(X_BT.translation());
      column.tail<3>() += joint.multiplier * axis;
    }
    X_BT = X_BT * jointMotion(joint, joint.multiplier * qc[joint.variable] + joint.offset);
  }
  const Vector3 tip = X_BT.translation();
  for (Eigen::Index c = 0; c < jacobian.cols(); ++c) {
    jacobian.col(c).head<3>() += Vector3(jacobian.col(c).tail<3>()).cross(tip);
  }
}

void KinematicChain::gather(const VectorX& q, VectorX& qc) const noexcept {
  for (std::size_t i = 0; i < variables_.size(); ++i) {
    qc[static_cast<Eigen::Index>(i)] = q[variables_[i]];
  }
}

void KinematicChain::scatter(const VectorX& qc, VectorX& q) const noexcept {
  for (std::size_t i = 0; i < variables_.size(); ++i) {
    q[variables_[i]] = qc[static_cast<Eigen::Index>(i)];
  }
}

}  // namespace lang2manip
