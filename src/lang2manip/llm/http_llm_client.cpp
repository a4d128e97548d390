#include "lang2manip/llm/http_llm_client.hpp"

#include <chrono>
#include <cmath>
#include <regex>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/llm/llm_support.hpp"

namespace lang2manip {

namespace {

using Clock = std::chrono::steady_clock;

/// A protocol may rewrite a rejected request a few times (json_object, max_completion_tokens...).
constexpr int kMaxAdaptations = 3;

std::string attemptsText(int attempts) {
  return std::to_string(attempts) + (attempts == 1 ? " attempt" : " attempts");
}

bool isSuccess(int status) { return status >= 200 && status <= 299; }

/// What a failed attempt leaves behind for the retry decision.
struct Failure {
  LlmErrorKind kind;
  std::string message;
  int status = 0;
  std::optional<double> retryAfter;
};

}  // namespace

void checkLlmRequest(const LlmRequest& request) {
  if (request.messages.empty()) throw InputError("LLM request: no messages");
  if (request.maxTokens < 1) {
    throw InputError("LLM request: maxTokens must be at least 1, got " +
                     std::to_string(request.maxTokens));
  }
  if (!std::isfinite(request.temperature) || request.temperature < 0.0 ||
      request.temperature > 2.0) {
    throw InputError("LLM request: temperature must be within [0, 2], got " +
                     std::to_string(request.temperature));
  }
  if (request.schema.is_null()) return;
  if (!request.schema.is_object()) throw InputError("LLM request: schema must be a JSON object");
  static const std::regex kSchemaName("[A-Za-z0-9_-]{1,64}");
  if (!std::regex_match(request.schemaName, kSchemaName)) {
    throw InputError("LLM request: schema name \"" + request.schemaName +
                     "\" must be 1-64 characters of A-Z, a-z, 0-9, _ and -");
  }
}

std::string describeHttpFailure(const HttpResponse& response) {
  const std::string serverMessage = errorMessageFromBody(response.body);
  std::string text = httpStatusText(response.status, response.reason) + ": " +
                     (serverMessage.empty() ? std::string("no body") : serverMessage);
  if (response.status >= 300 && response.status <= 399) {
    const std::string location = findHeader(response.headers, "Location");
    text += location.empty() ? std::string("; a redirect without a Location header")
                             : "; the server redirects to " + abbreviated(location, 200);
    text += ", and redirects are not followed (check the base URL)";
  }
  return text;
}

HttpLlmClient::HttpLlmClient(std::unique_ptr<LlmProtocol> protocol, HttpLlmClientConfig config)
    : protocol_(std::move(protocol)), config_(std::move(config)) {
  if (!protocol_) throw LlmError(LlmErrorKind::kConfiguration, "LLM client: no protocol");
  if (config_.model.empty()) {
    throw LlmError(LlmErrorKind::kConfiguration, protocol_->provider() + ": no model name");
  }
  checkHttpOptions(config_.http);
  checkRetryOptions(config_.retry);
  // The secrets are the key and whatever secret headers the protocol sends with it.
  std::vector<std::string> secrets{config_.apiKey};
  LlmRequest probe;
  probe.messages = {{LlmMessage::Role::kUser, "probe"}};
  SecretRedactor::collectSecretHeaderValues(protocol_->buildRequest(probe, config_.model, config_.apiKey).headers,
                                            secrets);
  redactor_ = SecretRedactor(secrets);
}

std::string HttpLlmClient::name() const { return protocol_->provider() + ":" + config_.model; }

LlmReply HttpLlmClient::complete(const LlmRequest& request, const StopCondition& stop) {
  checkLlmRequest(request);
  try {
    return completeUnredacted(request, stop);
  } catch (const LlmError& error) {
    throw LlmError(error.kind(), redacted(name() + ": " + error.what()), error.httpStatus());
  }
}

LlmReply HttpLlmClient::completeUnredacted(const LlmRequest& request, const StopCondition& stop) {
  const Clock::time_point start = Clock::now();
  const StopCondition limited =
      stop.orElse(StopCondition::afterSeconds(config_.retry.totalTimeoutSeconds));
  int attempts = 0;
  int failures = 0;
  int adaptations = 0;
  while (true) {
    ++attempts;
    Failure failure{LlmErrorKind::kTransport, {}, 0, std::nullopt};
    try {
      const HttpRequest httpRequest =
          protocol_->buildRequest(request, config_.model, config_.apiKey);
      HttpResponse response = postJson(config_.endpoint, httpRequest, config_.http, limited);
      response.body = redactor_.redact(std::move(response.body));
      response.headers = redactor_.redact(std::move(response.headers));
      if (isSuccess(response.status)) {
        LlmReply reply = redacted(parseReply(response, request));
        reply.attempts = attempts;
        reply.latencySeconds = std::chrono::duration<double>(Clock::now() - start).count();
        if (reply.model.empty()) reply.model = config_.model;
        return reply;
      }
      const std::string serverMessage = errorMessageFromBody(response.body);
      if ((response.status == 400 || response.status == 422) && adaptations < kMaxAdaptations &&
          protocol_->adaptToRejection(serverMessage)) {
        ++adaptations;
        logInfo(redacted(name() + ": server rejected the request (" + serverMessage +
                         "); sending it again in a form it accepts"));
        continue;
      }
      if (!isRetryableStatus(response.status)) throwForStatus(response, attempts);
      failure = {response.status == 429 ? LlmErrorKind::kRateLimited : LlmErrorKind::kServer,
                 describeHttpFailure(response), response.status, retryAfterSeconds(response.headers)};
    } catch (const LlmError& error) {
      if (error.kind() == LlmErrorKind::kTimeout && limited.shouldStop() && !stop.shouldStop()) {
        throw LlmError(LlmErrorKind::kTimeout,
                       "no answer within the time budget of " +
                           formatSeconds(config_.retry.totalTimeoutSeconds) + " s for one call (" +
                           attemptsText(attempts) + "; " + error.what() + ")");
      }
      const bool retryable =
          error.kind() == LlmErrorKind::kTransport || error.kind() == LlmErrorKind::kTimeout;
      if (!retryable || limited.shouldStop()) throw;
      failure = {error.kind(), error.what(), 0, std::nullopt};
    }
    ++failures;
    if (failures >= config_.retry.maxAttempts) {
      throw LlmError(failure.kind, failure.message + " (gave up after " + attemptsText(attempts) + ")",
                     failure.status);
    }
    const double wait = failure.retryAfter.value_or(backoffSeconds(config_.retry, failures));
    if (failure.retryAfter && *failure.retryAfter > config_.retry.maxRetryAfterSeconds) {
      throw LlmError(failure.kind,
                     failure.message + " (the server asks to wait " + formatSeconds(wait) +
                         " s, more than the " + formatSeconds(config_.retry.maxRetryAfterSeconds) +
                         " s allowed; " + attemptsText(attempts) + ")",
                     failure.status);
    }
    if (wait >= limited.secondsLeft()) {
      throw LlmError(failure.kind,
                     failure.message + " (no time left to wait " + formatSeconds(wait) +
                         " s for another attempt after " + attemptsText(attempts) + ")",
                     failure.status);
    }
    logInfo(redacted(name() + ": " + failure.message + "; retrying in " + formatSeconds(wait) +
                     " s (attempt " + std::to_string(attempts + 1) + " of " +
                     std::to_string(config_.retry.maxAttempts) + ")"));
    if (!sleepUnlessStopped(wait, limited)) {
      const bool deadline = limited.secondsLeft() <= 0.0;
      throw LlmError(deadline ? LlmErrorKind::kTimeout : LlmErrorKind::kCancelled,
                     std::string(deadline ? "time budget ran out" : "cancelled") +
                         " while waiting to retry after " + failure.message);
    }
  }
}

LlmReply HttpLlmClient::parseReply(const HttpResponse& response, const LlmRequest& request) const {
  const std::string who = "HTTP " + std::to_string(response.status);
  try {
    const JsonLimits limits{kDefaultJsonMaxDepth, config_.http.maxResponseBytes};
    return protocol_->parseReply(parseResponseJson(response.body, who, limits), request, who);
  } catch (const nlohmann::json::exception& error) {
    throw LlmError(LlmErrorKind::kBadResponse,
                   who + ": answer has an unexpected shape (" + jsonErrorText(error) + ")");
  }
}

void HttpLlmClient::throwForStatus(const HttpResponse& response, int attempts) const {
  const int status = response.status;
  const std::string http = describeHttpFailure(response);
  if (status == 401 || status == 403) {
    const std::string hint = config_.apiKeyVariable.empty()
                                 ? "check the API key"
                                 : "check the API key in " + config_.apiKeyVariable;
    throw LlmError(LlmErrorKind::kAuthentication, "the server refused the credentials (" + http +
                                                      "); " + hint, status);
  }
  if (status == 404) {
    throw LlmError(LlmErrorKind::kModelNotFound,
                   "model \"" + config_.model + "\" not found at " + config_.endpoint.toString() +
                       " (" + http + "); check the model name and the base URL",
                   status);
  }
  if (status >= 400 && status <= 499) {
    throw LlmError(LlmErrorKind::kConfiguration,
                   "the server rejected the request (" + http + ") after " +
                       attemptsText(attempts),
                   status);
  }
  if (status >= 300 && status <= 399) {
    throw LlmError(LlmErrorKind::kBadResponse, "the server answered with a redirect (" + http + ")", status);
  }
  throw LlmError(LlmErrorKind::kBadResponse, "unexpected " + http, status);
}

std::string HttpLlmClient::redacted(std::string message) const { return redactor_.redact(std::move(message)); }

LlmReply HttpLlmClient::redacted(LlmReply reply) const {
  // The body was redacted already; this catches a secret the server wrote with JSON escapes.
  reply.content = redactor_.redact(std::move(reply.content));
  reply.refusal = redactor_.redact(std::move(reply.refusal));
  reply.model = redactor_.redact(std::move(reply.model));
  return reply;
}

}  // namespace lang2manip
