#include "lang2manip/grounding/object_collision.hpp"

#include <fcl/narrowphase/collision.h>

#include "lang2manip/grounding/object_geometry.hpp"

namespace lang2manip {

ObjectCollisionWorld::ObjectCollisionWorld(const Scene& scene, const std::string& object)
    : object_(scene.object(object)) {
  FclGeometryBuilder builder;
  shapes_ = builder.build(object_.collisions);
  for (const SceneObject& other : scene.objects()) {
    if (other.name == object || !other.collisionEnabled || scene.findAttachment(other.name) != nullptr) continue;
    obstacles_.push_back({other.name, builder.build(other.collisions), other.pose, other.worldBounds()});
  }
}

bool ObjectCollisionWorld::touches(const Obstacle& obstacle, const Pose& X_WO) const {
  const fcl::CollisionRequestd request;
  for (const FclShape& mine : shapes_) {
    const Pose X_WA = X_WO * mine.origin;
    for (const FclShape& theirs : obstacle.shapes) {
      const Pose X_WB = obstacle.pose * theirs.origin;
      fcl::CollisionResultd result;
      fcl::collide(mine.geometry.get(), X_WA, theirs.geometry.get(), X_WB, request, result);
      if (result.isCollision()) return true;
    }
  }
  return false;
}

std::vector<std::string> ObjectCollisionWorld::collisions(const Pose& X_WO) const {
  const AlignedBox3 bounds = boundsAtPose(object_, X_WO);
  std::vector<std::string> names;
  for (const Obstacle& obstacle : obstacles_) {
    if (!bounds.intersects(obstacle.bounds)) continue;
    if (touches(obstacle, X_WO)) names.push_back(obstacle.name);
  }
  return names;
}

}  // namespace lang2manip
