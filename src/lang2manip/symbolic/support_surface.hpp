#pragma once
/// @file Whether other objects can rest on an object: the flat top of its collision shapes (a
/// box's level face, a standing cylinder's disk), or why it has none (round on top, tilted, a
/// container's open top). Used by plan validation ("place on") and the placement sampler.

#include <optional>
#include <string>
#include <vector>

#include "lang2manip/model/scene.hpp"

namespace lang2manip {

struct SupportSurface {
  /// The flat region objects may rest on: x/y the largest axis-aligned rectangle inside it
  /// (world frame), z its height (min = max). Absent when there is none.
  std::optional<AlignedBox3> top;
  /// Why there is none ("its top is round: a cylinder lying on its side").
  std::string why;
};

/// The support surface of `object` from its collision shapes at its top (within 3 mm): a box
/// with a face within 5 degrees of level, a cylinder standing within 5 degrees; a mesh counts by
/// its bounds (its shape is not analysed). Containers (with a cavity) offer none: what goes there
/// goes in.
SupportSurface supportSurface(const SceneObject& object);

/// How far a footprint may overhang the top it rests on, in all (metres): an equal-size block on a
/// block (models rarely match to the micrometre) rests centred on it.
inline constexpr double kFootprintSlack = 0.01;

/// True when a footprint of `size` (x, y; any yaw of 90-degree steps) fits inside `top`, up to
/// kFootprintSlack.
bool footprintFits(const Vector3& size, const AlignedBox3& top);

/// How far two footprints must overlap on each axis (m) for one to rest on the other's top.
inline constexpr double kLeastBridgeOverlap = 0.005;

/// Where a body with world bounds `item` rests when nothing is under its bottom centre: on two or
/// more of `candidates` (world bounds) whose tops lie within `gap` of its bottom and whose
/// footprints overlap its own by kLeastBridgeOverlap, when its centre lies within the rectangle
/// spanned by those overlaps (an object bridging two, as the top of a pyramid does). The index of
/// the candidate it overlaps most; none when it bridges nothing.
std::optional<std::size_t> bridgedSupport(const AlignedBox3& item, const std::vector<AlignedBox3>& candidates, double gap);

}  // namespace lang2manip
