#pragma once
/// @file An LlmClient that speaks one protocol over HTTP(S), with retries and precise errors.

#include <memory>
#include <string>

#include "lang2manip/llm/http_transport.hpp"
#include "lang2manip/llm/llm_client.hpp"
#include "lang2manip/llm/llm_protocol.hpp"
#include "lang2manip/llm/retry_policy.hpp"

namespace lang2manip {

struct HttpLlmClientConfig {
  std::string model;
  HttpEndpoint endpoint;
  /// Sent only in headers; removed from every error message.
  std::string apiKey;
  /// The environment variable that holds the key, named in authentication errors.
  std::string apiKeyVariable;
  HttpOptions http;
  RetryOptions retry;
};

/// Sends each request with its protocol; retries 408/409/425/429/5xx, timeouts and transport
/// failures with exponential backoff (Retry-After honoured) within the attempt and time limits;
/// maps the outcome to LlmError kinds (401/403 kAuthentication, 404 kModelNotFound, other 4xx
/// kConfiguration, unusable answers kBadResponse). Thread-safe.
class HttpLlmClient final : public LlmClient {
 public:
  /// Throws LlmError(kConfiguration) for out-of-range options or an empty model.
  HttpLlmClient(std::unique_ptr<LlmProtocol> protocol, HttpLlmClientConfig config);

  /// "provider:model".
  [[nodiscard]] std::string name() const override;

  /// Throws InputError for a malformed request (no messages, bad schema name, maxTokens < 1,
  /// temperature outside [0, 2]) and LlmError for failed calls.
  LlmReply complete(const LlmRequest& request, const StopCondition& stop) override;

 private:
  LlmReply completeUnredacted(const LlmRequest& request, const StopCondition& stop);
  [[nodiscard]] LlmReply parseReply(const HttpResponse& response,
                                    const LlmRequest& request) const;
  [[noreturn]] void throwForStatus(const HttpResponse& response, int attempts) const;
  [[nodiscard]] std::string redacted(std::string message) const;

  std::unique_ptr<LlmProtocol> protocol_;
  HttpLlmClientConfig config_;
};

/// Throws InputError "LLM request: ..." for a request no protocol can send.
void checkLlmRequest(const LlmRequest& request);

}  // namespace lang2manip
