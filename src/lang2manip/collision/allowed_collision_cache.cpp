#include "lang2manip/collision/allowed_collision_cache.hpp"

#include <cstdint>
#include <exception>
#include <future>
#include <iterator>
#include <map>
#include <mutex>
#include <tuple>

namespace lang2manip {
namespace {

using MatrixPtr = std::shared_ptr<const AllowedCollisionMatrix>;

struct CacheKey {
  const RobotModel* model;
  int samples;
  std::uint64_t seed;
  bool disableNever;
  bool disableAlways;

  bool operator<(const CacheKey& other) const {
    return std::tie(model, samples, seed, disableNever, disableAlways) <
           std::tie(other.model, other.samples, other.seed, other.disableNever, other.disableAlways);
  }
};

struct CacheEntry {
  /// Tells whether the keyed model still exists (its address may be reused once it does not).
  std::weak_ptr<const RobotModel> model;
  std::shared_future<MatrixPtr> matrix;
};

class MatrixCache {
 public:
  MatrixPtr get(const RobotModelPtr& model, const AllowedCollisionSettings& settings,
                const std::function<AllowedCollisionMatrix()>& compute) {
    const CacheKey key{model.get(), settings.samples, settings.seed, settings.disableNever,
                       settings.disableAlways};
    std::promise<MatrixPtr> promise;
    std::shared_future<MatrixPtr> future;
    bool computeHere = false;
    {
      const std::lock_guard lock(mutex_);
      dropDestroyedModels();
      const auto found = entries_.find(key);
      if (found != entries_.end()) {
        future = found->second.matrix;
      } else {
        future = promise.get_future().share();
        entries_.emplace(key, CacheEntry{model, future});
        computeHere = true;
      }
    }
    // Outside the lock: the first caller computes, the others wait on the future.
    if (computeHere) {
      try {
        promise.set_value(std::make_shared<const AllowedCollisionMatrix>(compute()));
      } catch (...) {
        promise.set_exception(std::current_exception());
        const std::lock_guard lock(mutex_);
        entries_.erase(key);
      }
    }
    return future.get();
  }

  std::size_t size() {
    const std::lock_guard lock(mutex_);
    dropDestroyedModels();
    return entries_.size();
  }

 private:
  void dropDestroyedModels() {
    for (auto entry = entries_.begin(); entry != entries_.end();) {
      entry = entry->second.model.expired() ? entries_.erase(entry) : std::next(entry);
    }
  }

  std::mutex mutex_;
  std::map<CacheKey, CacheEntry> entries_;
};

MatrixCache& cache() {
  static MatrixCache instance;
  return instance;
}

}  // namespace

std::shared_ptr<const AllowedCollisionMatrix> cachedAllowedCollisionMatrix(
    const RobotModelPtr& model, const AllowedCollisionSettings& settings,
    const std::function<AllowedCollisionMatrix()>& compute) {
  return cache().get(model, settings, compute);
}

std::size_t allowedCollisionCacheSize() { return cache().size(); }

}  // namespace lang2manip
