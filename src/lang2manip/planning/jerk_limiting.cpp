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

/// A trajectory's positions, velocities and accelerations on an even grid of `interval`.
struct EvenSamples {
  double interval = 0.0;
  std::vector<TrajectoryPoint> points;
};

TrajectoryPoint interpolated(const TrajectoryPoint& a, const TrajectoryPoint& b, double time) {
  const double span = b.time - a.time;
  const double f = span > 0.0 ? std::clamp((time - a.time) / span, 0.0, 1.0) : 1.0;
  return {a.positions + f * (b.positions - a.positions), a.velocities + f * (b.velocities - a.velocities),
          a.accelerations + f * (b.accelerations - a.accelerations), time};
}

/// `trajectory` on the even grid closest to its first interval that ends exactly at its end.
EvenSamples evenSamples(const JointTrajectory& trajectory) {
  const double duration = trajectory.duration();
  const double first = trajectory.points[1].time - trajectory.points[0].time;
  const auto steps = static_cast<std::size_t>(std::max(1.0, std::ceil(duration / first - 1e-9)));
  EvenSamples samples{duration / static_cast<double>(steps), {}};
  samples.points.reserve(steps + 1);
  std::size_t at = 0;
  for (std::size_t k = 0; k <= steps; ++k) {
    const double time = k == steps ? duration : static_cast<double>(k) * samples.interval;
    while (at + 2 < trajectory.points.size() && trajectory.points[at + 1].time <= time) ++at;
    samples.points.push_back(interpolated(trajectory.points[at], trajectory.points[at + 1], time));
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

/// The moving average over `width` samples of `samples` at rest before and after: entry m
/// averages samples m - width + 1 .. m (clamped to the ends), for m = 0 .. size + width - 2.
std::vector<TrajectoryPoint> movingAverage(const EvenSamples& samples, std::size_t width) {
  const std::vector<TrajectoryPoint>& in = samples.points;
  const auto count = static_cast<std::ptrdiff_t>(in.size());
  const VectorX zero = VectorX::Zero(in[0].positions.size());
  const TrajectoryPoint before{in.front().positions, zero, zero, 0.0};
  const TrajectoryPoint after{in.back().positions, zero, zero, 0.0};
  const auto at = [&](std::ptrdiff_t k) -> const TrajectoryPoint& {
    return k < 0 ? before : k >= count ? after : in[static_cast<std::size_t>(k)];
  };
  TrajectoryPoint sum{zero, zero, zero, 0.0};
  const auto w = static_cast<std::ptrdiff_t>(width);
  for (std::ptrdiff_t k = -w + 1; k <= 0; ++k) {
    sum.positions += at(k).positions;
    sum.velocities += at(k).velocities;
    sum.accelerations += at(k).accelerations;
  }
  std::vector<TrajectoryPoint> out;
  out.reserve(in.size() + width - 1);
  const double scale = 1.0 / static_cast<double>(width);
  for (std::ptrdiff_t m = 0; m < count + w - 1; ++m) {
    if (m > 0) {
      sum.positions += at(m).positions - at(m - w).positions;
      sum.velocities += at(m).velocities - at(m - w).velocities;
      sum.accelerations += at(m).accelerations - at(m - w).accelerations;
    }
    out.push_back({sum.positions * scale, sum.velocities * scale, sum.accelerations * scale,
                   static_cast<double>(m) * samples.interval});
  }
  out.back().positions = in.back().positions;  // exact, not a sum's rounding
  return out;
}

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
  const EvenSamples samples = evenSamples(trajectory);
  // An odd width (T / interval + 1 samples, within 0.1%) centres each average on a sample.
  const std::size_t width = 2 * static_cast<std::size_t>(std::ceil(result.window / (2.0 * samples.interval) - 1e-3)) + 1;
  const std::vector<TrajectoryPoint> averaged = movingAverage(samples, width);
  const std::size_t delay = (width - 1) / 2;
  for (std::size_t m = 0; m < averaged.size(); ++m) {
    const std::size_t source = std::min(samples.points.size() - 1, m >= delay ? m - delay : 0);
    result.deviation = std::max(result.deviation, (averaged[m].positions - samples.points[source].positions).norm());
  }
  result.trajectory.jointNames = trajectory.jointNames;
  const auto stride = static_cast<std::size_t>(std::max(1.0, std::round(outputInterval / samples.interval)));
  for (std::size_t m = 0; m < averaged.size(); m += stride) result.trajectory.points.push_back(averaged[m]);
  if (result.trajectory.points.back().time < averaged.back().time) result.trajectory.points.push_back(averaged.back());
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
