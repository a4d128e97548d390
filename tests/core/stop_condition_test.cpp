#include "lang2manip/core/stop_condition.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <thread>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/random.hpp"

namespace lang2manip {
namespace {

TEST(StopCondition, NeverStopsWithoutDeadlineOrFlag) {
  const StopCondition never = StopCondition::never();
  EXPECT_FALSE(never.shouldStop());
  EXPECT_TRUE(std::isinf(never.secondsLeft()));
}

TEST(StopCondition, StopsAfterDeadline) {
  const StopCondition soon = StopCondition::afterSeconds(0.001);
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_TRUE(soon.shouldStop());
  EXPECT_EQ(soon.secondsLeft(), 0.0);
  EXPECT_FALSE(StopCondition::afterSeconds(100.0).shouldStop());
}

TEST(StopCondition, StopsWhenCancelledAndCombines) {
  auto flag = std::make_shared<std::atomic<bool>>(false);
  const StopCondition combined =
      StopCondition::afterSeconds(100.0).orElse(StopCondition::onCancel(flag));
  EXPECT_FALSE(combined.shouldStop());
  flag->store(true);
  EXPECT_TRUE(combined.shouldStop());
  EXPECT_LE(combined.secondsLeft(), 100.0);
}

TEST(StopCondition, RejectsZeroNegativeAndNanBudgets) {
  EXPECT_THROW(StopCondition::afterSeconds(0.0), InputError);
  EXPECT_THROW(StopCondition::afterSeconds(-1.0), InputError);
  EXPECT_THROW(StopCondition::afterSeconds(std::nan("")), InputError);
  EXPECT_THROW(StopCondition::onCancel(nullptr), InputError);
}

TEST(RandomTest, SameSeedSameSequenceAndRange) {
  Random a(42);
  Random b(42);
  for (int i = 0; i < 100; ++i) {
    const double x = a.uniform(-1.0, 2.0);
    EXPECT_EQ(x, b.uniform(-1.0, 2.0));
    EXPECT_GE(x, -1.0);
    EXPECT_LT(x, 2.0);
  }
  EXPECT_NE(Random(1).unit(), Random(2).unit());
  const VectorX sample = a.uniformVector(Vector3(0, 1, 2), Vector3(0.5, 1.5, 2.5));
  EXPECT_TRUE((sample.array() >= Vector3(0, 1, 2).array()).all());
}

}  // namespace
}  // namespace lang2manip
