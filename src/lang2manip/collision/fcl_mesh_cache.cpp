#include "lang2manip/collision/fcl_mesh_cache.hpp"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <mutex>
#include <set>
#include <thread>
#include <tuple>

namespace lang2manip {
namespace {

using Key = std::tuple<const TriangleMesh*, double, double, double>;

Key keyOf(const MeshGeometry& geometry) {
  return {geometry.mesh.get(), geometry.scale.x(), geometry.scale.y(), geometry.scale.z()};
}

struct Entry {
  std::weak_ptr<const TriangleMesh> mesh;
  std::shared_ptr<const fcl::CollisionGeometryd> bvh;
};

class MeshBvhCache {
 public:
  static MeshBvhCache& instance() {
    static MeshBvhCache cache;
    return cache;
  }

  std::shared_ptr<const fcl::CollisionGeometryd> find(const MeshGeometry& geometry) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto found = entries_.find(keyOf(geometry));
    if (found == entries_.end() || found->second.mesh.lock() != geometry.mesh) return nullptr;
    return found->second.bvh;
  }

  /// Stores `bvh` unless another thread stored one first; returns the one kept.
  std::shared_ptr<const fcl::CollisionGeometryd> store(const MeshGeometry& geometry,
                                                       std::shared_ptr<const fcl::CollisionGeometryd> bvh) {
    const std::lock_guard<std::mutex> lock(mutex_);
    ++builds_;
    for (auto it = entries_.begin(); it != entries_.end();) {
      it = it->second.mesh.expired() ? entries_.erase(it) : std::next(it);
    }
    Entry& entry = entries_[keyOf(geometry)];
    if (entry.mesh.lock() == geometry.mesh && entry.bvh) return entry.bvh;
    entry = Entry{geometry.mesh, std::move(bvh)};
    return entry.bvh;
  }

  MeshBvhCacheStatistics statistics() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    MeshBvhCacheStatistics statistics;
    statistics.builds = builds_;
    statistics.liveEntries = static_cast<std::size_t>(
        std::count_if(entries_.begin(), entries_.end(), [](const auto& entry) { return !entry.second.mesh.expired(); }));
    return statistics;
  }

 private:
  mutable std::mutex mutex_;
  std::map<Key, Entry> entries_;
  std::size_t builds_ = 0;
};

std::shared_ptr<const fcl::CollisionGeometryd> buildBvh(const MeshGeometry& geometry) {
  const TriangleMesh& mesh = *geometry.mesh;
  std::vector<fcl::Vector3d> vertices;
  vertices.reserve(mesh.vertices.size());
  for (const Vector3& v : mesh.vertices) vertices.emplace_back(v.cwiseProduct(geometry.scale));
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    triangles.emplace_back(static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]),
                           static_cast<std::size_t>(t[2]));
  }
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
  model->addSubModel(vertices, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

bool buildable(const MeshGeometry* geometry) {
  return geometry && geometry->mesh && !geometry->mesh->triangles.empty();
}

}  // namespace

std::shared_ptr<const fcl::CollisionGeometryd> sharedMeshBvh(const MeshGeometry& geometry) {
  if (!buildable(&geometry)) return nullptr;
  MeshBvhCache& cache = MeshBvhCache::instance();
  if (auto found = cache.find(geometry)) return found;
  return cache.store(geometry, buildBvh(geometry));
}

void prebuildMeshBvhs(const std::vector<const MeshGeometry*>& geometries, unsigned threads) {
  std::vector<const MeshGeometry*> missing;
  std::set<Key> seen;
  for (const MeshGeometry* geometry : geometries) {
    if (!buildable(geometry) || !seen.insert(keyOf(*geometry)).second) continue;
    if (!MeshBvhCache::instance().find(*geometry)) missing.push_back(geometry);
  }
  std::sort(missing.begin(), missing.end(), [](const MeshGeometry* a, const MeshGeometry* b) {
    return a->mesh->triangles.size() > b->mesh->triangles.size();
  });
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t i = next++; i < missing.size(); i = next++) (void)sharedMeshBvh(*missing[i]);
  };
  const std::size_t helpers = std::min<std::size_t>(std::max(threads, 1U), missing.size());
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < helpers; ++t) pool.emplace_back(work);
  work();
  for (std::thread& thread : pool) thread.join();
}

MeshBvhCacheStatistics meshBvhCacheStatistics() { return MeshBvhCache::instance().statistics(); }

}  // namespace lang2manip
