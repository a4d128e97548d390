#include "lang2manip/kinematics/forward_kinematics.hpp"

namespace lang2manip {

KinematicsData::KinematicsData(const RobotModel& model)
    : linkPoses(model.links().size(), Pose::Identity()), jointValues(model.joints().size(), 0.0) {}

void computeForwardKinematics(const RobotModel& model, const VectorX& q,
                              KinematicsData& data) noexcept {
  const auto jointCount = static_cast<int>(model.joints().size());
  data.linkPoses[0].setIdentity();
  for (int joint = 0; joint < jointCount; ++joint) {
    const double value = model.jointValue(joint, q);
    data.jointValues[static_cast<std::size_t>(joint)] = value;
    data.linkPoses[static_cast<std::size_t>(model.childLinkOf(joint))] =
        data.linkPoses[static_cast<std::size_t>(model.parentLinkOf(joint))] *
        model.jointTransform(joint, value);
  }
}

Pose computeLinkPose(const RobotModel& model, const VectorX& q, const std::string& link) {
  const int linkIndex = model.linkIndex(link);
  model.checkConfiguration(q, "configuration");
  KinematicsData data(model);
  computeForwardKinematics(model, q, data);
  return data.linkPoses[static_cast<std::size_t>(linkIndex)];
}

}  // namespace lang2manip
