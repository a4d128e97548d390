#pragma once
/// @file The task planner a command runs, as chosen on the command line: `--llm offline` (the
/// default, no network) or `--llm PROVIDER:MODEL` with its companion flags (base URL, timeout,
/// record / replay). Shared by every command that plans tasks.

#include <CLI/CLI.hpp>
#include <memory>
#include <optional>
#include <string>

#include "lang2manip/llm/llm_client.hpp"
#include "lang2manip/symbolic/llm_task_planner.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip {

/// The name of the offline planner in `--llm offline`.
inline constexpr const char* kOfflinePlannerSpec = "offline";

/// What the user chose with the `--llm*` flags.
struct TaskPlannerChoice {
  /// "offline" or PROVIDER:MODEL.
  std::string llm = kOfflinePlannerSpec;
  /// --llm-base-url: overrides the provider's base URL variable.
  std::string baseUrl;
  /// --llm-timeout: seconds one LLM call may take, retries included; unset = the client's defaults.
  std::optional<double> timeoutSeconds;
  /// --llm-max-response-bytes: the largest LLM response body accepted; unset = the client's
  /// default (HttpOptions::maxResponseBytes).
  std::optional<long long> maxResponseBytes;
  /// --llm-record FILE / --llm-replay FILE.
  std::string recordFile;
  std::string replayFile;

  [[nodiscard]] bool offline() const { return llm == kOfflinePlannerSpec; }
};

/// Adds --llm, --llm-base-url, --llm-timeout, --llm-max-response-bytes, --llm-record and
/// --llm-replay to `command`,
/// writing into `choice` (which must outlive the command).
void addTaskPlannerOptions(CLI::App& command, TaskPlannerChoice& choice);

/// A plan document read from standard input (`run --plan -`), at most kDefaultJsonMaxBytes;
/// throws CLI::ValidationError when it is longer.
std::string planFromStandardInput();

/// Adds `--task TEXT` writing into `task`; "-" reads the instruction from standard input (at
/// most 64 KiB; surrounding whitespace dropped).
CLI::Option* addTaskOption(CLI::App& command, std::string& task, const std::string& description);

/// A ready task planner with the LLM client it uses (none for the offline planner).
class SelectedTaskPlanner {
 public:
  SelectedTaskPlanner(std::unique_ptr<LlmClient> client, std::unique_ptr<TaskPlanner> planner, std::string label);

  [[nodiscard]] TaskPlanner& planner() const { return *planner_; }
  /// For people: "offline", "openai:gpt-4o", "openai:gpt-4o (replayed from run.jsonl)".
  [[nodiscard]] const std::string& label() const { return label_; }

 private:
  std::unique_ptr<LlmClient> client_;
  std::unique_ptr<TaskPlanner> planner_;
  std::string label_;
};

/// The planner `choice` names. LLM planners use defaultLlmTaskPlannerOptions().
/// Throws InputError for a --llm that is neither "offline" nor PROVIDER:MODEL with a known
/// provider (listing the valid ones), for LLM flags given with the offline planner, and for a
/// timeout or a response size limit that is not positive; LlmError (its message names the variable to set) for a missing
/// API key, a bad base URL or an unreadable replay file. Never prints or logs a key.
SelectedTaskPlanner makeTaskPlanner(const TaskPlannerChoice& choice);

/// The options of LLM planners: the motion planner names of the planning registry, so that the
/// prompt lists them and answers are checked against them.
LlmTaskPlannerOptions defaultLlmTaskPlannerOptions();

}  // namespace lang2manip
