#pragma once
/// @file The LLM client interface: one request (system prompt, messages, JSON Schema for
/// structured output) and one reply, whatever the wire protocol. Implementations speak OpenAI
/// chat completions, Anthropic messages, Gemini generateContent and Ollama chat; decorators
/// record and replay.

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "lang2manip/core/stop_condition.hpp"

namespace lang2manip {

struct LlmMessage {
  enum class Role { kUser, kAssistant };
  Role role = Role::kUser;
  std::string content;
};

struct LlmRequest {
  std::string system;
  std::vector<LlmMessage> messages;
  /// The JSON Schema the answer must follow (strict-mode compatible); null for free text.
  nlohmann::json schema;
  /// A short identifier for the schema (OpenAI json_schema name, Anthropic tool name).
  std::string schemaName = "plan";
  int maxTokens = 4096;
  double temperature = 0.0;
  std::optional<long> seed;
};

enum class FinishReason { kStop, kLength, kRefusal, kContentFilter, kOther };

/// "stop", "length", "refusal", "content_filter", "other".
std::string finishReasonName(FinishReason reason);

/// The largest token count taken as known (2^53, exact in a double).
inline constexpr long kMaxTokenCount = 1L << 53;

/// Token counts as the server reported them. The rule, the same for every protocol: a count is
/// known only when the server sent a JSON number that is a whole number in [0, kMaxTokenCount]
/// (12 and 12.0 count; -3, 1.5, 1e300, "12", true, null or an absent field do not). Anything
/// else is unknown (nullopt) -- never a guess, never 0 -- and reports say "unknown".
struct LlmUsage {
  std::optional<long> inputTokens;
  std::optional<long> outputTokens;
};

/// a + b, or nullopt when either is unknown; saturates at LONG_MAX.
std::optional<long> addTokenCounts(std::optional<long> a, std::optional<long> b) noexcept;

/// "123", or "unknown" for nullopt.
std::string tokenCountText(const std::optional<long>& count);

struct LlmReply {
  /// The answer text (with structured output: the JSON document as text).
  std::string content;
  FinishReason finish = FinishReason::kStop;
  /// The model's refusal message when finish == kRefusal.
  std::string refusal;
  LlmUsage usage;
  /// Wall time of the call including retries.
  double latencySeconds = 0.0;
  /// HTTP attempts made (1 without retries).
  int attempts = 1;
  /// The model that answered, as the server named it.
  std::string model;
  /// True when the reply came from a --llm-replay file rather than the network.
  bool replayed = false;
};

enum class LlmErrorKind {
  kConfiguration,  ///< bad spec, missing API key, bad base URL
  kAuthentication, ///< 401/403
  kModelNotFound,  ///< 404 for the model
  kRateLimited,    ///< 429 after the retries
  kServer,         ///< 5xx after the retries
  kTimeout,        ///< no answer within the timeout
  kCancelled,      ///< the stop condition fired
  kTransport,      ///< connection, TLS, certificate
  kBadResponse,    ///< the server's answer does not follow the protocol
  kReplayMiss,     ///< --llm-replay has no recorded answer for this request
};

/// "configuration", "authentication", "model_not_found", "rate_limited", "server", "timeout",
/// "cancelled", "transport", "bad_response", "replay_miss".
std::string llmErrorKindName(LlmErrorKind kind);

/// The kind named by llmErrorKindName(), or nullopt for an unknown name.
std::optional<LlmErrorKind> llmErrorKindFromName(const std::string& name);

/// An LLM call that failed; the message never contains an API key.
class LlmError : public std::runtime_error {
 public:
  LlmError(LlmErrorKind kind, const std::string& message, int httpStatus = 0);
  [[nodiscard]] LlmErrorKind kind() const noexcept { return kind_; }
  /// The HTTP status that caused it (0 when none).
  [[nodiscard]] int httpStatus() const noexcept { return httpStatus_; }

 private:
  LlmErrorKind kind_;
  int httpStatus_;
};

/// One LLM endpoint and model.
class LlmClient {
 public:
  virtual ~LlmClient() = default;
  /// "openai:gpt-4o-mini", "anthropic:claude-...", "replay:FILE", ...
  [[nodiscard]] virtual std::string name() const = 0;
  /// Sends `request`; the reply, or LlmError. Honours `stop` (cancellation, deadline).
  virtual LlmReply complete(const LlmRequest& request, const StopCondition& stop) = 0;
};

}  // namespace lang2manip
