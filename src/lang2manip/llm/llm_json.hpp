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
/// "attempts","model"}; an unknown token count is null.
nlohmann::json llmReplyToJson(const LlmReply& reply);

/// The inverse of llmReplyToJson (replayed stays false). Throws InputError as above, also for
/// integers out of range (maxTokens and attempts 1..INT_MAX, token counts 0..kMaxTokenCount
/// or null).
LlmReply llmReplyFromJson(const nlohmann::json& json);

/// A token count for reports and records: the number, or null when unknown.
nlohmann::json tokenCountJson(const std::optional<long>& count);

/// The FinishReason named by finishReasonName(), or nullopt.
std::optional<FinishReason> finishReasonFromName(const std::string& name);

}  // namespace lang2manip
