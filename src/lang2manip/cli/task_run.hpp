#pragma once
/// @file One task, as `run` and `bench task` do it: planned through the repair loop with the
/// executor grounding every answer, then the last execution verified against the goals.

#include <string>
#include <vector>

#include "lang2manip/execution/execution_verification.hpp"
#include "lang2manip/execution/task_executor.hpp"
#include "lang2manip/symbolic/repair_loop.hpp"

namespace lang2manip {

struct TaskRun {
  RepairResult repair;
  /// The goals the instruction states (offline understanding), else those the plan implies.
  std::vector<Goal> goals;
  /// "instruction" or "plan".
  std::string goalSource;
  /// Of the last execution; default (not successful) when no plan was executed.
  ExecutionVerification verification;

  [[nodiscard]] bool success() const { return repair.succeeded() && verification.success; }
};

/// Plans `task` on `executor`'s initial scene with `planner` for at most `rounds` rounds, each
/// accepted answer executed by `executor`, and verifies the last execution.
TaskRun planExecuteAndVerify(TaskPlanner& planner, TaskExecutor& executor, const std::string& task, int rounds);

}  // namespace lang2manip
