#pragma once
/// @file Book-keeping shared by the IK solvers that restart: counters, the stop condition,
/// distinct solutions, the best failed attempt and the final status. Per call, not thread-safe.

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "lang2manip/core/random.hpp"
#include "lang2manip/kinematics/ik_solver.hpp"

namespace lang2manip {

class IkSearch {
 public:
  /// Two solutions are distinct when some chain variable differs by more than this (rad or m).
  static constexpr double kDistinctTolerance = 1e-3;

  explicit IkSearch(const IkProblem& problem) : problem_(problem) {
    if (problem.maxAttempts > 0) maxAttempts_ = problem.maxAttempts;
  }

  /// Ends the search after `attempts` attempts (default: only the stop condition ends it).
  void setMaxAttempts(int attempts) noexcept { maxAttempts_ = std::min(maxAttempts_, attempts); }

  /// True once the stop condition fired (checked now), and from then on.
  bool shouldStop() noexcept;
  /// True when enough solutions were found, the attempts are spent or the search was stopped.
  bool done() noexcept;

  void countIteration(int count = 1) noexcept { iterations_ += count; }
  void countAttempt() noexcept { ++attempts_; }

  /// Keeps chain configuration `qc` (tip pose X_BT) if it meets the tolerances within the limits
  /// and differs from the solutions already kept; otherwise records it as a failure.
  void addSolution(const VectorX& qc, const Pose& X_BT);
  /// Remembers the best failed attempt (its errors, and whether it ended at a joint limit).
  void recordFailure(const VectorX& qc, const Pose& X_BT) noexcept;

  /// A uniformly random configuration within the limits (+-pi where a limit is infinite).
  void randomConfiguration(Random& random, VectorX& qc) const noexcept;

  /// The result so far: success with the solutions, or the reason of the failure.
  [[nodiscard]] IkResult result() const;

 private:
  [[nodiscard]] bool isDistinct(const VectorX& qc) const noexcept;
  [[nodiscard]] bool withinLimits(const VectorX& qc) const noexcept;

  const IkProblem& problem_;
  std::vector<VectorX> solutions_;
  double bestPositionError_ = std::numeric_limits<double>::infinity();
  double bestOrientationError_ = std::numeric_limits<double>::infinity();
  double bestSolutionPositionError_ = 0.0;
  double bestSolutionOrientationError_ = 0.0;
  int limitVariable_ = -1;
  int iterations_ = 0;
  int attempts_ = 0;
  int maxAttempts_ = std::numeric_limits<int>::max();
  bool stopped_ = false;
};

}  // namespace lang2manip
