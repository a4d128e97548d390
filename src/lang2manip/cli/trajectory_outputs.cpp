#include "lang2manip/cli/trajectory_outputs.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "lang2manip/cli/run_report.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/symbolic/plan_json.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

/// Two points closer in time than this are one (segment boundaries repeat their last point).
constexpr double kSameTime = 1e-9;

json durationJson(double seconds) {
  double whole = std::floor(seconds);
  long nanoseconds = std::lround((seconds - whole) * 1e9);
  if (nanoseconds >= 1000000000L) {
    whole += 1.0;
    nanoseconds -= 1000000000L;
  }
  return {{"sec", static_cast<long>(whole)}, {"nanosec", nanoseconds}};
}

/// Where each of `names` is among the trajectory's "robot/joint" columns.
std::vector<Eigen::Index> columnsOf(const JointTrajectory& trajectory, const std::string& robot, const std::vector<std::string>& names) {
  std::vector<Eigen::Index> columns;
  for (const std::string& name : names) {
    const auto found = std::find(trajectory.jointNames.begin(), trajectory.jointNames.end(), robot + "/" + name);
    if (found == trajectory.jointNames.end()) throw InputError("trajectory: no column for joint " + name + " of " + robot);
    columns.push_back(found - trajectory.jointNames.begin());
  }
  return columns;
}

std::vector<double> pick(const VectorX& values, const std::vector<Eigen::Index>& columns) {
  std::vector<double> picked;
  for (const Eigen::Index column : columns) picked.push_back(values[column]);
  return picked;
}

/// A JointTrajectory of `columns`, times from `origin`, points at repeated times dropped.
json jointTrajectory(const JointTrajectory& trajectory, const std::vector<std::string>& names, const std::vector<Eigen::Index>& columns,
                     double origin, double& lastTime) {
  json points = json::array();
  for (const TrajectoryPoint& point : trajectory.points) {
    if (point.time <= lastTime + kSameTime) continue;
    lastTime = point.time;
    points.push_back({{"positions", pick(point.positions, columns)},
                      {"velocities", pick(point.velocities, columns)},
                      {"accelerations", pick(point.accelerations, columns)},
                      {"time_from_start", durationJson(point.time - origin)}});
  }
  return {{"joint_names", names}, {"points", points}};
}

json headerJson(const TrajectoryJoints& joints) {
  return {{"frame_id", joints.frame}, {"stamp", {{"sec", 0}, {"nanosec", 0}}}};
}

/// The joints `names` over the whole run as one JointTrajectory, times from the run's start.
json wholeRun(const ExecutionRecord& execution, const TrajectoryJoints& joints, const std::vector<std::string>& names) {
  json points = json::array();
  double last = -1.0;
  for (const auto& [action, trajectory] : timedActions(execution)) {
    if (trajectory.points.empty()) continue;
    const json part = jointTrajectory(trajectory, names, columnsOf(trajectory, joints.robot, names), 0.0, last);
    for (const json& point : part["points"]) points.push_back(point);
  }
  return {{"joint_names", names}, {"points", points}};
}

std::vector<std::string> allJoints(const TrajectoryJoints& joints) {
  std::vector<std::string> all = joints.arm;
  all.insert(all.end(), joints.gripper.begin(), joints.gripper.end());
  return all;
}

}  // namespace

TrajectoryJoints trajectoryJoints(const ArmContext& arm) {
  TrajectoryJoints joints;
  joints.robot = arm.robotName();
  joints.frame = arm.model().links().front().name;
  joints.arm = arm.manipulator().armJoints;
  joints.gripper = arm.manipulator().gripperJoints;
  joints.toolFrame = arm.manipulator().toolFrame;
  return joints;
}

json runTrajectoryJson(const ExecutionRecord& execution, const TrajectoryJoints& joints) {
  json segments = json::array();
  double end = 0.0;
  for (const auto& [action, trajectory] : timedActions(execution)) {
    if (trajectory.points.empty()) continue;
    const double start = trajectory.points.front().time;
    double armLast = start - 1.0;
    double gripperLast = start - 1.0;
    json segment{{"action", action->index + 1},
                 {"description", describeAction(action->action)},
                 {"start_time", start},
                 {"arm", jointTrajectory(trajectory, joints.arm, columnsOf(trajectory, joints.robot, joints.arm), start, armLast)}};
    if (!joints.gripper.empty()) {
      segment["gripper"] = jointTrajectory(trajectory, joints.gripper, columnsOf(trajectory, joints.robot, joints.gripper), start, gripperLast);
    }
    segments.push_back(std::move(segment));
    end = trajectory.points.back().time;
  }
  return {{"format_version", 2}, {"robot", joints.robot}, {"duration", end}, {"segments", segments}};
}

std::string runTrajectoryCsv(const ExecutionRecord& execution, const TrajectoryJoints& joints) {
  const std::vector<std::string> names = allJoints(joints);
  std::ostringstream csv;
  csv << std::setprecision(10) << "action,time";
  for (const char* suffix : {"", "_velocity", "_acceleration"}) {
    for (const std::string& name : names) csv << ',' << name << suffix;
  }
  csv << '\n';
  double last = -1.0;
  for (const auto& [action, trajectory] : timedActions(execution)) {
    if (trajectory.points.empty()) continue;
    const std::vector<Eigen::Index> columns = columnsOf(trajectory, joints.robot, names);
    for (const TrajectoryPoint& point : trajectory.points) {
      if (point.time <= last + kSameTime) continue;
      last = point.time;
      csv << action->index + 1 << ',' << point.time;
      for (const VectorX* values : {&point.positions, &point.velocities, &point.accelerations}) {
        for (const Eigen::Index column : columns) csv << ',' << (*values)[column];
      }
      csv << '\n';
    }
  }
  return csv.str();
}

json moveItRobotTrajectory(const ExecutionRecord& execution, const TrajectoryJoints& joints) {
  const json header = headerJson(joints);
  json arm = wholeRun(execution, joints, joints.arm);
  arm["header"] = header;
  return {{"joint_trajectory", arm},
          {"multi_dof_joint_trajectory", {{"header", header}, {"joint_names", json::array()}, {"points", json::array()}}}};
}

json gripperJointTrajectory(const ExecutionRecord& execution, const TrajectoryJoints& joints) {
  json gripper = wholeRun(execution, joints, joints.gripper);
  gripper["header"] = headerJson(joints);
  return gripper;
}

json gripperEvents(const ExecutionRecord& execution, const TrajectoryJoints& joints) {
  json events = json::array();
  for (const auto& [action, trajectory] : timedActions(execution)) {
    if (trajectory.points.empty()) continue;
    const double start = trajectory.points.front().time;
    for (std::size_t k = 0; k < action->segments.size() && k < action->segmentEndTimes.size(); ++k) {
      const GripperEvent event = action->segments[k].gripperEvent;
      if (event == GripperEvent::kNone) continue;
      events.push_back({{"time", start + action->segmentEndTimes[k]},
                        {"event", event == GripperEvent::kGrasp ? "attach" : "detach"},
                        {"object", action->action.object},
                        {"link", joints.toolFrame}});
    }
  }
  return {{"events", events}};
}

}  // namespace lang2manip
