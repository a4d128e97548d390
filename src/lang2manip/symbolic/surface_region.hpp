#pragma once
/// @file Regions of a support's top face ("the far left corner of the table", "the middle of the
/// desk", "the right half"), in the robot's base frame, computed from the part of the face the
/// robot's arms reach. One definition shared by the observation, the plan validator, the offline
/// planner, placement and the goal check, so that what one says the others do.
///
/// The reachable part of a top face is split in thirds along x (near, middle, far) and y (right,
/// middle, left): a corner is a corner cell, an edge the middle cell along that edge, the centre
/// the middle cell; halves and quadrants split it in two along x and/or y.

#include <optional>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"

namespace lang2manip {

class Scene;

/// A named region of a top face. `depth` is along the base x axis (-1 near the robot, "bottom";
/// +1 far from it, "top"), `side` along the base y axis (-1 right, +1 left); 0 is the middle.
struct SurfaceRegion {
  enum class Kind { kCorner, kEdge, kCentre, kHalf, kQuadrant };
  Kind kind = Kind::kCentre;
  int depth = 0;
  int side = 0;

  friend bool operator==(const SurfaceRegion&, const SurfaceRegion&) = default;
};

/// "far_left_corner", "near_edge", "left_edge", "centre", "far_half", "near_right_quadrant".
std::string surfaceRegionName(const SurfaceRegion& region);
/// The region as people write it in messages: "far left corner", "centre", "near right quadrant".
std::string surfaceRegionWords(const SurfaceRegion& region);
/// Inverse of surfaceRegionName(); nullopt for an unknown name.
std::optional<SurfaceRegion> surfaceRegionFromName(const std::string& name);
/// Every region name, corners first.
std::vector<std::string> surfaceRegionNames();

/// The rectangle of `region` inside `area` (x and y; z kept).
AlignedBox3 regionBox(const AlignedBox3& area, const SurfaceRegion& region);

/// True when the two regions share some area (of any top: they are fractions of it).
bool regionsOverlap(const SurfaceRegion& a, const SurfaceRegion& b);

/// The footprint's clearance from the edges of the reachable part, metres (placement's edge margin).
inline constexpr double kRegionEdgeMargin = 0.02;

/// Where the centre of a footprint of `size` (x, y, as it stands in the base frame) may be for it
/// to stand in `region` of `area`: within the region's rectangle, the whole footprint `margin`
/// inside `area`. Nullopt when nowhere.
std::optional<AlignedBox3> regionCentres(const AlignedBox3& area, const SurfaceRegion& region, const Vector3& size,
                                         double margin = kRegionEdgeMargin);

/// The corner, edge or centre cell of `area` that (x, y) of `point` falls in (the nearest one
/// when it is outside).
SurfaceRegion cellOfPoint(const AlignedBox3& area, const Vector3& point);

/// A support's top face in the robot's base frame and the part of it the robot reaches.
struct SupportArea {
  std::string support;
  /// The whole flat top (x, y; min z = max z = its height), base frame.
  AlignedBox3 top;
  /// The largest (area weighted by the square root of the aspect ratio) axis-aligned rectangle of
  /// `top` in front of the robot (base x >= 0) whose every
  /// point the arm (any arm, when none is named) reaches with the hand pointing down (within 30
  /// degrees of vertical),
  /// 2 and 12 cm above the top, 3 cm inside the boundary measured by IK (see arm_reach.hpp).
  /// `top` itself for a scene without robots.
  AlignedBox3 reachable;
  /// True when `reachable` is smaller than `top`.
  bool clipped = false;
};

/// The SupportArea of `support` for `robot` (the first robot when empty) and its arm `arm` (every
/// arm when empty); nullopt with `why` when it has no flat top (see supportSurface()) or the arm
/// reaches none of it. Throws InputError for an unknown object, robot or arm.
std::optional<SupportArea> supportArea(const Scene& scene, const std::string& support, const std::string& robot,
                                       std::string* why = nullptr, const std::string& arm = {});

/// The region's rectangle on `support` (base frame), or nullopt with `why` as supportArea().
std::optional<AlignedBox3> regionOnSupport(const Scene& scene, const std::string& support, const SurfaceRegion& region,
                                           const std::string& robot, std::string* why = nullptr,
                                           const std::string& arm = {});

}  // namespace lang2manip
