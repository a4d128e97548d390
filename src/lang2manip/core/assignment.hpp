#pragma once
/// @file The cheapest one-to-one assignment of rows to columns (the Hungarian method).

#include <cstddef>
#include <vector>

namespace lang2manip {

/// For a cost matrix of R rows and C >= R columns (every row of the same length), the column of
/// each row such that no two rows share a column and the summed cost is least. Ties go to the
/// assignment found first (deterministic). Throws std::invalid_argument when a row's length
/// differs or there are more rows than columns.
std::vector<std::size_t> cheapestAssignment(const std::vector<std::vector<double>>& costs);

}  // namespace lang2manip
