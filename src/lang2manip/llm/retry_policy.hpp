#pragma once
/// @file When and how long to wait before another attempt at an LLM call: exponential backoff
/// without jitter (deterministic), Retry-After honoured, bounded attempts and total time, and a
/// wait that wakes as soon as the stop condition fires.

#include <optional>

#include "lang2manip/core/stop_condition.hpp"
#include "lang2manip/llm/http_transport.hpp"

namespace lang2manip {

struct RetryOptions {
  /// HTTP attempts per call, the first included (1 = no retries).
  int maxAttempts = 4;
  /// Wait after the first failure; multiplied by backoffMultiplier after each further one.
  double initialBackoffSeconds = 1.0;
  double backoffMultiplier = 2.0;
  double maxBackoffSeconds = 30.0;
  /// A server asking (Retry-After) for a longer wait than this ends the call instead.
  double maxRetryAfterSeconds = 120.0;
  /// Limit for all attempts and waits of one call together.
  double totalTimeoutSeconds = 600.0;
};

/// Throws LlmError(kConfiguration) naming the field when a value is out of range
/// (maxAttempts < 1, a non-positive or non-finite time, multiplier < 1).
void checkRetryOptions(const RetryOptions& options);

/// Throws LlmError(kConfiguration) naming the field when a timeout is not positive and finite or
/// maxResponseBytes is 0.
void checkHttpOptions(const HttpOptions& options);

/// The wait after `failures` failed attempts (1 -> initialBackoffSeconds), capped.
double backoffSeconds(const RetryOptions& options, int failures);

/// The wait a server asked for: "retry-after-ms" (milliseconds), else "Retry-After" in seconds
/// (decimals accepted); nullopt when absent or not a number (an HTTP date is not used).
std::optional<double> retryAfterSeconds(const HttpHeaders& headers);

/// True for statuses worth another attempt: 408, 409, 425, 429 and 5xx.
bool isRetryableStatus(int status);

/// Sleeps for `seconds`, waking within a few milliseconds when `stop` fires. Returns false when
/// woken by `stop`.
bool sleepUnlessStopped(double seconds, const StopCondition& stop);

}  // namespace lang2manip
