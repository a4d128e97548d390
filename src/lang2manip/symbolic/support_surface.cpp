#include "lang2manip/symbolic/support_surface.hpp"

#include <algorithm>
#include <cmath>

namespace lang2manip {
namespace {

constexpr double kLevelCosine = 0.9962;  // cos(5 deg)
constexpr double kTopTolerance = 0.003;

/// A horizontal rectangle of `width` x `depth` centred at `centre`, turned by `yaw` about z: the
/// largest axis-aligned square inside it when turned, the rectangle itself when (nearly) aligned.
AlignedBox3 levelFace(const Vector3& centre, double width, double depth, double yaw) {
  const double c = std::abs(std::cos(yaw)), s = std::abs(std::sin(yaw));
  Vector3 half;
  if (s < 0.087 || c < 0.087) {  // within 5 deg of the axes
    half = s < c ? Vector3(width / 2.0, depth / 2.0, 0.0) : Vector3(depth / 2.0, width / 2.0, 0.0);
  } else {
    const double side = std::min(width, depth) / (c + s);
    half = Vector3(side / 2.0, side / 2.0, 0.0);
  }
  return {centre - half, centre + half};
}

/// The flat top of one shape placed at `pose` (world; its bounds there are `bounds`), or why it
/// is not flat.
SupportSurface shapeTop(const Shape& shape, const Pose& pose, AlignedBox3 bounds) {
  const Matrix3 R = pose.linear();
  if (const auto* box = std::get_if<Box>(&shape.geometry)) {
    for (int axis = 0; axis < 3; ++axis) {
      const double up = R.col(axis).z();
      if (std::abs(up) < kLevelCosine) continue;
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      const Vector3 centre = pose.translation() + R.col(axis) * (up > 0 ? 1.0 : -1.0) * box->size[axis] / 2.0;
      const double yaw = std::atan2(R.col(a).y(), R.col(a).x());
      return {levelFace(centre, box->size[a], box->size[b], yaw), ""};
    }
    return {std::nullopt, "its top is not level (a box standing tilted)"};
  }
  if (const auto* cylinder = std::get_if<Cylinder>(&shape.geometry)) {
    const double up = R.col(2).z();
    if (std::abs(up) < kLevelCosine) return {std::nullopt, "its top is round (a cylinder lying on its side)"};
    const Vector3 centre = pose.translation() + R.col(2) * (up > 0 ? 1.0 : -1.0) * cylinder->length / 2.0;
    const double side = cylinder->radius * std::sqrt(2.0);
    return {levelFace(centre, side, side, 0.0), ""};
  }
  if (std::holds_alternative<Sphere>(shape.geometry)) return {std::nullopt, "its top is round (a sphere)"};
  bounds.min().z() = bounds.max().z();  // a mesh: its bounds' top
  return {bounds, ""};
}

}  // namespace

SupportSurface supportSurface(const SceneObject& object) {
  if (object.cavity) return {std::nullopt, "it is open at the top (a container: put things in it)"};
  const double highest = object.worldBounds().max().z();
  SupportSurface best{std::nullopt, "it has no collision shape"};
  for (const Shape& shape : object.collisions) {
    const AlignedBox3 bounds = shapeBounds(shape).transformed(object.pose);
    if (bounds.max().z() < highest - kTopTolerance) continue;
    SupportSurface top = shapeTop(shape, object.pose * shape.origin, bounds);
    if (!top.top) {
      if (!best.top) best = top;
      continue;
    }
    const auto area = [](const AlignedBox3& box) { return box.sizes().x() * box.sizes().y(); };
    if (!best.top || area(*top.top) > area(*best.top)) best = top;
  }
  return best;
}

bool footprintFits(const Vector3& size, const AlignedBox3& top) {
  const Vector3 room = top.sizes() + Vector3::Constant(kFootprintSlack);
  return (size.x() <= room.x() && size.y() <= room.y()) || (size.y() <= room.x() && size.x() <= room.y());
}

std::optional<std::size_t> bridgedSupport(const AlignedBox3& item, const std::vector<AlignedBox3>& candidates, double gap) {
  std::optional<std::size_t> most;
  double mostArea = 0.0;
  int touching = 0;
  Eigen::AlignedBox2d contacts;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const AlignedBox3& below = candidates[i];
    if (std::abs(below.max().z() - item.min().z()) > gap) continue;
    const Eigen::AlignedBox2d overlap = Eigen::AlignedBox2d(item.min().head<2>(), item.max().head<2>())
                                            .intersection(Eigen::AlignedBox2d(below.min().head<2>(), below.max().head<2>()));
    if (overlap.isEmpty() || (overlap.sizes().array() < kLeastBridgeOverlap).any()) continue;
    ++touching;
    contacts.extend(overlap);
    if (overlap.volume() > mostArea) most = i, mostArea = overlap.volume();
  }
  if (touching < 2 || !contacts.contains(Eigen::Vector2d(item.center().head<2>()))) return std::nullopt;
  return most;
}

}  // namespace lang2manip
