#include "lang2manip/symbolic/surface_region.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "lang2manip/model/scene.hpp"
#include "lang2manip/symbolic/arm_reach.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"
#include "lang2manip/symbolic/support_surface.hpp"

namespace lang2manip {
namespace {

constexpr double kCell = 0.02;

std::string depthWord(int depth) { return depth > 0 ? "far" : "near"; }
std::string sideWord(int side) { return side > 0 ? "left" : "right"; }

/// [low, high] of the third (-1, 0, +1) or half (-1, +1) along one axis.
std::pair<double, double> span(double low, double high, int part, bool halves) {
  const double length = high - low;
  if (part == 0) return halves ? std::pair{low, high} : std::pair{low + length / 3.0, high - length / 3.0};
  const double share = halves ? length / 2.0 : length / 3.0;
  return part < 0 ? std::pair{low, low + share} : std::pair{high - share, high};
}

/// In front of the robot (base x >= 0) and within the measured reach of some arm.
bool reached(const std::vector<ArmReach>& arms, const Vector3& point) {
  if (point.x() < 0.0) return false;
  return std::any_of(arms.begin(), arms.end(), [&](const ArmReach& arm) { return arm.reaches(point); });
}

/// The rectangle of whole cells of `top` whose cell corners are all reached with the largest
/// area weighted by the square root of its aspect ratio (<= 1): regions split in thirds need
/// some depth, and a band across the front of an annulus would have little. The weighted area
/// grows with either side, so the best is among the maximal rectangles enumerated here.
std::optional<AlignedBox3> largestReachedRectangle(const AlignedBox3& top, const std::vector<ArmReach>& arms) {
  const int rows = std::max(1, static_cast<int>(std::floor(top.sizes().x() / kCell)));
  const int columns = std::max(1, static_cast<int>(std::floor(top.sizes().y() / kCell)));
  const double dx = top.sizes().x() / rows, dy = top.sizes().y() / columns;
  const double z = top.max().z();
  const auto corner = [&](int i, int j) { return Vector3(top.min().x() + i * dx, top.min().y() + j * dy, z); };
  std::vector<int> heights(static_cast<std::size_t>(columns), 0);
  double bestScore = 0.0;
  AlignedBox3 best;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < columns; ++j) {
      const bool cell = reached(arms, corner(i, j)) && reached(arms, corner(i + 1, j)) && reached(arms, corner(i, j + 1)) &&
                        reached(arms, corner(i + 1, j + 1));
      heights[static_cast<std::size_t>(j)] = cell ? heights[static_cast<std::size_t>(j)] + 1 : 0;
    }
    for (int j = 0; j < columns; ++j) {  // widest run of columns at least as tall as column j
      const int h = heights[static_cast<std::size_t>(j)];
      if (h == 0) continue;
      int left = j, right = j;
      while (left > 0 && heights[static_cast<std::size_t>(left - 1)] >= h) --left;
      while (right + 1 < columns && heights[static_cast<std::size_t>(right + 1)] >= h) ++right;
      const double depth = h * dx, width = (right - left + 1) * dy;
      const double score = depth * width * std::sqrt(std::min(depth, width) / std::max(depth, width));
      if (score <= bestScore) continue;
      bestScore = score;
      best = AlignedBox3(Vector3(top.min().x() + (i + 1 - h) * dx, top.min().y() + left * dy, top.max().z()),
                         Vector3(top.min().x() + (i + 1) * dx, top.min().y() + (right + 1) * dy, top.max().z()));
    }
  }
  if (bestScore <= 0.0) return std::nullopt;
  return best;
}

AlignedBox3 inBaseFrame(const AlignedBox3& world, const Pose& base) {
  const Pose inverse = base.inverse();
  AlignedBox3 box;
  for (int corner = 0; corner < 4; ++corner) {
    const Vector3 p((corner & 1) ? world.max().x() : world.min().x(), (corner & 2) ? world.max().y() : world.min().y(),
                    world.max().z());
    box.extend(inverse * p);
  }
  return box;
}

}  // namespace

std::string surfaceRegionWords(const SurfaceRegion& region) {
  std::string words = surfaceRegionName(region);
  std::replace(words.begin(), words.end(), '_', ' ');
  return words;
}

std::string surfaceRegionName(const SurfaceRegion& region) {
  switch (region.kind) {
    case SurfaceRegion::Kind::kCorner: return depthWord(region.depth) + "_" + sideWord(region.side) + "_corner";
    case SurfaceRegion::Kind::kEdge:
      return (region.depth != 0 ? depthWord(region.depth) : sideWord(region.side)) + "_edge";
    case SurfaceRegion::Kind::kCentre: return "centre";
    case SurfaceRegion::Kind::kHalf:
      return (region.depth != 0 ? depthWord(region.depth) : sideWord(region.side)) + "_half";
    case SurfaceRegion::Kind::kQuadrant: return depthWord(region.depth) + "_" + sideWord(region.side) + "_quadrant";
  }
  return "centre";
}

