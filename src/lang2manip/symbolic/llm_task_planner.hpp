#pragma once
/// @file A task planner on top of any LlmClient: it sends the fixed system prompt, the task
/// with the observation and the earlier attempts, asks for the plan schema as structured
/// output, and parses the answer.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "lang2manip/llm/llm_client.hpp"
#include "lang2manip/symbolic/observation.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip {

struct LlmTaskPlannerOptions {
  /// Motion planner names actions may use (listed in the prompt, checked in answers); empty =
  /// any name is passed through.
  std::vector<std::string> plannerNames;
  /// How many earlier attempts go into the conversation (the most recent ones).
  std::size_t maxAttemptsInContext = 3;
  int maxTokens = 4096;
  double temperature = 0.0;
  std::optional<long> seed = 7;
  ObservationOptions observation;
};

/// The request an LlmTaskPlanner with `options` sends for `request` (system prompt, task and
/// observation, earlier attempts, plan schema). Throws InputError when request.scene is null.
LlmRequest buildPlanRequest(const PlanningRequest& request, const LlmTaskPlannerOptions& options);

/// See the file comment. Not thread-safe (the client is used without locking).
class LlmTaskPlanner final : public TaskPlanner {
 public:
  /// `client` is not owned and must outlive the planner.
  explicit LlmTaskPlanner(LlmClient& client, LlmTaskPlannerOptions options = {});

  /// The client's name ("openai:gpt-4o", ...).
  [[nodiscard]] std::string name() const override;

  /// The request sent for `request`. Throws InputError when request.scene is null.
  [[nodiscard]] LlmRequest buildRequest(const PlanningRequest& request) const;

  /// One LLM call. Throws UnusableAnswerError for a truncated answer (finish reason length),
  /// a refusal, a filtered answer or an answer that does not parse (with every problem);
  /// LlmError propagates when the call itself fails. Adds the call, tokens and latency to
  /// `statistics`.
  Plan plan(const PlanningRequest& request, const StopCondition& stop, PlanningStatistics& statistics) override;

 private:
  LlmClient& client_;
  LlmTaskPlannerOptions options_;
};

}  // namespace lang2manip
