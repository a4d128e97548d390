#pragma once
/// @file LLM requests and replies as JSON, for record/replay files and reports. The request form
/// is canonical: the same request always gives the same text (keys sorted, numbers typed), so
/// its dump() identifies the request.

#include <nlohmann/json.hpp>
#include <string>

#include "lang2manip/llm/llm_client.hpp"

namespace lang2manip {

/// {"system","messages":[{"role","content"}],"schema","schemaName","maxTokens","temperature",
/// "seed"} (seed null when unset). Never holds credentials.
nlohmann::json llmRequestToJson(const LlmRequest& request);

/// The inverse of llmRequestToJson. Throws InputError "FIELD: problem" for a missing or
/// mistyped field.
LlmRequest llmRequestFromJson(const nlohmann::json& json);

/// {"content","finish","refusal","usage":{"inputTokens","outputTokens"},"latencySeconds",
/// "attempts","model"}.
nlohmann::json llmReplyToJson(const LlmReply& reply);

/// The inverse of llmReplyToJson (replayed stays false). Throws InputError as above.
LlmReply llmReplyFromJson(const nlohmann::json& json);

/// The FinishReason named by finishReasonName(), or nullopt.
std::optional<FinishReason> finishReasonFromName(const std::string& name);

}  // namespace lang2manip
