#include "lang2manip/core/random.hpp"

namespace lang2manip {

VectorX Random::uniformVector(const VectorX& lower, const VectorX& upper) {
  VectorX sample(lower.size());
  for (Eigen::Index i = 0; i < lower.size(); ++i) sample[i] = uniform(lower[i], upper[i]);
  return sample;
}

Random Random::forThread(std::uint64_t thread) {
  return Random(engine_() ^ (0x9E3779B97F4A7C15ULL * (thread + 1)));
}

}  // namespace lang2manip
