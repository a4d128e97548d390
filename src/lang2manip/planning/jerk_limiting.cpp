#include "lang2manip/planning/jerk_limiting.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {
namespace {

/// A trajectory's positions, velocities and accelerations on an even grid of `interval`: one
/// column per sample.
struct EvenSamples {
  double interval = 0.0;
  MatrixX positions;
  MatrixX velocities;
  MatrixX accelerations;

  [[nodiscard]] Eigen::Index count() const { return positions.cols(); }
};

/// `trajectory` on the even grid closest to its first interval that ends exactly at its end
/// (linear interpolation between its points).
EvenSamples evenSamples(const JointTrajectory& trajectory) {
  const double duration = trajectory.duration();
  const double first = trajectory.points[1].time - trajectory.points[0].time;
  const auto steps = static_cast<Eigen::Index>(std::max(1.0, std::ceil(duration / first - 1e-9)));
  const Eigen::Index joints = trajectory.points[0].positions.size();
  EvenSamples samples{duration / static_cast<double>(steps), MatrixX(joints, steps + 1), MatrixX(joints, steps + 1),
                      MatrixX(joints, steps + 1)};
  std::size_t at = 0;
  for (Eigen::Index k = 0; k <= steps; ++k) {
    const double time = k == steps ? duration : static_cast<double>(k) * samples.interval;
    while (at + 2 < trajectory.points.size() && trajectory.points[at + 1].time <= time) ++at;
    const TrajectoryPoint& a = trajectory.points[at];
    const TrajectoryPoint& b = trajectory.points[at + 1];
    const double span = b.time - a.time;
    const double f = span > 0.0 ? std::clamp((time - a.time) / span, 0.0, 1.0) : 1.0;
    samples.positions.col(k) = a.positions + f * (b.positions - a.positions);
    samples.velocities.col(k) = a.velocities + f * (b.velocities - a.velocities);
    samples.accelerations.col(k) = a.accelerations + f * (b.accelerations - a.accelerations);
  }
  return samples;
}

void checkInputs(const JointTrajectory& trajectory, const VectorX& maxAcceleration, const VectorX& maxJerk,
                 double outputInterval) {
  if (trajectory.points.size() < 2) throw InputError("jerk limits: the trajectory has fewer than two points");
  const Eigen::Index joints = trajectory.points.front().positions.size();
  if (maxAcceleration.size() != joints || maxJerk.size() != joints) {
    throw InputError("jerk limits: " + std::to_string(joints) + " joints but " + std::to_string(maxAcceleration.size()) +
                     " acceleration and " + std::to_string(maxJerk.size()) + " jerk limits");
  }
  for (Eigen::Index i = 0; i < joints; ++i) {
    const std::string joint = i < static_cast<Eigen::Index>(trajectory.jointNames.size())
                                  ? trajectory.jointNames[static_cast<std::size_t>(i)]
                                  : "joint " + std::to_string(i);
    if (!(std::isfinite(maxJerk[i]) && maxJerk[i] >= 0.0) || !(std::isfinite(maxAcceleration[i]) && maxAcceleration[i] >= 0.0)) {
      throw InputError("jerk limits: " + joint + ": limits must be finite and not negative (acceleration " +
                       numberText(maxAcceleration[i]) + ", jerk " + numberText(maxJerk[i]) + ")");
    }
    if (maxJerk[i] > 0.0 && maxAcceleration[i] == 0.0) throw InputError("jerk limits: " + joint + " has a jerk limit but no acceleration limit");
  }
  for (const TrajectoryPoint* end : {&trajectory.points.front(), &trajectory.points.back()}) {
    if (end->velocities.cwiseAbs().maxCoeff() > 1e-9) throw InputError("jerk limits: the trajectory must start and end at rest");
  }
  if (!(outputInterval > 0.0)) throw InputError("jerk limits: the output interval must be positive");
}

/// Refuses a filter window or sample count beyond kMaxJerkWindow / kMaxJerkSamples (a jerk limit
/// in the wrong unit, or a trajectory sampled too finely), naming the joint that sets the window.
void checkWorkBound(const JointTrajectory& trajectory, const VectorX& maxAcceleration, const VectorX& maxJerk,
                    double window) {
  if (window > kMaxJerkWindow) {
    Eigen::Index widest = 0;
    for (Eigen::Index i = 0; i < maxJerk.size(); ++i) {
      if (maxJerk[i] > 0.0 && 2.0 * maxAcceleration[i] / maxJerk[i] == window) widest = i;
    }
    const std::string joint = widest < static_cast<Eigen::Index>(trajectory.jointNames.size())
                                  ? trajectory.jointNames[static_cast<std::size_t>(widest)]
                                  : "joint " + std::to_string(widest);
    throw InputError("jerk limits: " + joint + "'s jerk limit " + numberText(maxJerk[widest]) + " with acceleration limit " +
                     numberText(maxAcceleration[widest]) + " needs a " + numberText(window) + " s filter window (at most " +
                     numberText(kMaxJerkWindow) + " s): raise max_jerk or lower the acceleration (a unit error?)");
  }
  const double first = trajectory.points[1].time - trajectory.points[0].time;
  const double samples = first > 0.0 ? (trajectory.duration() + window) / first : 0.0;
  if (samples > static_cast<double>(kMaxJerkSamples)) {
    throw InputError("jerk limits: a " + numberText(trajectory.duration()) + " s trajectory sampled every " + numberText(first) +
                     " s needs " + numberText(samples) + " filter samples (at most " + std::to_string(kMaxJerkSamples) + ")");
  }
}

/// Running sums over the last `width` samples of one quantity, at rest before and after.
class MovingSum {
 public:
  /// `before` and `after`: one column each, the value held before the first and after the last.
  MovingSum(const MatrixX& samples, const MatrixX& before, const MatrixX& after, Eigen::Index width)
      : samples_(samples), before_(before), after_(after), width_(width),
        sum_(before.col(0) * static_cast<double>(width - 1) + samples.col(0)) {}

