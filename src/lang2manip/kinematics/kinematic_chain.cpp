#include "lang2manip/kinematics/kinematic_chain.hpp"

#include <algorithm>
#include <cmath>

#include "lang2manip/core/error.hpp"

namespace lang2manip {
namespace {

/// R <- R * (rotation by `angle` about the joint's axis), written out for the coordinate axes.
void rotateAbout(const ChainJoint& joint, double angle, Matrix3& R) noexcept {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  const auto turn = [&](Eigen::Index a, Eigen::Index b) {
    const Vector3 first = R.col(a);
    R.col(a) = c * first + s * R.col(b);
    R.col(b) = c * R.col(b) - s * first;
  };
  switch (joint.coordinateAxis) {
    case 0: turn(1, 2); return;
    case 1: turn(2, 0); return;
    case 2: turn(0, 1); return;
    default: R = R * Eigen::AngleAxisd(angle, joint.axis).toRotationMatrix();
  }
}

/// Moves frame (R, p) by the joint's motion for joint value `value`.
void applyMotion(const ChainJoint& joint, double value, Matrix3& R, Vector3& p) noexcept {
  if (joint.type == JointType::kRevolute || joint.type == JointType::kContinuous) {
    rotateAbout(joint, value, R);
  } else if (joint.type == JointType::kPrismatic) {
    p += value * (R * joint.axis);
  }
}

int coordinateAxisOf(const Vector3& axis) {
  for (int i = 0; i < 3; ++i) {
    if (axis == Vector3::Unit(i)) return i;
  }
  return -1;
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
  entry.coordinateAxis = coordinateAxisOf(source.axis);
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
  Matrix3 R = Matrix3::Identity();
  Vector3 p = Vector3::Zero();
  for (const ChainJoint& joint : joints_) {
    p += R * joint.origin.translation();
    R = R * joint.origin.linear();
    if (joint.variable >= 0) {
      applyMotion(joint, joint.multiplier * qc[joint.variable] + joint.offset, R, p);
    }
  }
  Pose X_BT = Pose::Identity();
  X_BT.linear() = R;
  X_BT.translation() = p;
  return X_BT;
}

void KinematicChain::poseAndJacobian(const VectorX& qc, Pose& X_BT,
                                     Jacobian6& jacobian) const noexcept {
  // Columns are accumulated as (-axis x p_joint; axis) and corrected with axis x p_tip at the end,
  // once the tip position is known (linear in the columns, so mimic sums stay exact).
  jacobian.setZero();
  Matrix3 R = Matrix3::Identity();
  Vector3 p = Vector3::Zero();
  for (const ChainJoint& joint : joints_) {
    p += R * joint.origin.translation();
    R = R * joint.origin.linear();
    if (joint.variable < 0) continue;
    const Vector3 axis = joint.coordinateAxis >= 0 ? Vector3(R.col(joint.coordinateAxis))
                                                   : Vector3(R * joint.axis);
    auto column = jacobian.col(joint.variable);
    if (joint.type == JointType::kPrismatic) {
      column.head<3>() += joint.multiplier * axis;
    } else if (joint.type != JointType::kFixed) {
      column.head<3>() -= joint.multiplier * axis.cross(p);
      column.tail<3>() += joint.multiplier * axis;
    }
    applyMotion(joint, joint.multiplier * qc[joint.variable] + joint.offset, R, p);
  }
  for (Eigen::Index c = 0; c < jacobian.cols(); ++c) {
    jacobian.col(c).head<3>() += Vector3(jacobian.col(c).tail<3>()).cross(p);
  }
  X_BT.setIdentity();
  X_BT.linear() = R;
  X_BT.translation() = p;
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
