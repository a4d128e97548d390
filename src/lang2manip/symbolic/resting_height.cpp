#include "lang2manip/symbolic/resting_height.hpp"

#include <cmath>

#include "lang2manip/collision/shape_probe.hpp"

namespace lang2manip {
namespace {

constexpr double kColumnHalfWidth = 0.005;
constexpr int kBisections = 16;
constexpr double kSlab = 1e-3;

/// The column [low, high] about `centre`'s x, y.
AlignedBox3 column(const Vector3& centre, double low, double high) {
  return AlignedBox3(Vector3(centre.x() - kColumnHalfWidth, centre.y() - kColumnHalfWidth, low),
                     Vector3(centre.x() + kColumnHalfWidth, centre.y() + kColumnHalfWidth, high));
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
  const ShapeProbe probe(support);
  // Nothing of it under the body, or the body stands inside it (a solid that goes on above the
  // window): no surface to rest on.
  if (!probe.hits(column(bottom, low, high)) || probe.hits(column(bottom, high - kSlab, high))) return std::nullopt;
  // The highest z whose column above it, up to `high`, still meets the geometry.
  double surface = low, above = high;
  for (int i = 0; i < kBisections; ++i) {
    const double middle = 0.5 * (surface + above);
    (probe.hits(column(bottom, middle, high)) ? surface : above) = middle;
  }
  return surface;
}

}  // namespace lang2manip
