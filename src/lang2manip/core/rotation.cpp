#include "lang2manip/core/rotation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lang2manip {

Quaternion quaternionFromRpy(double roll, double pitch, double yaw) {
  return Quaternion(Eigen::AngleAxisd(yaw, Vector3::UnitZ()) *
                    Eigen::AngleAxisd(pitch, Vector3::UnitY()) *
                    Eigen::AngleAxisd(roll, Vector3::UnitX()));
}

Vector3 rpyFromQuaternion(const Quaternion& q) {
  const Matrix3 r = q.normalized().toRotationMatrix();
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  if (std::abs(r(2, 0)) > 1.0 - 1e-12) {
    // Gimbal lock: roll and yaw are not separable; put everything in yaw.
    return {0.0, pitch, std::atan2(-r(0, 1), r(1, 1))};
  }
  return {std::atan2(r(2, 1), r(2, 2)), pitch, std::atan2(r(1, 0), r(0, 0))};
}

Quaternion quaternionFromKauthamAxisAngle(const Vector3& axis, double angle) {
  if (axis.isZero(0.0)) return Quaternion::Identity();
  const Vector3 v = axis * std::sin(angle / 2.0);
  return Quaternion(std::cos(angle / 2.0), v.x(), v.y(), v.z()).normalized();
}

void axisAngleFromQuaternion(const Quaternion& q, Vector3& axis, double& angle) {
  Eigen::AngleAxisd angleAxis(q.normalized());
  angle = angleAxis.angle();
  axis = angle == 0.0 ? Vector3::UnitZ() : angleAxis.axis();
  if (angle > std::numbers::pi) {
    angle = 2.0 * std::numbers::pi - angle;
    axis = -axis;
  }
}

Pose makePose(const Vector3& translation, const Quaternion& rotation) {
  Pose pose = Pose::Identity();
  pose.linear() = rotation.normalized().toRotationMatrix();
  pose.translation() = translation;
  return pose;
}

Quaternion quaternionFromKauthamUnitCube(double x1, double x2, double x3) {
  constexpr double kPi = std::numbers::pi;
  const double a = std::sqrt(std::max(0.0, x1));
  const double b = std::sqrt(std::max(0.0, 1.0 - x1));
  return Quaternion(b * std::cos(kPi * x3), a * std::sin(2.0 * kPi * x2),
                    a * std::cos(2.0 * kPi * x2), b * std::sin(kPi * x3))
      .normalized();
}

}  // namespace lang2manip
