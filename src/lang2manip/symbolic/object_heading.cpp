#include "lang2manip/symbolic/object_heading.hpp"

#include <cmath>
#include <cstdio>
#include <variant>

namespace lang2manip {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kHorizontalSine = 0.1736;  // sin(10 deg)
constexpr double kParallelCosine = 0.9998;  // cos(~1 deg)
constexpr double kLengthTolerance = 1e-3;
constexpr double kLongSideRatio = 1.15;

bool sameLength(double a, double b) { return std::abs(a - b) <= kLengthTolerance; }

/// True when box `a` (rotation `ra`) and box `b` (rotation `rb`) have the same edges along the
/// same lines.
bool sameBox(const Box& a, const Matrix3& ra, const Box& b, const Matrix3& rb) {
  for (int i = 0; i < 3; ++i) {
    bool matched = false;
    for (int j = 0; j < 3 && !matched; ++j) {
      matched = std::abs(ra.col(i).dot(rb.col(j))) >= kParallelCosine && sameLength(a.size[i], b.size[j]);
    }
    if (!matched) return false;
  }
  return true;
}

/// True when `a` placed at `pa` and `b` placed at `pb` occupy the same space (primitives only).
bool sameSpace(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb) {
  if ((pa.translation() - pb.translation()).norm() > kLengthTolerance) return false;
  if (const auto* sa = std::get_if<Sphere>(&a.geometry)) {
    const auto* sb = std::get_if<Sphere>(&b.geometry);
    return sb != nullptr && sameLength(sa->radius, sb->radius);
  }
  if (const auto* ca = std::get_if<Cylinder>(&a.geometry)) {
    const auto* cb = std::get_if<Cylinder>(&b.geometry);
    return cb != nullptr && sameLength(ca->radius, cb->radius) && sameLength(ca->length, cb->length) &&
           std::abs(pa.linear().col(2).dot(pb.linear().col(2))) >= kParallelCosine;
  }
  if (const auto* ba = std::get_if<Box>(&a.geometry)) {
    const auto* bb = std::get_if<Box>(&b.geometry);
    return bb != nullptr && sameBox(*ba, pa.linear(), *bb, pb.linear());
  }
  return false;  // meshes are not compared
}

/// True when turning every collision shape of `object` by `yaw` about the vertical through
/// `pivot` lands each on a shape of the object.
bool symmetricUnder(const SceneObject& object, double yaw, const Vector3& pivot) {
  Pose turn = Pose::Identity();
  turn.linear() = verticalTurn(yaw);
  turn.translation() = pivot - turn.linear() * pivot;
  for (const Shape& shape : object.collisions) {
    const Pose turned = turn * object.pose * shape.origin;
    bool found = false;
    for (const Shape& other : object.collisions) {
      if (sameSpace(shape, turned, other, object.pose * other.origin)) {
        found = true;
        break;
      }
    }
    if (!found) return false;
  }
  return true;
}

}  // namespace

std::optional<double> longSideYaw(const SceneObject& object, const Matrix3& rotation) {
  const Vector3 size = object.dimensions();
  int first = -1, second = -1;
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(rotation.col(axis).z()) > kHorizontalSine) continue;
    (first < 0 ? first : second) = axis;
  }
  if (first < 0 || second < 0) return std::nullopt;
  const int longer = size[first] >= size[second] ? first : second;
  const int shorter = longer == first ? second : first;
  if (size[longer] < kLongSideRatio * size[shorter]) return std::nullopt;
  const Vector3 along = rotation.col(longer);
  double yaw = std::atan2(along.y(), along.x());
  if (yaw < 0.0) yaw += kPi;
  if (yaw >= kPi) yaw -= kPi;
  return yaw;
}

double turnSymmetry(const SceneObject& object) {
  if (object.collisions.empty()) return 2.0 * kPi;
  const Vector3 pivot = object.worldBounds().center();
  if (symmetricUnder(object, 0.1, pivot) && symmetricUnder(object, 1.0, pivot)) return 0.0;
  if (symmetricUnder(object, kPi / 2.0, pivot)) return kPi / 2.0;
  if (symmetricUnder(object, kPi, pivot)) return kPi;
  return 2.0 * kPi;
}

double reducedAngle(double angle, double period) {
  if (period <= 0.0) return 0.0;
  double reduced = std::fmod(angle, period);
  if (reduced > period / 2.0) reduced -= period;
  if (reduced <= -period / 2.0) reduced += period;
  return reduced;
}

TurnBetween turnBetween(const Matrix3& from, const Matrix3& to) {
  const Matrix3 relative = to * from.transpose();
  const Vector3 x = relative.col(0);
  TurnBetween turn;
  // The yaw of the relative rotation's x axis when it stays near horizontal, else of its y axis.
  const Vector3 reference = std::abs(x.z()) < 0.7 ? x : Vector3(relative.col(1));
  turn.yaw = std::atan2(reference.y(), reference.x()) - (std::abs(x.z()) < 0.7 ? 0.0 : kPi / 2.0);
  turn.yaw = reducedAngle(turn.yaw, 2.0 * kPi);
  const Matrix3 rest = verticalTurn(-turn.yaw) * relative;
  turn.tilt = Eigen::AngleAxisd(rest).angle();
  return turn;
}

Matrix3 verticalTurn(double yaw) { return Eigen::AngleAxisd(yaw, Vector3::UnitZ()).toRotationMatrix(); }

std::string degreesText(double radians) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f deg", radians * 180.0 / kPi);
  return text;
}

}  // namespace lang2manip
