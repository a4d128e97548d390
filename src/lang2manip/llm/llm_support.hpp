#pragma once
/// @file Small helpers shared by the LLM protocol clients: reading fields of a server's JSON
/// answer with errors that name what is missing, and number formatting for messages.

#include <nlohmann/json.hpp>
#include <string>

namespace lang2manip {

/// "0.25", "3", "1.5": seconds for messages, without trailing zeros.
std::string formatSeconds(double seconds);

/// Parses a server's answer body as JSON; throws LlmError(kBadResponse) naming `who` and quoting
/// the start of the body when it is not JSON.
nlohmann::json parseResponseJson(const std::string& body, const std::string& who);

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

/// `object[key]` as an integer when present and a number, else 0.
long optionalCount(const nlohmann::json& object, const std::string& key);

/// The human-readable message in an error body of any of the four protocols
/// ({"error":{"message":...}}, {"error":"..."}), or the start of the body when it has none.
std::string errorMessageFromBody(const std::string& body);

/// The first `limit` characters of `text` with "..." when cut.
std::string abbreviated(const std::string& text, std::size_t limit = 200);

}  // namespace lang2manip
