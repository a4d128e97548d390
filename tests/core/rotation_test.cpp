#include "lang2manip/core/rotation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace lang2manip {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Rotation, RpyFollowsUrdfConvention) {
  // R = Rz(yaw) Ry(pitch) Rx(roll): check against the explicit product.
  const Quaternion q = quaternionFromRpy(0.3, -0.2, 1.1);
  const Matrix3 expected = (Eigen::AngleAxisd(1.1, Vector3::UnitZ()) *
                            Eigen::AngleAxisd(-0.2, Vector3::UnitY()) *
                            Eigen::AngleAxisd(0.3, Vector3::UnitX()))
                               .toRotationMatrix();
  EXPECT_TRUE(q.toRotationMatrix().isApprox(expected, 1e-12));
  EXPECT_TRUE(rpyFromQuaternion(q).isApprox(Vector3(0.3, -0.2, 1.1), 1e-12));
}

TEST(Rotation, RpyRoundTripsAtGimbalLock) {
  const Quaternion q = quaternionFromRpy(0.4, kPi / 2, -0.3);
  const Vector3 rpy = rpyFromQuaternion(q);
  EXPECT_TRUE(quaternionFromRpy(rpy[0], rpy[1], rpy[2]).isApprox(q, 1e-9) ||
              quaternionFromRpy(rpy[0], rpy[1], rpy[2]).coeffs().isApprox(-q.coeffs(), 1e-9));
}

TEST(Rotation, KauthamAxisAngleFollowsKauthamAndTreatsZeroAxisAsIdentity) {
  EXPECT_TRUE(quaternionFromKauthamAxisAngle(Vector3::Zero(), 1.0).isApprox(Quaternion::Identity()));
  const Quaternion unit = quaternionFromKauthamAxisAngle(Vector3(0, 0, -1), kPi / 2);
  EXPECT_TRUE((unit * Vector3::UnitX()).isApprox(Vector3(0, -1, 0), 1e-12));
  // Non-unit axis (0,0,2), TH = pi/2: q = (cos(pi/4), 0, 0, 2 sin(pi/4)) normalized
  // = (1, 0, 0, 2)/sqrt(5): a rotation of 2*atan(2) about z, not pi/2.
  const Quaternion scaled = quaternionFromKauthamAxisAngle(Vector3(0, 0, 2), kPi / 2);
  EXPECT_NEAR(Eigen::AngleAxisd(scaled).angle(), 2.0 * std::atan(2.0), 1e-12);
}

TEST(Rotation, AxisAngleRoundTrip) {
  const Quaternion q = quaternionFromKauthamAxisAngle(Vector3(1, 2, 3).normalized(), 2.5);
  Vector3 axis;
  double angle = 0.0;
  axisAngleFromQuaternion(q, axis, angle);
  EXPECT_NEAR(angle, 2.5, 1e-12);
  EXPECT_TRUE(axis.isApprox(Vector3(1, 2, 3).normalized(), 1e-12));
  axisAngleFromQuaternion(Quaternion::Identity(), axis, angle);
  EXPECT_EQ(angle, 0.0);
}

TEST(Rotation, KauthamUnitCubeMap) {
  EXPECT_TRUE(quaternionFromKauthamUnitCube(0, 0, 0).isApprox(Quaternion::Identity()));
  // With X1 = X2 = 0, X3 is a yaw of 2*pi*X3.
  const Quaternion yaw = quaternionFromKauthamUnitCube(0, 0, 0.125);
  EXPECT_TRUE(yaw.isApprox(Quaternion(Eigen::AngleAxisd(kPi / 4, Vector3::UnitZ())), 1e-12));
  // The formula of kautham-format.md, X1 = 0.5, X2 = 0.25, X3 = 0.5.
  const Quaternion q = quaternionFromKauthamUnitCube(0.5, 0.25, 0.5);
  const double s = std::sqrt(0.5);
  EXPECT_NEAR(q.x(), s * std::sin(2 * kPi * 0.25), 1e-12);
  EXPECT_NEAR(q.y(), s * std::cos(2 * kPi * 0.25), 1e-12);
  EXPECT_NEAR(q.z(), s * std::sin(kPi * 0.5), 1e-12);
  EXPECT_NEAR(q.w(), s * std::cos(kPi * 0.5), 1e-12);
}

TEST(Rotation, UnitQuaternionsOfHugeOrTinyComponentsAreTheirRotationAndZeroIsNone) {
  const std::optional<Quaternion> huge = unitQuaternion(0.0, 0.0, 0.0, 1e300);
  ASSERT_TRUE(huge.has_value());
  EXPECT_NEAR(std::abs(huge->z()), 1.0, 1e-12) << "a half turn about z, not no rotation";
  const std::optional<Quaternion> tiny = unitQuaternion(1e-300, 1e-300, 0.0, 0.0);
  ASSERT_TRUE(tiny.has_value());
  EXPECT_NEAR(tiny->w(), std::sqrt(0.5), 1e-12);
  EXPECT_FALSE(unitQuaternion(0.0, 0.0, 0.0, 0.0).has_value());
  EXPECT_FALSE(unitQuaternion(1.0, std::numeric_limits<double>::infinity(), 0.0, 0.0).has_value());
  EXPECT_FALSE(unitQuaternion(std::nan(""), 0.0, 0.0, 0.0).has_value());
}

}  // namespace
}  // namespace lang2manip
