#include "lang2manip/cli/task_planner_choice.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>
#include <utility>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/json_limits.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/llm/http_transport.hpp"
#include "lang2manip/llm/llm_client_factory.hpp"
#include "lang2manip/planning/planner_registry.hpp"

namespace lang2manip {
namespace {

/// A connection is given at most this long, however long a call may take.
constexpr double kMaxConnectSeconds = 10.0;

std::string validChoices() {
  std::string providers;
  for (const std::string& name : llmProviderNames()) providers += (providers.empty() ? "" : ", ") + name;
  return std::string(kOfflinePlannerSpec) + " (the default, no network) or PROVIDER:MODEL with PROVIDER one of " +
         providers;
}

void checkLlmSpec(const std::string& spec) {
  const std::size_t colon = spec.find(':');
  const std::vector<std::string> providers = llmProviderNames();
  const std::string provider = spec.substr(0, colon);
  if (colon == std::string::npos || std::find(providers.begin(), providers.end(), provider) == providers.end()) {
    throw InputError("--llm \"" + spec + "\": unknown task planner; valid: " + validChoices());
  }
  if (colon + 1 == spec.size()) {
    throw InputError("--llm \"" + spec + "\": no model named; write " + provider + ":MODEL");
  }
}

/// LLM flags make no sense for the offline planner; saying so beats ignoring them.
void checkOfflineFlags(const TaskPlannerChoice& choice) {
  const std::pair<const char*, bool> flags[] = {{"--llm-base-url", !choice.baseUrl.empty()},
                                                {"--llm-timeout", choice.timeoutSeconds.has_value()},
                                                {"--llm-max-response-bytes", choice.maxResponseBytes.has_value()},
                                                {"--llm-record", !choice.recordFile.empty()},
                                                {"--llm-replay", !choice.replayFile.empty()}};
  for (const auto& [flag, given] : flags) {
    if (given) {
      throw InputError(std::string(flag) +
                       " needs an LLM task planner (--llm PROVIDER:MODEL); the offline planner makes no LLM calls");
    }
  }
}

std::string formatTimeout(double seconds) {
  std::ostringstream text;
  text << seconds;
  return text.str();
}

LlmClientOptions clientOptions(const TaskPlannerChoice& choice) {
  LlmClientOptions options;
  options.baseUrl = choice.baseUrl;
  options.recordFile = choice.recordFile;
  options.replayFile = choice.replayFile;
  if (const std::optional<double> timeout = choice.timeoutSeconds) {
    if (!std::isfinite(*timeout) || *timeout <= 0.0) {
      throw InputError("--llm-timeout " + formatTimeout(*timeout) + ": must be a positive number of seconds");
    }
    options.http.requestTimeoutSeconds = *timeout;
    options.http.connectTimeoutSeconds = std::min(kMaxConnectSeconds, *timeout);
    options.retry.totalTimeoutSeconds = *timeout;
  }
  if (const std::optional<long long> bytes = choice.maxResponseBytes) {
    if (*bytes < 1) {
      throw InputError("--llm-max-response-bytes " + std::to_string(*bytes) + ": must be a positive number of bytes");
    }
    options.http.maxResponseBytes = static_cast<std::size_t>(*bytes);
  }
  return options;
}

std::string llmLabel(const TaskPlannerChoice& choice) {
  if (!choice.replayFile.empty()) return choice.llm + " (replayed from " + choice.replayFile + ")";
  if (!choice.recordFile.empty()) return choice.llm + " (recorded to " + choice.recordFile + ")";
  return choice.llm;
}

}  // namespace

namespace {

/// Standard input, surrounding whitespace dropped; CLI::ValidationError naming `option` when it
/// is longer than maxBytes.
std::string standardInputText(const std::string& option, const std::string& what, std::size_t maxBytes) {
  std::string text;
  char buffer[4096];
  while (std::cin.read(buffer, sizeof buffer) || std::cin.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(std::cin.gcount()));
    if (text.size() > maxBytes) {
      throw CLI::ValidationError(option, what + " on standard input is longer than " + std::to_string(maxBytes / 1024) + " KiB");
    }
  }
  return std::string(trimmed(text));
}

}  // namespace

std::string taskFromStandardInput() { return standardInputText("--task -", "the instruction", std::size_t{64} * 1024); }

std::string planFromStandardInput() {
  return standardInputText("--plan -", "the plan document", kDefaultJsonMaxBytes);
}

CLI::Option* addTaskOption(CLI::App& command, std::string& task, const std::string& description) {
  return command.add_option("--task", task, description + " (\"-\": read it from standard input)")
      ->transform([](std::string value) { return value == "-" ? taskFromStandardInput() : value; }, "", "stdin");
}

void addTaskPlannerOptions(CLI::App& command, TaskPlannerChoice& choice) {
  command.add_option("--llm", choice.llm, "Task planner: " + validChoices())->capture_default_str();
  command.add_option("--llm-base-url", choice.baseUrl,
                     "Base URL of the LLM server (overrides OPENAI_BASE_URL, ANTHROPIC_BASE_URL, "
                     "GEMINI_BASE_URL, OLLAMA_HOST)");
  command.add_option_function<double>(
      "--llm-timeout", [&choice](const double& seconds) { choice.timeoutSeconds = seconds; },
      "Seconds one LLM call may take, retries included (default: 120 per attempt)");
  command.add_option_function<long long>(
      "--llm-max-response-bytes", [&choice](const long long& bytes) { choice.maxResponseBytes = bytes; },
      "Largest LLM response accepted, in bytes; a larger one is refused while it arrives (default: " +
          std::to_string(kDefaultMaxResponseBytes) + ")");
  command.add_option("--llm-record", choice.recordFile, "Append every LLM request and answer to FILE (JSON Lines)");
  command.add_option("--llm-replay", choice.replayFile,
                     "Answer LLM requests from FILE written by --llm-record (no network, no API key)");
}

SelectedTaskPlanner::SelectedTaskPlanner(std::unique_ptr<LlmClient> client, std::unique_ptr<TaskPlanner> planner,
                                         std::string label)
    : client_(std::move(client)), planner_(std::move(planner)), label_(std::move(label)) {}

LlmTaskPlannerOptions defaultLlmTaskPlannerOptions() {
  LlmTaskPlannerOptions options;
  options.plannerNames = plannerNames();
  return options;
}

SelectedTaskPlanner makeTaskPlanner(const TaskPlannerChoice& choice) {
  if (choice.offline()) {
    checkOfflineFlags(choice);
    return {nullptr, std::make_unique<OfflineTaskPlanner>(), kOfflinePlannerSpec};
  }
  checkLlmSpec(choice.llm);
  std::unique_ptr<LlmClient> client = makeLlmClient(choice.llm, clientOptions(choice));
  auto planner = std::make_unique<LlmTaskPlanner>(*client, defaultLlmTaskPlannerOptions());
  return {std::move(client), std::move(planner), llmLabel(choice)};
}

}  // namespace lang2manip
