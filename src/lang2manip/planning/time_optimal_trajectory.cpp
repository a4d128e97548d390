#include "lang2manip/planning/time_optimal_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>

#include "lang2manip/core/error.hpp"
#include "lang2manip/planning/blended_path.hpp"
#include "lang2manip/planning/phase_integrator.hpp"
#include "lang2manip/planning/phase_plane.hpp"
#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {
namespace {

InputError badInput(const std::string& message) {
  return InputError("time-optimal parameterization: " + message);
}

// Bounds on the work of one call: integration steps of all pieces (lines take one or two; arcs
// one per time step: a thousand seconds on arcs at 1 ms), and output points.
constexpr std::size_t kMaxIntegrationSteps = 1'000'000;
constexpr double kMaxOutputPoints = 1e7;
// A regular sample closer than this fraction of sampleInterval to the end is left out.
constexpr double kMinLastGap = 1e-3;

void checkOptions(const TimeOptimalOptions& options) {
  const auto check = [](double value, bool valid, const std::string& what) {
    if (!valid) throw badInput(what + " (got " + std::to_string(value) + ")");
  };
  check(options.maxDeviation, options.maxDeviation >= 0.0 && std::isfinite(options.maxDeviation),
        "max deviation must be finite and >= 0");
  check(options.velocityScaling, options.velocityScaling > 0.0 && options.velocityScaling <= 1.0,
        "velocity scaling must be in (0, 1]");
  check(options.accelerationScaling, options.accelerationScaling > 0.0 && options.accelerationScaling <= 1.0,
        "acceleration scaling must be in (0, 1]");
  check(options.timeStep, options.timeStep > 0.0 && std::isfinite(options.timeStep),
        "time step must be positive and finite");
  check(options.sampleInterval, options.sampleInterval > 0.0 && std::isfinite(options.sampleInterval),
        "sample interval must be positive and finite");
}

void checkLimits(const VectorX& limits, const std::vector<std::string>& names, const std::string& kind) {
  if (limits.size() != static_cast<Eigen::Index>(names.size())) {
    throw badInput(std::to_string(limits.size()) + " " + kind + " limits for " +
                   std::to_string(names.size()) + " joints");
  }
  for (Eigen::Index i = 0; i < limits.size(); ++i) {
    if (!(limits[i] > 0.0 && std::isfinite(limits[i]))) {
      throw badInput("joint " + names[static_cast<std::size_t>(i)] + " has " + kind + " limit " +
                     numberText(limits[i]) + "; it must be positive and finite");
    }
  }
}

/// What both overloads share: the limited joints (q = J x, J the identity when null) and how
/// output positions are made from path points.
struct JointMap {
  const MatrixX* jacobian = nullptr;
  const PlanningSpace* space = nullptr;
  std::vector<std::string> names;

  [[nodiscard]] VectorX positions(const VectorX& x) const { return space != nullptr ? space->trajectoryPositions(x) : x; }
};

/// Turns phase trajectories (piece by piece) into output points every sampleInterval.
class TrajectorySampler {
 public:
  TrajectorySampler(const totg::PhasePlane& plane, const JointMap& map, double interval, JointTrajectory& out)
      : plane_(plane), map_(map), interval_(interval), out_(out) {}

  // Emits the samples of one piece (segments first..lastSegment) that starts at time start_.
  // lastPiece: no piece follows (the end point is added by addEnd()).
  void addPiece(const std::vector<totg::PhasePoint>& points, std::size_t first, std::size_t lastSegment,
                  bool lastPiece);
  void addEnd(const VectorX& position);

 private:
  void addPoint(const totg::PhasePoint& from, const totg::PhasePoint& to, double elapsed, double time,
                std::size_t first, std::size_t lastSegment);

  const totg::PhasePlane& plane_;
  const JointMap& map_;
  double interval_;
  JointTrajectory& out_;
  double start_ = 0.0;
  std::size_t nextSample_ = 0;
  std::vector<double> times_;
};

void TrajectorySampler::addPiece(const std::vector<totg::PhasePoint>& points, std::size_t first,
                                 std::size_t lastSegment, bool lastPiece) {
  if (points.size() < 2) return;
  times_.assign(points.size(), start_);
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double speeds = points[i - 1].v + points[i].v;
    const double ds = points[i].s - points[i - 1].s;
    times_[i] = times_[i - 1] + (speeds > 0.0 && ds > 0.0 ? 2.0 * ds / speeds : 0.0);
  }
  const double end = times_.back();
  if (end / interval_ > kMaxOutputPoints) {
    throw badInput("more than 1e7 output points (a trajectory of " + std::to_string(end) +
                   " s); use a larger sample interval");
  }
  const double stop = lastPiece ? end - kMinLastGap * interval_ : end;
  std::size_t j = 0;
  for (double t = static_cast<double>(nextSample_) * interval_; t < stop;
       t = static_cast<double>(++nextSample_) * interval_) {
    while (j + 2 < points.size() && times_[j + 1] <= t) ++j;
    addPoint(points[j], points[j + 1], t - times_[j], t, first, lastSegment);
  }
  start_ = end;
}

