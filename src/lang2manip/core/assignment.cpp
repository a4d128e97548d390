// The Hungarian method with potentials (Kuhn 1955, Munkres 1957), O(R^2 C), for rectangular
// matrices: rows are added one at a time and each is given a column along the shortest
// augmenting path in reduced costs.

#include "lang2manip/core/assignment.hpp"

#include <limits>
#include <stdexcept>

namespace lang2manip {

std::vector<std::size_t> cheapestAssignment(const std::vector<std::vector<double>>& costs) {
  const std::size_t rows = costs.size();
  if (rows == 0) return {};
  const std::size_t columns = costs.front().size();
  for (const auto& row : costs) {
    if (row.size() != columns) throw std::invalid_argument("cheapestAssignment: rows of different lengths");
  }
  if (rows > columns) throw std::invalid_argument("cheapestAssignment: more rows than columns");
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  constexpr std::size_t kNone = 0;  // 1-based indices below; 0 is the virtual start
  std::vector<double> rowPotential(rows + 1, 0.0), columnPotential(columns + 1, 0.0);
  std::vector<std::size_t> rowOfColumn(columns + 1, kNone), previous(columns + 1, kNone);
  for (std::size_t row = 1; row <= rows; ++row) {
    rowOfColumn[0] = row;
    std::size_t column = 0;
    std::vector<double> slack(columns + 1, kInfinity);
    std::vector<bool> used(columns + 1, false);
    do {
      used[column] = true;
      const std::size_t from = rowOfColumn[column];
      double delta = kInfinity;
      std::size_t next = kNone;
      for (std::size_t j = 1; j <= columns; ++j) {
        if (used[j]) continue;
        const double reduced = costs[from - 1][j - 1] - rowPotential[from] - columnPotential[j];
        if (reduced < slack[j]) slack[j] = reduced, previous[j] = column;
        if (slack[j] < delta) delta = slack[j], next = j;
      }
      for (std::size_t j = 0; j <= columns; ++j) {
        if (used[j]) {
          rowPotential[rowOfColumn[j]] += delta;
          columnPotential[j] -= delta;
        } else {
          slack[j] -= delta;
        }
      }
      column = next;
    } while (rowOfColumn[column] != kNone);
    do {  // flip the augmenting path
      const std::size_t back = previous[column];
      rowOfColumn[column] = rowOfColumn[back];
      column = back;
    } while (column != 0);
  }
  std::vector<std::size_t> columnOfRow(rows);
  for (std::size_t j = 1; j <= columns; ++j) {
    if (rowOfColumn[j] != kNone) columnOfRow[rowOfColumn[j] - 1] = j - 1;
  }
  return columnOfRow;
}

}  // namespace lang2manip
