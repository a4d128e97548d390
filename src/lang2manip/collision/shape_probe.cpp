#include "lang2manip/collision/shape_probe.hpp"

#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision.h>

namespace lang2manip {

ShapeProbe::ShapeProbe(const SceneObject& object) : pose_(object.pose), shapes_(FclGeometryBuilder().build(object.collisions)) {}

bool ShapeProbe::hits(const AlignedBox3& box) const {
  const fcl::Boxd probe(box.sizes());
  Pose X_WP = Pose::Identity();
  X_WP.translation() = box.center();
  const fcl::CollisionRequestd request;
  for (const FclShape& shape : shapes_) {
    fcl::CollisionResultd result;
    fcl::collide(&probe, X_WP, shape.geometry.get(), pose_ * shape.origin, request, result);
    if (result.isCollision()) return true;
  }
  return false;
}

}  // namespace lang2manip
