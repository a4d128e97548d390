#pragma once
/// @file Model shapes to FCL collision geometry: primitives as FCL primitives, meshes as
/// BVHModel<OBBRSS> shared per (mesh, scale) process-wide (fcl_mesh_cache.hpp), and the built-in robots' capsule triples
/// ("capsuleN_cylinder", "capsuleN_a", "capsuleN_b") merged back into one fcl::Capsule.

#include <fcl/geometry/collision_geometry.h>

#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/geometry.hpp"

namespace lang2manip {

/// One FCL geometry placed in a frame (a link or an object frame).
struct FclShape {
  std::shared_ptr<const fcl::CollisionGeometryd> geometry;
  /// X_FG: the geometry in the frame it belongs to.
  Pose origin = Pose::Identity();
  /// Axis-aligned bounds in the geometry's own frame, as centre and half extents.
  Vector3 localCenter = Vector3::Zero();
  Vector3 localHalfExtent = Vector3::Zero();
};

/// Converts shapes, sharing one BVH per (TriangleMesh, scale) with every other builder of the
/// process. Not thread-safe (used while a checker is built); the geometries it returns are
/// immutable and shareable.
class FclGeometryBuilder {
 public:
  /// The FCL geometries of `shapes` (in the same frame). Capsule triples whose cylinder and
  /// spheres have the same radius and whose spheres sit on the cylinder's ends become one
  /// capsule. Meshes without triangles and degenerate primitives (zero size) are left out;
  /// their count is added to skipped().
  std::vector<FclShape> build(const std::vector<Shape>& shapes);

  /// Shapes left out so far (see build()).
  [[nodiscard]] int skipped() const noexcept { return skipped_; }
  /// Distinct mesh BVHs used so far.
  [[nodiscard]] std::size_t meshCount() const noexcept { return meshes_.size(); }

 private:
  std::shared_ptr<const fcl::CollisionGeometryd> mesh(const MeshGeometry& geometry);
  std::shared_ptr<const fcl::CollisionGeometryd> primitive(const Geometry& geometry);

  using MeshKey = std::tuple<const TriangleMesh*, double, double, double>;
  std::map<MeshKey, std::shared_ptr<const fcl::CollisionGeometryd>> meshes_;
  int skipped_ = 0;
};

}  // namespace lang2manip
