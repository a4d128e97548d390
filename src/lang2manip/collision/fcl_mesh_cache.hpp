#pragma once
/// @file The FCL bounding-volume hierarchy of each (mesh, scale), built once per process and
/// shared by every checker while the mesh is alive: a pipeline builds a checker per world
/// change, and rebuilding the BVHs of a 70 000-triangle gripper each time cost 0.3 s.

#include <fcl/geometry/collision_geometry.h>

#include <cstddef>
#include <memory>
#include <vector>

#include "lang2manip/model/geometry.hpp"

namespace lang2manip {

/// The BVHModel<OBBRSS> of `geometry` (its mesh with its scale applied), from the process-wide
/// cache or built now; nullptr for a mesh without triangles. Thread-safe. An entry lives as long
/// as its TriangleMesh: a mesh freed and another allocated at its address is a new entry.
[[nodiscard]] std::shared_ptr<const fcl::CollisionGeometryd> sharedMeshBvh(const MeshGeometry& geometry);

/// Builds the BVHs of `geometries` that are not cached yet, on up to `threads` threads (the
/// largest meshes first), so that sharedMeshBvh() finds them. Thread-safe.
void prebuildMeshBvhs(const std::vector<const MeshGeometry*>& geometries, unsigned threads);

/// Counters of the cache, for tests and benchmarks.
struct MeshBvhCacheStatistics {
  /// BVHs built since the process started.
  std::size_t builds = 0;
  /// Entries whose mesh is still alive.
  std::size_t liveEntries = 0;
};
[[nodiscard]] MeshBvhCacheStatistics meshBvhCacheStatistics();

}  // namespace lang2manip
