#include "lang2manip/grounding/object_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include "lang2manip/core/error.hpp"
#include "lang2manip/symbolic/resting_height.hpp"
#include "lang2manip/symbolic/support_surface.hpp"

namespace lang2manip {
namespace {

double boxHalfExtent(const Matrix3& R, const Vector3& half, const Vector3& u) {
  return std::abs(u.dot(R.col(0))) * half.x() + std::abs(u.dot(R.col(1))) * half.y() +
         std::abs(u.dot(R.col(2))) * half.z();
}

double primitiveHalfExtent(const Shape& shape, const Matrix3& R_WS, const Vector3& u, bool& known) {
  known = true;
  if (const auto* box = std::get_if<Box>(&shape.geometry)) return boxHalfExtent(R_WS, box->size / 2.0, u);
  if (const auto* sphere = std::get_if<Sphere>(&shape.geometry)) return sphere->radius;
  if (const auto* cylinder = std::get_if<Cylinder>(&shape.geometry)) {
    const double along = std::abs(u.dot(R_WS.col(2)));
    return cylinder->radius * std::sqrt(std::max(0.0, 1.0 - along * along)) + cylinder->length / 2.0 * along;
  }
  known = false;
  return 0.0;
}

void addUnique(std::vector<Quaternion>& list, const Quaternion& q) {
  for (const Quaternion& existing : list) {
    if (std::abs(existing.dot(q)) > 1.0 - 1e-9) return;
  }
  list.push_back(q.normalized());
}

}  // namespace

AlignedBox3 transformedBox(const AlignedBox3& box, const Pose& X) {
  AlignedBox3 result;
  if (box.isEmpty()) return result;
  for (int corner = 0; corner < 8; ++corner) {
    result.extend(X * box.corner(static_cast<AlignedBox3::CornerType>(corner)));
  }
  return result;
}

double halfExtentAlong(const SceneObject& object, const Pose& X_WO, const Vector3& direction) {
  if (object.collisions.size() == 1) {
    const Shape& shape = object.collisions.front();
    bool known = false;
    const double half = primitiveHalfExtent(shape, X_WO.linear() * shape.origin.linear(), direction, known);
    if (known) return half;
  }
  return boxHalfExtent(X_WO.linear(), object.localBounds().sizes() / 2.0, direction);
}

Vector3 objectCentre(const SceneObject& object, const Pose& X_WO) { return X_WO * object.localBounds().center(); }

AlignedBox3 boundsAtPose(const SceneObject& object, const Pose& X_WO) {
  SceneObject moved = object;
  moved.pose = X_WO;
  return moved.worldBounds();
}

std::vector<Quaternion> restingOrientations(const Quaternion& current) {
  const Matrix3 R = current.toRotationMatrix();
  const Vector3 up = Vector3::UnitZ();
  const Vector3 axes[] = {R.col(2), R.col(0), -R.col(0), R.col(1), -R.col(1), -R.col(2)};
  std::vector<Quaternion> orientations;
  for (const Vector3& axis : axes) {
    const Quaternion tilt = Quaternion::FromTwoVectors(axis, up);
    for (int k = 0; k < 4; ++k) {
      const Quaternion yaw(Eigen::AngleAxisd(k * M_PI / 2.0, up));
      addUnique(orientations, yaw * tilt * current);
    }
  }
  return orientations;
}

const SceneObject* supportUnder(const Scene& scene, const Vector3& point, double tolerance,
                                const std::vector<std::string>& exclude) {
  const SceneObject* best = nullptr;
  double bestTop = -std::numeric_limits<double>::infinity();
  for (const SceneObject& candidate : scene.objects()) {
    if (std::find(exclude.begin(), exclude.end(), candidate.name) != exclude.end()) continue;
    if (scene.findAttachment(candidate.name) != nullptr) continue;
    const std::optional<double> top = restingHeight(candidate, point, tolerance);
    if (!top || *top <= bestTop) continue;
    best = &candidate;
    bestTop = *top;
  }
  return best;
}

double surfaceUnder(const SceneObject& support, const Vector3& bottom, double tolerance) {
  return restingHeight(support, bottom, tolerance).value_or(support.worldBounds().max().z());
}

const SceneObject* supportUnderBody(const Scene& scene, const AlignedBox3& bounds, double tolerance,
                                    const std::vector<std::string>& exclude) {
  const Vector3 bottom(bounds.center().x(), bounds.center().y(), bounds.min().z());
  if (const SceneObject* under = supportUnder(scene, bottom, tolerance, exclude)) return under;
  std::vector<AlignedBox3> below;
  std::vector<const SceneObject*> owners;
  for (const SceneObject& candidate : scene.objects()) {
    if (std::find(exclude.begin(), exclude.end(), candidate.name) != exclude.end() || scene.findAttachment(candidate.name) != nullptr) continue;
    below.push_back(candidate.worldBounds());
    owners.push_back(&candidate);
  }
  const std::optional<std::size_t> bridged = bridgedSupport(bounds, below, tolerance);
  return bridged ? owners[*bridged] : nullptr;
}

const SceneObject* currentSupport(const Scene& scene, const SceneObject& object, double tolerance) {
  return supportUnderBody(scene, object.worldBounds(), tolerance, {object.name});
}

Pose currentObjectPose(const Scene& scene, const std::string& name) {
  const SceneObject& object = scene.object(name);
  const Attachment* attachment = scene.findAttachment(name);
  if (attachment == nullptr) return object.pose;
  const SceneRobot& robot = scene.robot(attachment->robot);
  const std::vector<Pose> poses = robot.model->linkPoses(robot.configuration);
  return robot.basePose * poses[static_cast<std::size_t>(robot.model->linkIndex(attachment->link))] *
         attachment->linkToObject;
}

void requireSettingLength(double value, const char* settings, const char* field) {
  if (!std::isfinite(value) || value < 0.0) {
    throw InputError(std::string(settings) + " settings: " + field + " must be a finite length >= 0 (got " + std::to_string(value) + ")");
  }
}

void requireSettingCount(int value, const char* settings, const char* field) {
  if (value < 1) throw InputError(std::string(settings) + " settings: " + field + " must be >= 1 (got " + std::to_string(value) + ")");
}

}  // namespace lang2manip
