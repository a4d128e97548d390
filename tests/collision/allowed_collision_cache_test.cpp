// The process-wide allowed-collision matrix cache: one computation per (model, settings),
// shared by checkers, thread-safe, never handing out the matrix of a destroyed model.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "collision_test_support.hpp"
#include "lang2manip/collision/allowed_collision_cache.hpp"

namespace lang2manip::test {
namespace {

/// A cheap stand-in computation that counts its calls.
struct CountingCompute {
  std::atomic<int> calls{0};
  int links = 4;
  AllowedCollisionMatrix operator()() {
    ++calls;
    AllowedCollisionMatrix matrix(links);
    matrix.allow(0, 1, AllowedReason::kAdjacent);
    return matrix;
  }
};

TEST(AllowedCollisionCache, ComputesOncePerModelAndSettings) {
  const RobotModelPtr panda = builtinRobot("panda");
  CountingCompute compute;
  const auto call = [&] { return compute(); };
  AllowedCollisionSettings settings;
  settings.seed = 101;
  const auto first = cachedAllowedCollisionMatrix(panda, settings, call);
  const auto second = cachedAllowedCollisionMatrix(panda, settings, call);
  EXPECT_EQ(first, second);
  EXPECT_EQ(compute.calls, 1);
  EXPECT_EQ(first->reason(0, 1), AllowedReason::kAdjacent);
  // Other settings, or another model object read from the same file: another entry.
  settings.samples = 17;
  EXPECT_NE(cachedAllowedCollisionMatrix(panda, settings, call), first);
  EXPECT_NE(cachedAllowedCollisionMatrix(builtinRobot("panda"), {}, call).get(), nullptr);
  EXPECT_EQ(compute.calls, 3);
}

TEST(AllowedCollisionCache, ForgetsDestroyedModels) {
  CountingCompute compute;
  const auto call = [&] { return compute(); };
  AllowedCollisionSettings settings;
  settings.seed = 202;
  RobotModelPtr model = builtinRobot("ur5");
  (void)cachedAllowedCollisionMatrix(model, settings, call);
  const std::size_t live = allowedCollisionCacheSize();
  model.reset();
  EXPECT_EQ(allowedCollisionCacheSize(), live - 1);
  // A new model (possibly at the same address) is computed afresh.
  model = builtinRobot("ur5");
  (void)cachedAllowedCollisionMatrix(model, settings, call);
  EXPECT_EQ(compute.calls, 2);
}

TEST(AllowedCollisionCache, ConcurrentFirstRequestsComputeOnce) {
  const RobotModelPtr model = builtinRobot("iiwa14");
  CountingCompute compute;
  AllowedCollisionSettings settings;
  settings.seed = 303;
  std::vector<std::shared_ptr<const AllowedCollisionMatrix>> results(8);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < results.size(); ++t) {
    threads.emplace_back([&, t] {
      results[t] = cachedAllowedCollisionMatrix(model, settings, [&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        return compute();
      });
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(compute.calls, 1);
  for (const auto& result : results) EXPECT_EQ(result, results.front());
}

TEST(AllowedCollisionCache, AFailedComputationIsRetried) {
  const RobotModelPtr model = builtinRobot("tx90");
  AllowedCollisionSettings settings;
  settings.seed = 404;
  int calls = 0;
  const auto failing = [&]() -> AllowedCollisionMatrix {
    ++calls;
    throw std::runtime_error("no matrix today");
  };
  EXPECT_THROW((void)cachedAllowedCollisionMatrix(model, settings, failing), std::runtime_error);
  EXPECT_THROW((void)cachedAllowedCollisionMatrix(model, settings, failing), std::runtime_error);
  EXPECT_EQ(calls, 2);
  CountingCompute compute;
  EXPECT_NE(cachedAllowedCollisionMatrix(model, settings, [&] { return compute(); }), nullptr);
}

TEST(AllowedCollisionCache, CheckersOfOneModelShareTheMatrix) {
  Scene scene = robotOnlyScene("panda");
  const FclCollisionChecker first(scene);
  const FclCollisionChecker second(scene);
  EXPECT_EQ(first.sharedAllowedCollisions(0), second.sharedAllowedCollisions(0));
  // A model loaded again is another model: its matrix is computed again, and equal (seeded).
  const FclCollisionChecker other(robotOnlyScene("panda"));
  EXPECT_NE(other.sharedAllowedCollisions(0), first.sharedAllowedCollisions(0));
  const AllowedCollisionMatrix& a = first.allowedCollisions(0);
  const AllowedCollisionMatrix& b = other.allowedCollisions(0);
  for (int i = 0; i < a.linkCount(); ++i) {
    for (int j = 0; j < a.linkCount(); ++j) ASSERT_EQ(a.reason(i, j), b.reason(i, j));
  }
}

}  // namespace
}  // namespace lang2manip::test