void TrajectorySampler::addPoint(const totg::PhasePoint& from, const totg::PhasePoint& to, double elapsed,
                                 double time, std::size_t first, std::size_t lastSegment) {
  const double ds = to.s - from.s;
  const double acceleration = ds > 0.0 ? (to.v * to.v - from.v * from.v) / (2.0 * ds) : 0.0;
  const double duration = from.v + to.v > 0.0 ? 2.0 * ds / (from.v + to.v) : 0.0;
  const double tau = std::clamp(elapsed, 0.0, duration);
  const double s = std::clamp(from.s + from.v * tau + 0.5 * acceleration * tau * tau, from.s, to.s);
  const double v = std::max(0.0, from.v + acceleration * tau);
  const std::size_t k = std::clamp(plane_.path().segmentIndex(s), first, lastSegment);
  const PathSegment& segment = plane_.path().segments()[k];
  TrajectoryPoint point;
  point.positions = map_.positions(segment.position(s - segment.start));
  point.velocities.resize(plane_.jointCount());
  point.accelerations.resize(plane_.jointCount());
  plane_.jointMotion(k, s, v, acceleration, point.velocities, point.accelerations);
  point.time = time;
  out_.points.push_back(std::move(point));
}

void TrajectorySampler::addEnd(const VectorX& position) {
  TrajectoryPoint point;
  point.positions = map_.positions(position);
  point.velocities = VectorX::Zero(plane_.jointCount());
  point.accelerations = VectorX::Zero(plane_.jointCount());
  point.time = start_;
  out_.points.push_back(std::move(point));
}

JointTrajectory parameterize(const BlendedPath& blended, const VectorX& maxVelocity,
                             const VectorX& maxAcceleration, const TimeOptimalOptions& options,
                             const JointMap& map) {
  checkLimits(maxVelocity, map.names, "velocity");
  checkLimits(maxAcceleration, map.names, "acceleration");
  JointTrajectory trajectory;
  trajectory.jointNames = map.names;
  const auto joints = static_cast<Eigen::Index>(map.names.size());
  if (blended.segments().empty()) {
    trajectory.points.push_back({map.positions(blended.waypoints().front()), VectorX::Zero(joints),
                                 VectorX::Zero(joints), 0.0});
    return trajectory;
  }
  const totg::PhasePlane plane(blended, map.jacobian, maxVelocity * options.velocityScaling,
                               maxAcceleration * options.accelerationScaling);
  totg::PhaseIntegrator integrator(plane, options.timeStep, kMaxIntegrationSteps);
  TrajectorySampler sampler(plane, map, options.sampleInterval, trajectory);
  // Rest-to-rest pieces between the stop points (each the exact start of a segment).
  std::vector<std::size_t> pieceStarts{0};
  for (const double stop : blended.stopPoints()) pieceStarts.push_back(blended.segmentIndex(stop));
  pieceStarts.push_back(blended.segments().size());
  for (std::size_t p = 0; p + 1 < pieceStarts.size(); ++p) {
    const std::size_t first = pieceStarts[p];
    const std::size_t last = pieceStarts[p + 1] - 1;
    sampler.addPiece(integrator.integratePiece(first, last), first, last, p + 2 == pieceStarts.size());
  }
  sampler.addEnd(blended.position(blended.length()));
  return trajectory;
}

}  // namespace

JointTrajectory timeOptimalParameterize(const std::vector<VectorX>& path, const VectorX& maxVelocity,
                                        const VectorX& maxAcceleration, const TimeOptimalOptions& options) {
  checkOptions(options);
  if (path.empty()) throw badInput("the path is empty (no waypoints)");
  JointMap map;
  for (Eigen::Index i = 0; i < path.front().size(); ++i) map.names.push_back("joint_" + std::to_string(i));
  return parameterize(BlendedPath(path, options.maxDeviation), maxVelocity, maxAcceleration, options, map);
}

JointTrajectory timeOptimalParameterize(const PlanningSpace& space, const std::vector<VectorX>& path,
                                        const TimeOptimalOptions& options) {
  checkOptions(options);
  if (path.empty()) throw badInput("the path is empty (no waypoints)");
  for (std::size_t i = 0; i < path.size(); ++i) space.checkPoint(path[i], "path point " + std::to_string(i));
  return timeOptimalParameterize(space, BlendedPath(path, options.maxDeviation), options);
}

JointTrajectory timeOptimalParameterize(const PlanningSpace& space, const BlendedPath& path,
                                        const TimeOptimalOptions& options) {
  checkOptions(options);
  if (path.dimension() != space.dimension()) {
    throw badInput("the path has " + std::to_string(path.dimension()) + " coordinates; the space has " +
                   std::to_string(space.dimension()));
  }
  JointMap map;
  map.jacobian = &space.trajectoryJacobian();
  map.space = &space;
  map.names = space.trajectoryJointNames();
  return parameterize(path, space.jointVelocityLimits(), space.jointAccelerationLimits(), options, map);
}

}  // namespace lang2manip
