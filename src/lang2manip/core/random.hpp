#pragma once
/// @file Seeded random numbers: the same seed gives the same sequence on every platform run.

#include <cstdint>
#include <random>

#include "lang2manip/core/types.hpp"

namespace lang2manip {

/// A seeded generator. Not thread-safe: give each thread its own (see forThread()).
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  /// Uniform in [lower, upper).
  double uniform(double lower, double upper) {
    return lower + (upper - lower) * unit();
  }

  /// Uniform in [0, 1), computed from the raw engine output so that it is identical on every
  /// standard library (std::uniform_real_distribution is not).
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  /// Each component uniform within [lower_i, upper_i).
  VectorX uniformVector(const VectorX& lower, const VectorX& upper);

  /// Uniform integer in [0, count).
  std::uint64_t index(std::uint64_t count) { return count == 0 ? 0 : engine_() % count; }

  /// A generator for worker `thread` derived deterministically from this one's seed stream.
  Random forThread(std::uint64_t thread);

  std::mt19937_64& engine() { return engine_; }

 private:
  std::mt19937_64 engine_;
};

}  // namespace lang2manip
