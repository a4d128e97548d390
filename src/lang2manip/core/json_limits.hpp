#pragma once
/// @file Limits on the JSON documents lang2manip reads from untrusted sources (LLM response
/// bodies and answers, record/replay files, plan files, API bodies), checked on the text BEFORE
/// nlohmann parses it: nlohmann's parser, dump(), operator== and copies recurse once per nesting
/// level, so a document nested 100,000 levels deep overflows the stack unless it is refused
/// first. A document within the limits parses into a value whose depth is at most maxDepth, which
/// every later recursive operation handles safely.
///
/// Also: JSON parsing that turns every nlohmann exception into an InputError naming the
/// document, a bounded rendering of a JSON value for messages, and a line reader for JSON Lines
/// files that never buffers more than a line limit.

#include <cstddef>
#include <istream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "lang2manip/core/error.hpp"

namespace lang2manip {

/// Nesting levels (arrays and objects) any document may have. Plans need about 5, LLM response
/// bodies about 10, recorded requests with their JSON Schema about 25.
inline constexpr std::size_t kDefaultJsonMaxDepth = 128;
/// Bytes a document may have unless a caller sets a tighter limit (LLM responses are capped
/// while being received, see HttpOptions::maxResponseBytes).
inline constexpr std::size_t kDefaultJsonMaxBytes = std::size_t{16} << 20;

/// How big and how deep one JSON document may be. Plain values, cheap to copy.
struct JsonLimits {
  std::size_t maxDepth = kDefaultJsonMaxDepth;
  std::size_t maxBytes = kDefaultJsonMaxBytes;
};

/// Why a text was refused.
struct JsonLimitViolation {
  enum class Kind { kTooLarge, kTooDeep };
  Kind kind = Kind::kTooLarge;
  /// The limit that was exceeded (bytes or levels).
  std::size_t limit = 0;
  /// kTooLarge: the text's size in bytes; kTooDeep: the byte offset of the bracket that went
  /// one level too deep.
  std::size_t at = 0;
};

/// The first limit `text` exceeds, or nullopt. Depth counts '[' and '{' outside JSON strings
/// (escapes respected), so it bounds the depth nlohmann reaches for any text, valid or not.
/// Linear in the text, no allocation, noexcept; thread-safe.
std::optional<JsonLimitViolation> findJsonLimitViolation(std::string_view text,
                                                         const JsonLimits& limits) noexcept;

/// "DOCUMENT: 20000000 bytes, more than the limit of 16777216 bytes" or
/// "DOCUMENT: nested deeper than 128 levels (at byte 128)".
std::string describeJsonLimitViolation(const JsonLimitViolation& violation, std::string_view document);

/// Throws InputError (message as describeJsonLimitViolation) when `text` exceeds `limits`.
/// `document` names the text in the message, e.g. "plan file plan.json" or "HTTP 200 body".
void checkJsonLimits(std::string_view text, const JsonLimits& limits, std::string_view document);

/// checkJsonLimits(), then parses. Throws InputError "DOCUMENT: not valid JSON: <nlohmann's
/// message without its [json.exception...] prefix>" for any nlohmann exception (syntax errors,
/// numbers out of range such as 1e400, invalid UTF-8). Thread-safe.
nlohmann::json parseJsonWithinLimits(std::string_view text, const JsonLimits& limits,
                                     std::string_view document);

/// nlohmann's exception message without its "[json.exception.parse_error.101] " prefix.
std::string jsonErrorText(const nlohmann::json::exception& error);

/// A rendering of `value` for messages of at most about `maxChars` characters ("..." marks a
/// cut): never serialises more than that, however large or deep the value; invalid UTF-8 is
/// replaced, so nothing but std::bad_alloc is thrown. Thread-safe.
std::string boundedJsonDump(const nlohmann::json& value, std::size_t maxChars = 40);

/// The longest prefix of `text` of at most `maxBytes` bytes that does not end inside a UTF-8
/// sequence (so a cut never turns valid UTF-8 into invalid UTF-8).
std::string_view utf8Prefix(std::string_view text, std::size_t maxBytes) noexcept;

/// What readBoundedLine found.
enum class LineReadStatus { kLine, kEnd, kTooLong };

/// Reads the next line of `in` (without its '\n') into `line`. kTooLong when the line has more
/// than `maxBytes` bytes: then `line` holds the first maxBytes and the rest of the line is
/// skipped (never buffered). kEnd when no characters were left.
LineReadStatus readBoundedLine(std::istream& in, std::string& line, std::size_t maxBytes);

}  // namespace lang2manip
