#pragma once
/// @file Builds an LLM client from a spec "PROVIDER:MODEL" (openai, anthropic, gemini, ollama),
/// with base URL and key from the usual environment variables unless given, optionally
/// recording every call to a file or answering from one.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lang2manip/llm/http_transport.hpp"
#include "lang2manip/llm/llm_client.hpp"
#include "lang2manip/llm/retry_policy.hpp"

namespace lang2manip {

/// Reads an environment variable; nullopt when unset.
using EnvironmentLookup = std::function<std::optional<std::string>(const std::string&)>;

struct LlmClientOptions {
  /// Overrides the provider's base URL variable (OPENAI_BASE_URL, ANTHROPIC_BASE_URL,
  /// GEMINI_BASE_URL, OLLAMA_HOST) and default.
  std::string baseUrl;
  /// Overrides the provider's key variable. Never logged or recorded.
  std::string apiKey;
  HttpOptions http;
  RetryOptions retry;
  /// --llm-record FILE: append every call to FILE (JSON Lines).
  std::string recordFile;
  /// --llm-replay FILE: answer from FILE without network (no key needed).
  std::string replayFile;
  /// Where variables are read; empty: the process environment. Empty values count as unset.
  EnvironmentLookup environment;
};

/// "openai", "anthropic", "gemini", "ollama".
std::vector<std::string> llmProviderNames();

/// A client for `spec` = PROVIDER:MODEL.
///   openai:    key OPENAI_API_KEY (needed only for api.openai.com; local OpenAI-compatible
///              servers may run without), base OPENAI_BASE_URL (default https://api.openai.com/v1)
///   anthropic: key ANTHROPIC_API_KEY, base ANTHROPIC_BASE_URL (default https://api.anthropic.com)
///   gemini:    key GEMINI_API_KEY, else GOOGLE_API_KEY, base GEMINI_BASE_URL
///              (default https://generativelanguage.googleapis.com)
///   ollama:    no key (OLLAMA_API_KEY sent as a bearer token when set), host OLLAMA_HOST
///              (default http://localhost:11434; "host:port" without scheme means http)
/// SSL_CERT_FILE, when set, replaces the system CA bundle unless options.http.caCertFile is set.
/// Throws LlmError(kConfiguration) for a spec that is not PROVIDER:MODEL (listing the valid
/// providers), a missing key (naming the variable to set), a bad base URL, out-of-range
/// options, both record and replay files, or an unreadable/malformed replay file.
std::unique_ptr<LlmClient> makeLlmClient(const std::string& spec, const LlmClientOptions& options);

}  // namespace lang2manip
