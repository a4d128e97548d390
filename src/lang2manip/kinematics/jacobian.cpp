#include "lang2manip/kinematics/jacobian.hpp"

namespace lang2manip {

void computeLinkJacobian(const RobotModel& model, const KinematicsData& data, int link,
                         const Vector3& offset, Eigen::Ref<Eigen::MatrixXd> jacobian) noexcept {
  jacobian.setZero();
  const Vector3 point = data.linkPoses[static_cast<std::size_t>(link)] * offset;
  for (int joint = model.parentJoint(link); joint >= 0;
       joint = model.parentJoint(model.parentLinkOf(joint))) {
    int variable = model.variableOfJoint(joint);
    double multiplier = 1.0;
    if (variable < 0 && model.mimicSource(joint) >= 0) {
      variable = model.mimicSource(joint);
      multiplier = model.joints()[static_cast<std::size_t>(joint)].mimic->multiplier;
    }
    const Joint& description = model.joints()[static_cast<std::size_t>(joint)];
    const bool revolute = description.type == JointType::kRevolute ||
                          description.type == JointType::kContinuous;
    if (variable < 0 || (!revolute && description.type != JointType::kPrismatic)) continue;
    // The child frame turns (or slides) about the joint axis through the child origin.
    const Pose& X_RC = data.linkPoses[static_cast<std::size_t>(model.childLinkOf(joint))];
    const Vector3 axis = X_RC.linear() * description.axis;
    auto column = jacobian.col(variable);
    if (description.type == JointType::kPrismatic) {
      column.head<3>() += multiplier * axis;
    } else {
      column.head<3>() += multiplier * axis.cross(point - X_RC.translation());
      column.tail<3>() += multiplier * axis;
    }
  }
}

Eigen::MatrixXd computeLinkJacobian(const RobotModel& model, const VectorX& q,
                                    const std::string& link, const Vector3& offset) {
  const int linkIndex = model.linkIndex(link);
  model.checkConfiguration(q, "configuration");
  KinematicsData data(model);
  computeForwardKinematics(model, q, data);
  Eigen::MatrixXd jacobian(6, model.variableCount());
  computeLinkJacobian(model, data, linkIndex, offset, jacobian);
  return jacobian;
}

}  // namespace lang2manip
