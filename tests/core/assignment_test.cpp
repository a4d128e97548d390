#include "lang2manip/core/assignment.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

namespace lang2manip {
namespace {

double totalCost(const std::vector<std::vector<double>>& costs, const std::vector<std::size_t>& columns) {
  double total = 0.0;
  for (std::size_t row = 0; row < costs.size(); ++row) total += costs[row][columns[row]];
  return total;
}

/// The least total over every injective map of rows to columns.
double cheapestByEnumeration(const std::vector<std::vector<double>>& costs) {
  std::vector<std::size_t> order(costs.front().size());
  std::iota(order.begin(), order.end(), 0);
  double best = 1e300;
  do {
    best = std::min(best, totalCost(costs, order));
  } while (std::next_permutation(order.begin(), order.end()));
  return best;
}

TEST(CheapestAssignment, MatchesEnumerationOnRandomRectangularMatrices) {
  std::mt19937 generator(7);
  std::uniform_real_distribution<double> cost(0.0, 10.0);
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t columns = 1 + static_cast<std::size_t>(trial % 6);
    const std::size_t rows = 1 + static_cast<std::size_t>(trial / 6) % columns;
    std::vector<std::vector<double>> costs(rows, std::vector<double>(columns));
    for (auto& row : costs) {
      for (double& value : row) value = trial % 3 == 0 ? std::floor(cost(generator)) : cost(generator);  // ties too
    }
    const std::vector<std::size_t> assigned = cheapestAssignment(costs);
    ASSERT_EQ(assigned.size(), rows);
    std::vector<std::size_t> sorted = assigned;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << "a column used twice";
    EXPECT_NEAR(totalCost(costs, assigned), cheapestByEnumeration(costs), 1e-9) << "trial " << trial;
  }
}

TEST(CheapestAssignment, RefusesMoreRowsThanColumnsAndRaggedRows) {
  EXPECT_TRUE(cheapestAssignment({}).empty());
  EXPECT_THROW((void)cheapestAssignment({{1.0}, {2.0}}), std::invalid_argument);
  EXPECT_THROW((void)cheapestAssignment({{1.0, 2.0}, {2.0}}), std::invalid_argument);
}

}  // namespace
}  // namespace lang2manip
