#pragma once
/// @file Small helpers shared by the LLM protocol clients: reading fields of a server's JSON
/// answer with errors that name what is missing, and number formatting for messages.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "lang2manip/core/json_limits.hpp"

namespace lang2manip {

/// "0.25", "3", "1.5": seconds for messages, without trailing zeros.
std::string formatSeconds(double seconds);

/// Parses a server's answer body as JSON within `limits` (depth checked before parsing); throws
/// LlmError(kBadResponse) naming `who` and the limit for a body too large or too deeply nested,
/// and quoting the start of the body when it is not JSON (any nlohmann failure, e.g. 1e400).
nlohmann::json parseResponseJson(const std::string& body, const std::string& who,
                                 const JsonLimits& limits = {});

/// Member `key` of `object` (which must be an object); throws LlmError(kBadResponse)
/// "WHO: answer has no PATH.KEY" when absent or null.
const nlohmann::json& requireMember(const nlohmann::json& object, const std::string& key,
                                    const std::string& path, const std::string& who);

/// Like requireMember, and the member must be a string.
std::string requireString(const nlohmann::json& object, const std::string& key,
                          const std::string& path, const std::string& who);

/// Element 0 of the array `object[key]`; throws LlmError(kBadResponse) when it is missing, not an
/// array or empty.
const nlohmann::json& requireFirstElement(const nlohmann::json& object, const std::string& key,
                                          const std::string& path, const std::string& who);

/// `object[key]` as a string when present and a string, else "".
std::string optionalString(const nlohmann::json& object, const std::string& key);

/// `object[key]` as a token count by the rule of LlmUsage: known only for a whole number in
/// [0, kMaxTokenCount]; nullopt when `object` is not an object, the member is absent or null,
/// or its value is anything else.
std::optional<long> tokenCount(const nlohmann::json& object, const std::string& key);

/// Like tokenCount, but an absent or null member counts 0 (for counts a server leaves out when
/// they are zero, such as Gemini's thoughtsTokenCount).
std::optional<long> tokenCountOrZero(const nlohmann::json& object, const std::string& key);

/// The human-readable message in an error body of any of the four protocols
/// ({"error":{"message":...}}, {"error":"..."}), or the start of the body when it has none;
/// "" for an empty (or blank) body. Never parses a body beyond the default JsonLimits.
std::string errorMessageFromBody(const std::string& body);

/// The first `limit` bytes of `text` (never cutting a UTF-8 sequence) with "..." when cut.
std::string abbreviated(const std::string& text, std::size_t limit = 200);

}  // namespace lang2manip
