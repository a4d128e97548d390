#pragma once
/// @file Box probes against one object's collision geometry: whether a world-aligned box meets
/// it. Used to measure shapes that bounds say little about (a container's hollow, the surface a
/// support offers inside its bounds).

#include <vector>

#include "lang2manip/collision/fcl_geometry.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// Box probes against `object`'s collision geometry at its current pose (world frame). Builds
/// the object's FCL geometry once (meshes shared process-wide, see FclGeometryBuilder).
class ShapeProbe {
 public:
  explicit ShapeProbe(const SceneObject& object);

  /// True when the world-aligned `box` meets the object's geometry (a mesh counts by its
  /// triangles: a box wholly inside a closed mesh does not meet it).
  [[nodiscard]] bool hits(const AlignedBox3& box) const;

 private:
  Pose pose_;
  std::vector<FclShape> shapes_;
};

}  // namespace lang2manip
