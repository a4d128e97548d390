#include "lang2manip/llm/retry_policy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include "lang2manip/llm/llm_client.hpp"

namespace lang2manip {

namespace {

constexpr auto kStopPollInterval = std::chrono::milliseconds(5);

void requirePositive(double value, const char* field) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw LlmError(LlmErrorKind::kConfiguration,
                   std::string("LLM options: ") + field +
                       " must be a positive number of seconds, got " + std::to_string(value));
  }
}

std::optional<double> parseNonNegative(const std::string& text) {
  if (text.empty()) return std::nullopt;
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  while (used < text.size() && text[used] == ' ') ++used;
  if (used != text.size() || !std::isfinite(value) || value < 0.0) return std::nullopt;
  return value;
}

}  // namespace

void checkRetryOptions(const RetryOptions& options) {
  if (options.maxAttempts < 1) {
    throw LlmError(LlmErrorKind::kConfiguration,
                   "LLM options: maxAttempts must be at least 1, got " +
                       std::to_string(options.maxAttempts));
  }
  requirePositive(options.initialBackoffSeconds, "initialBackoffSeconds");
  requirePositive(options.maxBackoffSeconds, "maxBackoffSeconds");
  requirePositive(options.maxRetryAfterSeconds, "maxRetryAfterSeconds");
  requirePositive(options.totalTimeoutSeconds, "totalTimeoutSeconds");
  if (!std::isfinite(options.backoffMultiplier) || options.backoffMultiplier < 1.0) {
    throw LlmError(LlmErrorKind::kConfiguration,
                   "LLM options: backoffMultiplier must be at least 1, got " +
                       std::to_string(options.backoffMultiplier));
  }
}

void checkHttpOptions(const HttpOptions& options) {
  requirePositive(options.connectTimeoutSeconds, "connectTimeoutSeconds");
  requirePositive(options.requestTimeoutSeconds, "requestTimeoutSeconds");
  if (options.maxResponseBytes < 1) {
    throw LlmError(LlmErrorKind::kConfiguration, "LLM options: maxResponseBytes must be at least 1");
  }
}

double backoffSeconds(const RetryOptions& options, int failures) {
  const double growth = std::pow(options.backoffMultiplier, std::max(0, failures - 1));
  return std::min(options.maxBackoffSeconds, options.initialBackoffSeconds * growth);
}

std::optional<double> retryAfterSeconds(const HttpHeaders& headers) {
  if (const auto millis = parseNonNegative(findHeader(headers, "retry-after-ms"))) {
    return *millis / 1000.0;
  }
  return parseNonNegative(findHeader(headers, "retry-after"));
}

bool isRetryableStatus(int status) {
  return status == 408 || status == 409 || status == 425 || status == 429 ||
         (status >= 500 && status <= 599);
}

bool sleepUnlessStopped(double seconds, const StopCondition& stop) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point end =
      Clock::now() +
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  while (true) {
    if (stop.shouldStop()) return false;
    const Clock::time_point now = Clock::now();
    if (now >= end) return true;
    std::this_thread::sleep_for(std::min<Clock::duration>(end - now, kStopPollInterval));
  }
}

}  // namespace lang2manip
