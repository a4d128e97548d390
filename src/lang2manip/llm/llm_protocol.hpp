#pragma once
/// @file The wire format of one LLM protocol: how an LlmRequest becomes an HTTP request and how
/// the server's JSON answer becomes an LlmReply. Pure functions of their inputs (no network), so
/// each format is testable on its own; HttpLlmClient adds transport, retries and errors.

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "lang2manip/llm/http_transport.hpp"
#include "lang2manip/llm/llm_client.hpp"

namespace lang2manip {

class LlmProtocol {
 public:
  virtual ~LlmProtocol() = default;

  /// "openai", "anthropic", "gemini" or "ollama".
  [[nodiscard]] virtual std::string provider() const = 0;

  /// Path (below the base URL), headers (authentication included when `apiKey` is not empty)
  /// and JSON body for `request` to `model`.
  [[nodiscard]] virtual HttpRequest buildRequest(const LlmRequest& request,
                                                 const std::string& model,
                                                 const std::string& apiKey) const = 0;

  /// The reply in a successful (2xx) answer body. Throws LlmError(kBadResponse) naming the field
  /// that is missing or malformed; `who` prefixes messages.
  [[nodiscard]] virtual LlmReply parseReply(const nlohmann::json& body, const LlmRequest& request,
                                            const std::string& who) const = 0;

  /// Called with the server's message when it rejected a request (HTTP 400/422). A protocol that
  /// can write the request differently (e.g. an older server without json_schema support)
  /// switches for this and later requests and returns true; false when it has nothing to try.
  /// Thread-safe.
  virtual bool adaptToRejection(const std::string& /*serverMessage*/) { return false; }
};

/// OpenAI-compatible chat completions (POST {base}/chat/completions) with
/// response_format json_schema (strict); falls back to json_object, max_completion_tokens or no
/// temperature when the server rejects those.
std::unique_ptr<LlmProtocol> makeOpenAiProtocol();

/// Anthropic messages (POST {base}/v1/messages): the schema is the input_schema of a tool that
/// tool_choice forces; the reply's content is the tool input as JSON text, or the text blocks
/// when the model answered in text instead (the caller judges them like any answer).
std::unique_ptr<LlmProtocol> makeAnthropicProtocol();

/// Gemini generateContent (POST {base}/v1beta/models/{model}:generateContent) with
/// responseMimeType application/json and the schema converted to Gemini's subset.
std::unique_ptr<LlmProtocol> makeGeminiProtocol();

/// Ollama native chat (POST {host}/api/chat) with format = schema and stream false.
std::unique_ptr<LlmProtocol> makeOllamaProtocol();

/// Role name shared by OpenAI, Anthropic and Ollama: "user" or "assistant".
std::string chatRoleName(LlmMessage::Role role);

}  // namespace lang2manip