std::vector<std::string> surfaceRegionNames() {
  std::vector<std::string> names;
  using Kind = SurfaceRegion::Kind;
  for (int depth : {1, -1}) {
    for (int side : {1, -1}) names.push_back(surfaceRegionName({Kind::kCorner, depth, side}));
  }
  for (const auto& [depth, side] : std::array<std::pair<int, int>, 4>{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}}) {
    names.push_back(surfaceRegionName({Kind::kEdge, depth, side}));
  }
  names.push_back("centre");
  for (const auto& [depth, side] : std::array<std::pair<int, int>, 4>{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}}) {
    names.push_back(surfaceRegionName({Kind::kHalf, depth, side}));
  }
  for (int depth : {1, -1}) {
    for (int side : {1, -1}) names.push_back(surfaceRegionName({Kind::kQuadrant, depth, side}));
  }
  return names;
}

std::optional<SurfaceRegion> surfaceRegionFromName(const std::string& name) {
  using Kind = SurfaceRegion::Kind;
  for (Kind kind : {Kind::kCorner, Kind::kEdge, Kind::kCentre, Kind::kHalf, Kind::kQuadrant}) {
    for (int depth : {-1, 0, 1}) {
      for (int side : {-1, 0, 1}) {
        const bool corner = kind == Kind::kCorner || kind == Kind::kQuadrant;
        const bool single = kind == Kind::kEdge || kind == Kind::kHalf;
        if (corner && (depth == 0 || side == 0)) continue;
        if (single && (depth == 0) == (side == 0)) continue;
        if (kind == Kind::kCentre && (depth != 0 || side != 0)) continue;
        const SurfaceRegion region{kind, depth, side};
        if (surfaceRegionName(region) == name) return region;
      }
    }
  }
  return std::nullopt;
}

AlignedBox3 regionBox(const AlignedBox3& area, const SurfaceRegion& region) {
  const bool halves = region.kind == SurfaceRegion::Kind::kHalf || region.kind == SurfaceRegion::Kind::kQuadrant;
  const auto [x0, x1] = span(area.min().x(), area.max().x(), region.depth, halves);
  const auto [y0, y1] = span(area.min().y(), area.max().y(), region.side, halves);
  return AlignedBox3(Vector3(x0, y0, area.min().z()), Vector3(x1, y1, area.max().z()));
}

bool regionsOverlap(const SurfaceRegion& a, const SurfaceRegion& b) {
  const AlignedBox3 unit(Vector3::Zero(), Vector3(1.0, 1.0, 0.0));
  const AlignedBox3 overlap = regionBox(unit, a).intersection(regionBox(unit, b));
  return !overlap.isEmpty() && overlap.sizes().x() > 1e-9 && overlap.sizes().y() > 1e-9;
}

std::optional<AlignedBox3> regionCentres(const AlignedBox3& area, const SurfaceRegion& region, const Vector3& size,
                                         double margin) {
  const AlignedBox3 box = regionBox(area, region);
  const Vector3 half(size.x() / 2.0 + margin, size.y() / 2.0 + margin, 0.0);
  const Vector3 low = box.min().cwiseMax(area.min() + half);
  const Vector3 high = box.max().cwiseMin(area.max() - half);
  if (low.x() > high.x() || low.y() > high.y()) return std::nullopt;
  return AlignedBox3(Vector3(low.x(), low.y(), area.min().z()), Vector3(high.x(), high.y(), area.max().z()));
}

SurfaceRegion cellOfPoint(const AlignedBox3& area, const Vector3& point) {
  const auto third = [](double value, double low, double high) {
    const double t = (value - low) / std::max(high - low, 1e-9);
    return t < 1.0 / 3.0 ? -1 : (t > 2.0 / 3.0 ? 1 : 0);
  };
  const int depth = third(point.x(), area.min().x(), area.max().x());
  const int side = third(point.y(), area.min().y(), area.max().y());
  using Kind = SurfaceRegion::Kind;
  if (depth != 0 && side != 0) return {Kind::kCorner, depth, side};
  if (depth != 0 || side != 0) return {Kind::kEdge, depth, side};
  return {Kind::kCentre, 0, 0};
}

std::optional<SupportArea> supportArea(const Scene& scene, const std::string& support, const std::string& robot,
                                       std::string* why, const std::string& arm) {
  const SceneObject& object = scene.object(support);
  const SupportSurface surface = supportSurface(object);
  const auto fail = [&](const std::string& reason) -> std::optional<SupportArea> {
    if (why != nullptr) *why = reason;
    return std::nullopt;
  };
  if (!surface.top) return fail(support + " has no flat top: " + surface.why);
  const Pose base = robotBaseFrame(scene, robot);
  SupportArea area{support, inBaseFrame(*surface.top, base), {}, false};
  area.reachable = area.top;
  if (scene.robots().empty()) return area;
  const SceneRobot& reacher = robot.empty() ? scene.robots().front() : scene.robot(robot);
  const std::vector<ArmReach> arms = measuredArmReaches(reacher, base, area.top.max().z(), arm);
  if (arms.empty()) return area;
  const auto reachable = largestReachedRectangle(area.top, arms);
  if (!reachable) return fail("no part of the top of " + support + " is within reach of " + reacher.name + (arm.empty() ? "" : " " + arm));
  area.reachable = *reachable;
  area.clipped = reachable->sizes().head<2>().prod() < area.top.sizes().head<2>().prod() - 1e-9;
  return area;
}

std::optional<AlignedBox3> regionOnSupport(const Scene& scene, const std::string& support, const SurfaceRegion& region,
                                           const std::string& robot, std::string* why, const std::string& arm) {
  const auto area = supportArea(scene, support, robot, why, arm);
  if (!area) return std::nullopt;
  return regionBox(area->reachable, region);
}

}  // namespace lang2manip
