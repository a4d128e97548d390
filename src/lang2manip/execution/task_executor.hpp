#pragma once
/// @file The execution layer's PlanExecutor: grounds and executes a symbolic plan action by
/// action in a world it keeps (object poses, what is held, the robot's configuration), records
/// per action a status with a reason, the motions and the trajectory, and reports the first
/// failure to the repair loop. Each execute() starts again from the initial world.

#include <vector>

#include "lang2manip/core/progress.hpp"
#include "lang2manip/execution/arm_motion.hpp"

namespace lang2manip {

/// See the file comment. Not thread-safe.
class TaskExecutor final : public PlanExecutor {
 public:
  /// Throws InputError as ArmContext does (unknown robot, arm, IK solver, grasp planner, bad
  /// settings).
  TaskExecutor(Scene initial, ExecutionSettings settings = {});

  /// Executes `plan` from the initial world; the first action that failed, or nullopt. A pick of
  /// an object wider than the gripper opens in every direction fails at stage "precondition"
  /// before any action runs (nothing the plan does first could make it fit).
  std::optional<GroundingFailure> execute(const Plan& plan, const StopCondition& stop) override;

  /// Told when each action starts and ends (kActionStarted, kActionFinished).
  void setProgressSink(ProgressSink sink) { progress_ = std::move(sink); }

  [[nodiscard]] const Scene& initialScene() const noexcept { return initial_; }
  [[nodiscard]] const ArmContext& arm() const noexcept { return arm_; }
  /// Every execution so far, oldest first.
  [[nodiscard]] const std::vector<ExecutionRecord>& executions() const noexcept { return executions_; }
  /// The last execution; throws InputError when execute() was never called.
  [[nodiscard]] const ExecutionRecord& lastExecution() const;

 private:
  Scene initial_;
  ArmContext arm_;
  std::vector<ExecutionRecord> executions_;
  ProgressSink progress_;
};

}  // namespace lang2manip
