#pragma once
/// @file Summary statistics the benchmark commands print.

#include <algorithm>
#include <numeric>
#include <vector>

namespace lang2manip {

/// The value at `fraction` (0.5 = median) of `values` by nearest rank; 0 when empty.
inline double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  const auto index = static_cast<std::size_t>(fraction * static_cast<double>(values.size() - 1) + 0.5);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index), values.end());
  return values[index];
}

inline double mean(const std::vector<double>& values) {
  if (values.empty()) return 0.0;
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

inline double maximum(const std::vector<double>& values) {
  return values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
}

}  // namespace lang2manip