  /// Moves the window to end at sample m (m = 0, 1, ... in order; m = 0 needs no call).
  void advanceTo(Eigen::Index m) {
    sum_ += column(m);
    sum_ -= column(m - width_);
  }
  [[nodiscard]] const VectorX& sum() const { return sum_; }

 private:
  [[nodiscard]] Eigen::Block<const MatrixX, Eigen::Dynamic, 1, true> column(Eigen::Index k) const {
    return k < 0 ? before_.col(0) : k >= samples_.cols() ? after_.col(0) : samples_.col(k);
  }

  const MatrixX& samples_;
  const MatrixX& before_;
  const MatrixX& after_;
  Eigen::Index width_;
  VectorX sum_;
};

}  // namespace

JerkLimitedTrajectory limitJerk(const JointTrajectory& trajectory, const VectorX& maxAcceleration,
                                const VectorX& maxJerk, double outputInterval) {
  checkInputs(trajectory, maxAcceleration, maxJerk, outputInterval);
  JerkLimitedTrajectory result;
  for (Eigen::Index i = 0; i < maxJerk.size(); ++i) {
    if (maxJerk[i] > 0.0) result.window = std::max(result.window, 2.0 * maxAcceleration[i] / maxJerk[i]);
  }
  if (result.window == 0.0 || trajectory.duration() == 0.0) {
    result.trajectory = trajectory;
    result.window = 0.0;
    return result;
  }
  checkWorkBound(trajectory, maxAcceleration, maxJerk, result.window);
  const EvenSamples samples = evenSamples(trajectory);
  // An odd width (T / interval + 1 samples, within 0.1%) centres each average on a sample, the
  // one `delay` samples earlier.
  const Eigen::Index width = 2 * static_cast<Eigen::Index>(std::ceil(result.window / (2.0 * samples.interval) - 1e-3)) + 1;
  const Eigen::Index delay = (width - 1) / 2;
  const Eigen::Index count = samples.count();
  const MatrixX zero = MatrixX::Zero(samples.positions.rows(), 1);
  const MatrixX start = samples.positions.col(0);
  const MatrixX end = samples.positions.col(count - 1);
  MovingSum positions(samples.positions, start, end, width);
  MovingSum velocities(samples.velocities, zero, zero, width);
  MovingSum accelerations(samples.accelerations, zero, zero, width);
  const auto stride = static_cast<Eigen::Index>(std::max(1.0, std::round(outputInterval / samples.interval)));
  const double scale = 1.0 / static_cast<double>(width);
  const Eigen::Index last = count + width - 2;
  result.trajectory.jointNames = trajectory.jointNames;
  result.trajectory.points.reserve(static_cast<std::size_t>(last / stride + 2));
  for (Eigen::Index m = 0; m <= last; ++m) {
    if (m > 0) {
      positions.advanceTo(m);
      velocities.advanceTo(m);
      accelerations.advanceTo(m);
    }
    const Eigen::Index source = std::clamp<Eigen::Index>(m - delay, 0, count - 1);
    result.deviation = std::max(result.deviation, (positions.sum() * scale - samples.positions.col(source)).norm());
    if (m % stride == 0 || m == last) {
      result.trajectory.points.push_back({positions.sum() * scale, velocities.sum() * scale,
                                          accelerations.sum() * scale, static_cast<double>(m) * samples.interval});
    }
  }
  result.trajectory.points.back().positions = end.col(0);  // exact, not a sum's rounding
  result.window = static_cast<double>(width - 1) * samples.interval;
  return result;
}

std::string checkJerkLimits(const JointTrajectory& trajectory, const VectorX& maxJerk, double tolerance) {
  for (std::size_t k = 1; k < trajectory.points.size(); ++k) {
    const TrajectoryPoint& a = trajectory.points[k - 1];
    const TrajectoryPoint& b = trajectory.points[k];
    const double span = b.time - a.time;
    for (Eigen::Index i = 0; i < maxJerk.size() && i < a.accelerations.size(); ++i) {
      if (maxJerk[i] <= 0.0 || span <= 0.0) continue;
      const double jerk = std::abs(b.accelerations[i] - a.accelerations[i]) / span;
      if (jerk > maxJerk[i] * (1.0 + tolerance)) {
        const std::string joint = i < static_cast<Eigen::Index>(trajectory.jointNames.size())
                                      ? trajectory.jointNames[static_cast<std::size_t>(i)]
                                      : "joint " + std::to_string(i);
        return joint + ": jerk " + numberText(jerk) + " above its limit " + numberText(maxJerk[i]) + " between points " +
               std::to_string(k - 1) + " and " + std::to_string(k);
      }
    }
  }
  return {};
}

}  // namespace lang2manip
