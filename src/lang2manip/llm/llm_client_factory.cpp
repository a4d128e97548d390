#include "lang2manip/llm/llm_client_factory.hpp"

#include <array>
#include <cstdlib>

#include "lang2manip/llm/http_llm_client.hpp"
#include "lang2manip/llm/http_proxy.hpp"
#include "lang2manip/llm/llm_protocol.hpp"
#include "lang2manip/llm/llm_recording.hpp"

namespace lang2manip {

namespace {

struct ProviderInfo {
  const char* name;
  /// Key variables in order of preference; empty for none.
  std::vector<std::string> keyVariables;
  /// Whether a call can work without a key for this endpoint.
  bool (*keyOptional)(const HttpEndpoint&);
  const char* baseVariable;
  const char* defaultBase;
  std::unique_ptr<LlmProtocol> (*makeProtocol)();
};

bool never(const HttpEndpoint& /*endpoint*/) { return false; }
bool always(const HttpEndpoint& /*endpoint*/) { return true; }
bool unlessOpenAi(const HttpEndpoint& endpoint) { return endpoint.host != "api.openai.com"; }

const std::vector<ProviderInfo>& providers() {
  static const std::vector<ProviderInfo> kProviders = {
      {"openai", {"OPENAI_API_KEY"}, unlessOpenAi, "OPENAI_BASE_URL", "https://api.openai.com/v1",
       makeOpenAiProtocol},
      {"anthropic", {"ANTHROPIC_API_KEY"}, never, "ANTHROPIC_BASE_URL",
       "https://api.anthropic.com", makeAnthropicProtocol},
      {"gemini", {"GEMINI_API_KEY", "GOOGLE_API_KEY"}, never, "GEMINI_BASE_URL",
       "https://generativelanguage.googleapis.com", makeGeminiProtocol},
      {"ollama", {"OLLAMA_API_KEY"}, always, "OLLAMA_HOST", "http://localhost:11434",
       makeOllamaProtocol},
  };
  return kProviders;
}

std::string providerList() {
  std::string list;
  for (const std::string& name : llmProviderNames()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

std::optional<std::string> lookup(const LlmClientOptions& options, const std::string& variable) {
  std::optional<std::string> value;
  if (options.environment) {
    value = options.environment(variable);
  } else if (const char* text = std::getenv(variable.c_str())) {
    value = std::string(text);
  }
  if (value && value->empty()) return std::nullopt;
  return value;
}

struct ParsedSpec {
  const ProviderInfo* provider;
  std::string model;
};

ParsedSpec parseSpec(const std::string& spec) {
  const std::size_t colon = spec.find(':');
  if (colon == std::string::npos) {
    throw LlmError(LlmErrorKind::kConfiguration,
                   "LLM \"" + spec + "\" is not PROVIDER:MODEL; providers: " + providerList());
  }
  const std::string provider = spec.substr(0, colon);
  const std::string model = spec.substr(colon + 1);
  for (const ProviderInfo& info : providers()) {
    if (provider != info.name) continue;
    if (model.empty()) {
      throw LlmError(LlmErrorKind::kConfiguration,
                     "LLM \"" + spec + "\" names no model (write " + provider + ":MODEL)");
    }
    return {&info, model};
  }
  throw LlmError(LlmErrorKind::kConfiguration, "unknown LLM provider \"" + provider + "\" in \"" +
                                                   spec + "\"; providers: " + providerList() +
                                                   " (as PROVIDER:MODEL)");
}

/// OLLAMA_HOST may be "host", "host:port" or a URL; the Ollama CLI reads it the same way.
std::string ollamaHostUrl(const std::string& host) {
  if (host.find("://") != std::string::npos) return host;
  const bool hasPort = host.find(':') != std::string::npos;
  return "http://" + host + (hasPort ? "" : ":11434");
}

HttpEndpoint endpointFor(const ProviderInfo& info, const LlmClientOptions& options) {
  if (!options.baseUrl.empty()) return parseBaseUrl(options.baseUrl, "LLM base URL option");
  const std::optional<std::string> fromEnvironment = lookup(options, info.baseVariable);
  if (!fromEnvironment) return parseBaseUrl(info.defaultBase, info.name);
  const bool ollama = std::string(info.name) == "ollama";
  return parseBaseUrl(ollama ? ollamaHostUrl(*fromEnvironment) : *fromEnvironment,
                      info.baseVariable);
}

/// The key and the variable it came from.
std::pair<std::string, std::string> keyFor(const ProviderInfo& info,
                                           const LlmClientOptions& options,
                                           const HttpEndpoint& endpoint) {
  const std::string variables = [&] {
    std::string names;
    for (const std::string& name : info.keyVariables) names += (names.empty() ? "" : " or ") + name;
    return names;
  }();
  if (!options.apiKey.empty()) return {options.apiKey, variables};
  for (const std::string& variable : info.keyVariables) {
    if (const auto key = lookup(options, variable)) return {*key, variable};
  }
  if (info.keyOptional(endpoint)) return {"", variables};
  throw LlmError(LlmErrorKind::kConfiguration,
                 std::string(info.name) + ": no API key; set " + variables +
                     " in the environment lang2manip runs in (keys are read only from there, never from the command line)");
}

}  // namespace

std::vector<std::string> llmProviderNames() {
  std::vector<std::string> names;
  for (const ProviderInfo& info : providers()) names.emplace_back(info.name);
  return names;
}

std::unique_ptr<LlmClient> makeLlmClient(const std::string& spec, const LlmClientOptions& options) {
  const ParsedSpec parsed = parseSpec(spec);
  checkHttpOptions(options.http);
  checkRetryOptions(options.retry);
  if (!options.recordFile.empty() && !options.replayFile.empty()) {
    throw LlmError(LlmErrorKind::kConfiguration,
                   "--llm-record and --llm-replay cannot be used together");
  }
  if (!options.replayFile.empty()) {
    return makeReplayLlmClient(options.replayFile, std::string(parsed.provider->name) + ":" + parsed.model);
  }
  HttpLlmClientConfig config;
  config.model = parsed.model;
  config.endpoint = endpointFor(*parsed.provider, options);
  std::tie(config.apiKey, config.apiKeyVariable) = keyFor(*parsed.provider, options, config.endpoint);
  config.http = options.http;
  for (const char* name : kProxyVariableNames) {
    if (const auto value = lookup(options, name)) config.http.proxyVariables[name] = *value;
  }
  (void)proxyFor(config.endpoint, config.http.proxyVariables);  // a malformed proxy variable fails here, not at the first call
  if (config.http.caCertFile.empty()) {
    config.http.caCertFile = lookup(options, "SSL_CERT_FILE").value_or("");
  }
  config.retry = options.retry;
  std::unique_ptr<LlmClient> client =
      std::make_unique<HttpLlmClient>(parsed.provider->makeProtocol(), std::move(config));
  if (!options.recordFile.empty()) return makeRecordingLlmClient(std::move(client), options.recordFile);
  return client;
}

}  // namespace lang2manip
