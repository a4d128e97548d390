#include "lang2manip/planning/trajectory.hpp"

#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {
namespace {

// A rest-to-rest trapezoid for s in [0, 1] with peak speed `v` and acceleration `a`.
struct Trapezoid {
  double v = 0.0;
  double a = 0.0;
  double accelerationTime = 0.0;
  double cruiseTime = 0.0;

  Trapezoid(double peakSpeed, double acceleration) : v(peakSpeed), a(acceleration) {
    if (v * v / a > 1.0) {  // never reaches v: triangular profile
      v = std::sqrt(a);
      accelerationTime = v / a;
    } else {
      accelerationTime = v / a;
      cruiseTime = (1.0 - v * accelerationTime) / v;
    }
  }
  [[nodiscard]] double duration() const { return 2.0 * accelerationTime + cruiseTime; }

  // s, ds/dt, d2s/dt2 at time t.
  [[nodiscard]] Vector3 at(double t) const {
    const double total = duration();
    if (t <= accelerationTime) return {0.5 * a * t * t, a * t, a};
    if (t <= accelerationTime + cruiseTime) {
      return {0.5 * a * accelerationTime * accelerationTime + v * (t - accelerationTime), v, 0.0};
    }
    const double left = std::max(0.0, total - t);
    return {1.0 - 0.5 * a * left * left, a * left, t >= total ? 0.0 : -a};
  }
};

void appendPoint(const PlanningSpace& space, const VectorX& x, const VectorX& dx,
                 const Vector3& profile, double time, JointTrajectory& trajectory) {
  const MatrixX& jacobian = space.trajectoryJacobian();
  TrajectoryPoint point;
  point.positions = space.trajectoryPositions(x);
  point.velocities = jacobian * dx * profile[1];
  point.accelerations = jacobian * dx * profile[2];
  point.time = time;
  trajectory.points.push_back(std::move(point));
}

}  // namespace

std::string scalingProblem(double scaling) {
  if (scaling >= kSmallestScaling && scaling <= 1.0) return {};
  return numberText(scaling) + ": must be in [" + numberText(kSmallestScaling) + ", 1] (a fraction of the joint limits)";
}

JointTrajectory timeParameterize(const PlanningSpace& space, const std::vector<VectorX>& path,
                                 const TimeParameterizationOptions& options) {
  if (path.empty()) throw InputError("time parameterization: the path is empty");
  if (const std::string problem = scalingProblem(options.velocityScaling); !problem.empty()) {
    throw InputError("time parameterization: velocity scaling " + problem);
  }
  if (const std::string problem = scalingProblem(options.accelerationScaling); !problem.empty()) {
    throw InputError("time parameterization: acceleration scaling " + problem);
  }
  if (!(options.sampleInterval > 0.0 && std::isfinite(options.sampleInterval))) {
    throw InputError("time parameterization: sample interval must be positive");
  }
  for (std::size_t i = 0; i < path.size(); ++i) {
    space.checkPoint(path[i], "path point " + std::to_string(i));
  }
  JointTrajectory trajectory;
  trajectory.jointNames = space.trajectoryJointNames();
  const VectorX zero = VectorX::Zero(space.dimension());
  appendPoint(space, path.front(), zero, Vector3::Zero(), 0.0, trajectory);
  const VectorX velocityLimits = space.jointVelocityLimits() * options.velocityScaling;
  const VectorX accelerationLimits = space.jointAccelerationLimits() * options.accelerationScaling;
  double start = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const VectorX dx = path[i] - path[i - 1];
    const VectorX jointStep = (space.trajectoryJacobian() * dx).cwiseAbs();
    double peak = std::numeric_limits<double>::infinity();
    double acceleration = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < jointStep.size(); ++j) {
      if (jointStep[j] <= 0.0) continue;
      peak = std::min(peak, velocityLimits[j] / jointStep[j]);
      acceleration = std::min(acceleration, accelerationLimits[j] / jointStep[j]);
    }
    if (!std::isfinite(peak)) continue;  // a repeated waypoint
    const Trapezoid profile(peak, acceleration);
    const double duration = profile.duration();
    const int samples = std::max(1, static_cast<int>(std::ceil(duration / options.sampleInterval)));
    for (int k = 1; k <= samples; ++k) {
      const double t = duration * k / samples;
      const Vector3 s = profile.at(t);
      appendPoint(space, path[i - 1] + dx * s[0], dx, s, start + t, trajectory);
    }
    start += duration;
  }
  return trajectory;
}

