#pragma once
/// @file What `lang2manip run` writes: the report (report.json) and the short summary it prints
/// (the trajectory files: trajectory_outputs.hpp).

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lang2manip/execution/execution_verification.hpp"
#include "lang2manip/symbolic/repair_loop.hpp"

namespace lang2manip {

/// The fractions of the joint limits a run uses when neither the request nor the robot's
/// joint_limits.yaml names them: half the velocity limits and a quarter of the acceleration
/// limits (MoveIt's Panda configuration allows a quarter of the datasheet accelerations).
inline constexpr double kDefaultRunVelocityScaling = 0.5;
inline constexpr double kDefaultRunAccelerationScaling = 0.25;

/// The scaling a run uses, and where each came from ("request", "full speed",
/// "joint_limits.yaml", "default").
struct RunScaling {
  double velocity = kDefaultRunVelocityScaling;
  double acceleration = kDefaultRunAccelerationScaling;
  std::string velocitySource = "default";
  std::string accelerationSource = "default";
  /// How far transits keep from the position limits: PositionMargin's default, none at full speed.
  PositionMargin positionMargin;
};

/// Everything a run produced.
struct RunOutcome {
  std::string problem;
  std::string task;
  std::string taskPlanner;
  std::string robot;
  std::string manipulator;
  long seed = 1;
  /// How the trajectories were timed ("time-optimal", "rest-to-rest") and the limit fractions.
  std::string timing;
  RunScaling scaling;
  RepairResult repair;
  /// The execution of the last plan tried (the accepted one on success); null when no plan got
  /// as far as execution.
  const ExecutionRecord* execution = nullptr;
  /// Every execution (one per plan that reached grounding), for the counters and timings.
  const std::vector<ExecutionRecord>* executions = nullptr;
  std::vector<Goal> goals;
  /// "instruction" (understood from the task) or "plan" (implied by the plan's actions).
  std::string goalSource;
  ExecutionVerification verification;
  double observationSeconds = 0.0;
  double totalSeconds = 0.0;

  [[nodiscard]] bool success() const { return repair.succeeded() && verification.success; }
};

/// Each succeeded action of `execution` with its trajectory, times from the start of the run.
std::vector<std::pair<const ActionExecution*, JointTrajectory>> timedActions(const ExecutionRecord& execution);

/// The report: success, goals and whether each holds, final object poses, per-action status,
/// timings per stage and counters.
nlohmann::json runReportJson(const RunOutcome& outcome);

/// A few lines for people: success, each action with its status, the goals, the times.
std::string runSummary(const RunOutcome& outcome);

}  // namespace lang2manip
