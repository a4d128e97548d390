#include "lang2manip/llm/llm_client.hpp"

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

LlmError::LlmError(LlmErrorKind kind, const std::string& message, int httpStatus)
    : std::runtime_error(message), kind_(kind), httpStatus_(httpStatus) {}

}  // namespace lang2manip