std::string checkTrajectoryLimits(const PlanningSpace& space, const JointTrajectory& trajectory,
                                  double tolerance, double velocityScaling, double accelerationScaling) {
  const VectorX velocity = space.jointVelocityLimits() * velocityScaling;
  const VectorX acceleration = space.jointAccelerationLimits() * accelerationScaling;
  double previousTime = -1.0;
  for (std::size_t p = 0; p < trajectory.points.size(); ++p) {
    const TrajectoryPoint& point = trajectory.points[p];
    const std::string where = "point " + std::to_string(p) + " (t = " + numberText(point.time) + " s)";
    if (!(point.time > previousTime)) return where + ": time does not increase";
    previousTime = point.time;
    for (Eigen::Index j = 0; j < point.velocities.size(); ++j) {
      const std::string& joint = trajectory.jointNames[static_cast<std::size_t>(j)];
      if (std::abs(point.velocities[j]) > velocity[j] * (1.0 + tolerance)) {
        return where + ": " + joint + " velocity " + std::to_string(point.velocities[j]) +
               " exceeds its limit " + std::to_string(velocity[j]);
      }
      if (std::abs(point.accelerations[j]) > acceleration[j] * (1.0 + tolerance)) {
        return where + ": " + joint + " acceleration " + std::to_string(point.accelerations[j]) +
               " exceeds its limit " + std::to_string(acceleration[j]);
      }
    }
  }
  return {};
}

std::vector<TrajectoryJoint> trajectoryJoints(const std::vector<std::string>& names) {
  std::vector<TrajectoryJoint> joints;
  std::map<std::string, int> uses;
  for (const std::string& name : names) {
    const auto slash = name.find('/');
    joints.push_back(slash == std::string::npos ? TrajectoryJoint{"", name, name}
                                                : TrajectoryJoint{name.substr(0, slash), name.substr(slash + 1), name});
    ++uses[joints.back().joint];
  }
  for (TrajectoryJoint& joint : joints) {
    if (uses[joint.joint] == 1) joint.label = joint.joint;
  }
  return joints;
}

nlohmann::json trajectoryToJson(const JointTrajectory& trajectory) {
  nlohmann::json points = nlohmann::json::array();
  for (const TrajectoryPoint& point : trajectory.points) {
    const auto toArray = [](const VectorX& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
    double seconds = std::floor(point.time);
    long nanoseconds = std::lround((point.time - seconds) * 1e9);
    if (nanoseconds >= 1000000000L) {
      seconds += 1.0;
      nanoseconds -= 1000000000L;
    }
    points.push_back({{"positions", toArray(point.positions)},
                      {"velocities", toArray(point.velocities)},
                      {"accelerations", toArray(point.accelerations)},
                      {"time_from_start",
                       {{"sec", static_cast<long>(seconds)},
                        {"nanosec", nanoseconds}}}});
  }
  std::vector<std::string> labels;
  for (const TrajectoryJoint& joint : trajectoryJoints(trajectory.jointNames)) labels.push_back(joint.label);
  return {{"joint_names", labels}, {"points", points}};
}

nlohmann::json trajectoryJointRobots(const JointTrajectory& trajectory) {
  nlohmann::json robots = nlohmann::json::array();
  for (const TrajectoryJoint& joint : trajectoryJoints(trajectory.jointNames)) robots.push_back(joint.robot);
  return robots;
}

std::string trajectoryToCsv(const JointTrajectory& trajectory) {
  std::ostringstream csv;
  csv << std::setprecision(10) << "time";
  const std::vector<TrajectoryJoint> joints = trajectoryJoints(trajectory.jointNames);
  for (const TrajectoryJoint& joint : joints) csv << ',' << joint.label;
  for (const TrajectoryJoint& joint : joints) csv << ',' << joint.label << "_velocity";
  for (const TrajectoryJoint& joint : joints) csv << ',' << joint.label << "_acceleration";
  csv << '\n';
  for (const TrajectoryPoint& point : trajectory.points) {
    csv << point.time;
    for (const VectorX* values : {&point.positions, &point.velocities, &point.accelerations}) {
      for (Eigen::Index j = 0; j < values->size(); ++j) csv << ',' << (*values)[j];
    }
    csv << '\n';
  }
  return csv.str();
}

}  // namespace lang2manip
