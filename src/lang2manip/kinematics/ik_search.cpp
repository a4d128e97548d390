#include "lang2manip/kinematics/ik_search.hpp"

#include <cmath>
#include <numbers>

namespace lang2manip {

bool IkSearch::shouldStop() noexcept {
  if (!stopped_) stopped_ = problem_.stop.shouldStop();
  return stopped_;
}

bool IkSearch::done() noexcept {
  return static_cast<int>(solutions_.size()) >= problem_.solutionCount ||
         attempts_ >= maxAttempts_ || shouldStop();
}

bool IkSearch::withinLimits(const VectorX& qc) const noexcept {
  return (qc.array() >= problem_.lower.array()).all() &&
         (qc.array() <= problem_.upper.array()).all();
}

bool IkSearch::isDistinct(const VectorX& qc) const noexcept {
  for (const VectorX& solution : solutions_) {
    if ((solution - qc).cwiseAbs().maxCoeff() <= kDistinctTolerance) return false;
  }
  return true;
}

void IkSearch::addSolution(const VectorX& qc, const Pose& X_BT) {
  double positionError = 0.0;
  double orientationError = 0.0;
  ikTargetError(problem_.target, X_BT, positionError, orientationError);
  if (positionError > problem_.positionTolerance ||
      orientationError > problem_.orientationTolerance || !withinLimits(qc)) {
    recordFailure(qc, X_BT);
    return;
  }
  if (!isDistinct(qc)) return;
  if (solutions_.empty()) {
    bestSolutionPositionError_ = positionError;
    bestSolutionOrientationError_ = orientationError;
  }
  solutions_.push_back(qc);
}

void IkSearch::recordFailure(const VectorX& qc, const Pose& X_BT) noexcept {
  double positionError = 0.0;
  double orientationError = 0.0;
  ikTargetError(problem_.target, X_BT, positionError, orientationError);
  if (positionError + orientationError >= bestPositionError_ + bestOrientationError_) return;
  bestPositionError_ = positionError;
  bestOrientationError_ = orientationError;
  limitVariable_ = -1;
  for (Eigen::Index i = 0; i < qc.size(); ++i) {
    if (qc[i] <= problem_.lower[i] || qc[i] >= problem_.upper[i]) limitVariable_ = static_cast<int>(i);
  }
}

void IkSearch::randomConfiguration(Random& random, VectorX& qc) const noexcept {
  for (Eigen::Index i = 0; i < qc.size(); ++i) {
    const double lower = std::isfinite(problem_.lower[i]) ? problem_.lower[i] : -std::numbers::pi;
    const double upper = std::isfinite(problem_.upper[i]) ? problem_.upper[i] : std::numbers::pi;
    qc[i] = random.uniform(lower, upper);
  }
}

IkResult IkSearch::result() const {
  IkResult result;
  result.iterations = iterations_;
  result.attempts = attempts_;
  if (!solutions_.empty()) {
    result.status = IkStatus::kSuccess;
    result.solutions = solutions_;
    result.positionError = bestSolutionPositionError_;
    result.orientationError = bestSolutionOrientationError_;
    return result;
  }
  result.positionError = bestPositionError_;
  result.orientationError = bestOrientationError_;
  const std::string best = "best attempt off by " + std::to_string(bestPositionError_) + " m and " +
                           std::to_string(bestOrientationError_) + " rad";
  if (limitVariable_ >= 0) {
    const int variable = problem_.chain.variables()[static_cast<std::size_t>(limitVariable_)];
    result.status = IkStatus::kJointLimits;
    result.message = "no solution within the joint limits after " + std::to_string(attempts_) +
                     " attempts; the " + best + " pressed against the limit of joint \"" +
                     problem_.model.variableNames()[static_cast<std::size_t>(variable)] + "\"";
  } else {
    result.status = stopped_ ? IkStatus::kTimeout : IkStatus::kNoConvergence;
    result.message = std::string(stopped_ ? "time budget spent" : "did not converge") + " after " +
                     std::to_string(attempts_) + " attempts (" + std::to_string(iterations_) +
                     " iterations); " + best;
  }
  return result;
}

}  // namespace lang2manip
