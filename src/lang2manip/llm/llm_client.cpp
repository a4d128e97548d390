#include "lang2manip/llm/llm_client.hpp"

#include <limits>

namespace lang2manip {

std::string finishReasonName(FinishReason reason) {
  switch (reason) {
    case FinishReason::kStop: return "stop";
    case FinishReason::kLength: return "length";
    case FinishReason::kRefusal: return "refusal";
    case FinishReason::kContentFilter: return "content_filter";
    case FinishReason::kOther: return "other";
  }
  return "other";
}

std::optional<long> addTokenCounts(std::optional<long> a, std::optional<long> b) noexcept {
  if (!a || !b) return std::nullopt;
  long sum = 0;
  if (__builtin_add_overflow(*a, *b, &sum)) {
    return *a > 0 ? std::numeric_limits<long>::max() : std::numeric_limits<long>::min();
  }
  return sum;
}

std::string tokenCountText(const std::optional<long>& count) {
  return count ? std::to_string(*count) : std::string("unknown");
}

namespace {
constexpr LlmErrorKind kAllErrorKinds[] = {
    LlmErrorKind::kConfiguration, LlmErrorKind::kAuthentication, LlmErrorKind::kModelNotFound,
    LlmErrorKind::kRateLimited,   LlmErrorKind::kServer,         LlmErrorKind::kTimeout,
    LlmErrorKind::kCancelled,     LlmErrorKind::kTransport,      LlmErrorKind::kBadResponse,
    LlmErrorKind::kReplayMiss};
}  // namespace

std::string llmErrorKindName(LlmErrorKind kind) {
  switch (kind) {
    case LlmErrorKind::kConfiguration: return "configuration";
    case LlmErrorKind::kAuthentication: return "authentication";
    case LlmErrorKind::kModelNotFound: return "model_not_found";
    case LlmErrorKind::kRateLimited: return "rate_limited";
    case LlmErrorKind::kServer: return "server";
    case LlmErrorKind::kTimeout: return "timeout";
    case LlmErrorKind::kCancelled: return "cancelled";
    case LlmErrorKind::kTransport: return "transport";
    case LlmErrorKind::kBadResponse: return "bad_response";
    case LlmErrorKind::kReplayMiss: return "replay_miss";
  }
  return "transport";
}

std::optional<LlmErrorKind> llmErrorKindFromName(const std::string& name) {
  for (const LlmErrorKind kind : kAllErrorKinds) {
    if (llmErrorKindName(kind) == name) return kind;
  }
  return std::nullopt;
}

LlmError::LlmError(LlmErrorKind kind, const std::string& message, int httpStatus)
    : std::runtime_error(message), kind_(kind), httpStatus_(httpStatus) {}

}  // namespace lang2manip
