#pragma once
/// @file The repair loop: ask a task planner for a plan, check it (schema, symbolic validation,
/// optionally grounding by an executor), and when it is not accepted ask again with the failure
/// described in words together with the earlier attempts; bounded rounds.

#include <optional>
#include <string>
#include <vector>

#include "lang2manip/core/progress.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip {

struct RepairOptions {
  /// Planner calls at most (>= 1).
  int maxRounds = 3;
  /// Check plans against the symbolic state before accepting or executing them.
  bool validate = true;
  SymbolicStateTolerances tolerances;
  /// Told of every planner call and of each answer's outcome.
  ProgressSink progress;
};

/// What happened to one round's answer.
enum class RoundOutcome {
  kAccepted,        ///< valid (and executed when there is an executor)
  kUnusableAnswer,  ///< malformed, truncated or refused answer
  kInvalidPlan,     ///< failed symbolic validation
  kGroundingFailed, ///< the executor could not ground an action
  kPlannerError,    ///< the planner gave up (not repairable): the loop ends
};

/// "accepted", "unusable answer", "invalid plan", "grounding failed", "planner error".
std::string roundOutcomeName(RoundOutcome outcome);

struct RepairRound {
  int round = 0;
  RoundOutcome outcome = RoundOutcome::kAccepted;
  /// The answer, the parsed plan (absent for unusable answers and planner errors) and, unless
  /// accepted, why it was rejected, in words and as data (fed back to the planner).
  PlanAttempt attempt;
  PlanningStatistics statistics;
};

struct RepairResult {
  /// The accepted plan; absent when every round failed.
  std::optional<Plan> plan;
  std::vector<RepairRound> rounds;
  /// Summed over the rounds.
  PlanningStatistics statistics;
  /// Empty on success; otherwise why it ended, followed by every round and its failure (when a
  /// planner error ended it: the rounds before that error).
  std::string failure;

  [[nodiscard]] bool succeeded() const noexcept { return plan.has_value(); }
};

/// "step 2 (place marker in holder) could not be grounded (placement): <reason>".
std::string describeGroundingFailure(const GroundingFailure& failure, const Plan& plan);

/// Runs the loop described in the file comment. `executor` may be null (then a valid plan is
/// accepted without grounding). Ends early when `stop` fires, when the planner throws a
/// PlanningError that is not an UnusableAnswerError, or when an LlmError escapes the planner;
/// those become the failure, never exceptions. Throws InputError when request.scene is null or
/// options.maxRounds < 1.
RepairResult planWithRepair(TaskPlanner& planner, const PlanningRequest& request, PlanExecutor* executor,
                            const RepairOptions& options, const StopCondition& stop);

}  // namespace lang2manip
