#pragma once
/// @file An LlmClient that speaks one protocol over HTTP(S), with retries and precise errors.

#include <memory>
#include <string>

#include "lang2manip/llm/http_transport.hpp"
#include "lang2manip/llm/llm_client.hpp"
#include "lang2manip/llm/llm_protocol.hpp"
#include "lang2manip/llm/retry_policy.hpp"
#include "lang2manip/llm/secret_redaction.hpp"

namespace lang2manip {

struct HttpLlmClientConfig {
  std::string model;
  HttpEndpoint endpoint;
  /// Sent only in headers; replaced by "[redacted]" in every error message, log line and reply
  /// (and so in record files), together with the values of the secret headers the protocol
  /// sends (see isSecretHeader), wherever a server echoes them.
  std::string apiKey;
  /// The environment variable that holds the key, named in authentication errors.
  std::string apiKeyVariable;
  HttpOptions http;
  RetryOptions retry;
};

/// Sends each request with its protocol; retries 408/409/425/429/5xx, timeouts and transport
/// failures with exponential backoff (Retry-After honoured) within the attempt and time limits;
/// maps the outcome to LlmError kinds (401/403 kAuthentication, 404 kModelNotFound, other 4xx
/// kConfiguration, 3xx (redirects are not followed), unusable answers and bodies over
/// http.maxResponseBytes kBadResponse). Every HTTP failure message names the status, its reason
/// phrase and the server's message or "no body", and for 3xx the Location. Response bodies and
/// headers are redacted (see apiKey) before anything reads them. Thread-safe.
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
  [[nodiscard]] LlmReply redacted(LlmReply reply) const;

  std::unique_ptr<LlmProtocol> protocol_;
  HttpLlmClientConfig config_;
  SecretRedactor redactor_;
};

/// Throws InputError "LLM request: ..." for a request no protocol can send.
void checkLlmRequest(const LlmRequest& request);

/// The words for a failed HTTP answer: "HTTP 404 Not Found: <the server's message>",
/// "HTTP 502 Bad Gateway: no body", "HTTP 302 Found: no body; the server redirects to
/// https://elsewhere/v1, and redirects are not followed (check the base URL)".
std::string describeHttpFailure(const HttpResponse& response);

}  // namespace lang2manip
