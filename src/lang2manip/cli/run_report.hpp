#pragma once
/// @file What `lang2manip run` writes: the report (report.json) and the short summary it prints
/// (the trajectory files: trajectory_outputs.hpp).

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lang2manip/execution/execution_verification.hpp"
#include "lang2manip/symbolic/repair_loop.hpp"

namespace lang2manip {

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
  double velocityScaling = 1.0;
  double accelerationScaling = 1.0;
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
