#pragma once
/// @file The check before a run is reported successful: every motion of the execution is
/// re-verified with the exact checker (held objects included) at the verification resolution,
/// every goal relation is evaluated on the final world from geometry, and no object that the
/// plan did not act on has moved.

#include <string>
#include <vector>

#include "lang2manip/execution/arm_motion.hpp"

namespace lang2manip {

struct GoalOutcome {
  Goal goal;
  bool holds = false;
  /// Why, in words ("marker is in holder").
  std::string explanation;
};

struct ExecutionVerification {
  /// Empty when every motion is collision-free; otherwise the first collision, naming the
  /// action, the motion and the pair.
  std::string collision;
  std::vector<GoalOutcome> goals;
  /// Objects the plan did not act on whose pose changed, with the displacement in words.
  std::vector<std::string> disturbedObjects;
  /// Motion segments re-checked.
  int segmentsChecked = 0;
  /// Robot states checked in them.
  long collisionChecks = 0;
  double seconds = 0.0;
  /// The execution succeeded, its motions are collision-free, every goal holds and nothing else
  /// moved.
  bool success = false;
};

/// Verifies `record` (an execution from `initial`) against `goals` (see the file comment).
ExecutionVerification verifyExecution(const ArmContext& arm, const Scene& initial, const ExecutionRecord& record,
                                      const std::vector<Goal>& goals);

/// The goals a plan achieves when the task planner gives none: for each object its last
/// placement (relation, or position: at_position), each push as a displacement, the last move to a named configuration,
/// and holding an object picked and never placed.
std::vector<Goal> goalsImpliedByPlan(const Plan& plan);

}  // namespace lang2manip
