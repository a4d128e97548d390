#include "lang2manip/symbolic/resting_height.hpp"

#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision.h>

#include "lang2manip/collision/fcl_geometry.hpp"

namespace lang2manip {
namespace {

constexpr double kColumnHalfWidth = 0.005;
constexpr int kBisections = 16;
constexpr double kSlab = 1e-3;

/// Whether the box [low, high] of the column about `centre` meets any of `shapes` (placed by `pose`).
bool columnHits(const std::vector<FclShape>& shapes, const Pose& pose, const Vector3& centre, double low, double high) {
  const fcl::Boxd probe(2.0 * kColumnHalfWidth, 2.0 * kColumnHalfWidth, high - low);
  Pose X_WP = Pose::Identity();
  X_WP.translation() = Vector3(centre.x(), centre.y(), 0.5 * (low + high));
  const fcl::CollisionRequestd request;
  for (const FclShape& shape : shapes) {
    fcl::CollisionResultd result;
    fcl::collide(&probe, X_WP, shape.geometry.get(), pose * shape.origin, request, result);
    if (result.isCollision()) return true;
  }
  return false;
}

}  // namespace

std::optional<double> restingHeight(const SceneObject& support, const Vector3& bottom, double tolerance) {
  const AlignedBox3 bounds = support.worldBounds();
  const bool over = bounds.min().x() <= bottom.x() && bottom.x() <= bounds.max().x() && bounds.min().y() <= bottom.y() &&
                    bottom.y() <= bounds.max().y();
  if (!over) return std::nullopt;
  const double top = bounds.max().z();
  if (std::abs(top - bottom.z()) <= tolerance) return top;
  const double low = bottom.z() - tolerance, high = bottom.z() + tolerance;
  if (top < high || bounds.min().z() > high || support.role == ObjectRole::kContainer) return std::nullopt;
  const std::vector<FclShape> shapes = FclGeometryBuilder().build(support.collisions);
  // Nothing of it under the body, or the body stands inside it (a solid that goes on above the
  // window): no surface to rest on.
  if (!columnHits(shapes, support.pose, bottom, low, high) || columnHits(shapes, support.pose, bottom, high - kSlab, high)) return std::nullopt;
  // The highest z whose column above it, up to `high`, still meets the geometry.
  double surface = low, above = high;
  for (int i = 0; i < kBisections; ++i) {
    const double middle = 0.5 * (surface + above);
    (columnHits(shapes, support.pose, bottom, middle, high) ? surface : above) = middle;
  }
  return surface;
}

}  // namespace lang2manip
