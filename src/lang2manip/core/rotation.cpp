#include "lang2manip/core/rotation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "lang2manip/core/error.hpp"

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

std::optional<Quaternion> unitQuaternion(double w, double x, double y, double z) {
  const double largest = std::max({std::abs(w), std::abs(x), std::abs(y), std::abs(z)});
  if (!std::isfinite(largest) || !(largest > 0.0)) return std::nullopt;
  Quaternion q(w / largest, x / largest, y / largest, z / largest);
  q.normalize();
  return q;
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

Pose kauthamPose(const std::vector<double>& values) {
  if (values.size() != 7) {
    throw InputError("a Kautham pose has 7 values (x y z ax ay az angle), got " +
                     std::to_string(values.size()));
  }
  for (const double value : values) {
    if (!std::isfinite(value)) throw InputError("a Kautham pose has a value that is not finite");
  }
  if (values[3] == 0.0 && values[4] == 0.0 && values[5] == 0.0 && values[6] != 0.0) {
    throw InputError("a Kautham pose has the zero rotation axis (0 0 0) with angle " +
                     std::to_string(values[6]) + ": give a rotation axis, or angle 0 for no rotation");
  }
  return makePose(Vector3(values[0], values[1], values[2]),
                  quaternionFromKauthamAxisAngle(Vector3(values[3], values[4], values[5]), values[6]));
}

}  // namespace lang2manip
