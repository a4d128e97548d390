#pragma once
/// @file The task-planner interface: the offline planner and the LLM planners answer a task
/// with a symbolic Plan. Failures found later (validation, grounding) come back through
/// PlanFeedback so the planner can repair its plan.

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "lang2manip/core/stop_condition.hpp"
#include "lang2manip/model/scene.hpp"
#include "lang2manip/symbolic/action.hpp"

namespace lang2manip {

/// Why an action of a plan could not be grounded, reported by the execution layer.
struct GroundingFailure {
  std::size_t actionIndex = 0;
  /// "grasp", "placement", "ik", "motion", "push", "precondition" (an action the world does not
  /// allow: an unknown object, one already held, an unknown planner or configuration).
  std::string stage;
  std::string object;
  /// In words, naming objects: "no collision-free grasp of eraser: ...".
  std::string reason;
  /// The objects standing where the action needed room (every placement blocked by them).
  std::vector<std::string> blockingObjects;
  /// True when the gripper cannot hold `object` in any direction as it stands (too wide or too
  /// narrow for it): no plan that picks it can succeed.
  bool objectUngraspable = false;
};

/// One earlier round: what the planner answered and why it was not accepted, in words (for
/// LLMs) and, when a plan was grounded, as data (for planners that choose their next try).
struct PlanAttempt {
  /// The raw answer (LLM text) or the plan as JSON.
  std::string answer;
  std::string failure;
  /// The plan that was tried, when the answer was one.
  std::optional<Plan> plan;
  /// Why the plan could not be executed, when it got that far.
  std::optional<GroundingFailure> grounding;
};

struct PlanningRequest {
  std::string task;
  /// The world the task is about; not owned, must outlive the call.
  const Scene* scene = nullptr;
  /// The robot that will execute the plan, and its arm (every arm may act when empty).
  std::string robot;
  std::string arm;
  /// Earlier rounds of this task, oldest first (empty on the first round).
  std::vector<PlanAttempt> earlierAttempts;
};

/// Counters of one planning round (accumulated over rounds by the repair loop).
struct PlanningStatistics {
  int llmCalls = 0;
  /// Tokens of all calls (0 without calls); unknown (nullopt) as soon as one call's count was
  /// unknown (see LlmUsage), so a total never silently leaves calls out. Add with
  /// addTokenCounts().
  std::optional<long> inputTokens = 0;
  std::optional<long> outputTokens = 0;
  double llmSeconds = 0.0;
  double planningSeconds = 0.0;
};

/// A task planner could not produce a plan (an instruction it cannot ground, an LLM error that
/// retries did not fix, a refusal). The message says why, in words for the user.
class PlanningError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A planner's answer could not be used: malformed or truncated JSON, a refusal, a plan with
/// unknown names. Unlike other PlanningErrors the repair loop feeds it back to the planner.
class UnusableAnswerError : public PlanningError {
 public:
  /// `answer` is the raw answer (may be empty); `failure` says what is wrong, in words.
  UnusableAnswerError(std::string answer, const std::string& failure)
      : PlanningError(failure), answer_(std::move(answer)) {}
  [[nodiscard]] const std::string& answer() const noexcept { return answer_; }

 private:
  std::string answer_;
};

/// A planner answering tasks with symbolic plans.
class TaskPlanner {
 public:
  virtual ~TaskPlanner() = default;
  /// "offline", "openai:gpt-4o", ...
  [[nodiscard]] virtual std::string name() const = 0;
  /// A plan for `request`, or PlanningError. May return a plan that later fails validation;
  /// the repair loop checks it. Adds to `statistics`.
  virtual Plan plan(const PlanningRequest& request, const StopCondition& stop,
                    PlanningStatistics& statistics) = 0;
};

/// Grounds and executes a plan; implemented by the execution layer.
class PlanExecutor {
 public:
  virtual ~PlanExecutor() = default;
  /// Executes `plan`; the first action that could not be grounded, or nullopt on success.
  virtual std::optional<GroundingFailure> execute(const Plan& plan, const StopCondition& stop) = 0;
};

}  // namespace lang2manip
