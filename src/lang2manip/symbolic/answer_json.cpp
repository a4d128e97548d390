#include <optional>
#include <string>

#include "lang2manip/core/json_limits.hpp"
#include "lang2manip/symbolic/plan_parser.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

std::string_view trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r\n");
  return text.substr(first, last - first + 1);
}

/// The body of the first ``` fence (to the end of the text when the fence is not closed).
std::optional<std::string_view> fencedBlock(std::string_view text) {
  const auto open = text.find("```");
  if (open == std::string_view::npos) return std::nullopt;
  const auto lineEnd = text.find('\n', open);
  if (lineEnd == std::string_view::npos) return std::nullopt;
  const auto close = text.find("```", lineEnd);
  const auto length = close == std::string_view::npos ? std::string_view::npos : close - lineEnd - 1;
  return text.substr(lineEnd + 1, length);
}

/// From the first '{' to its matching '}' (strings and escapes respected), or to the end of the
/// text when it never closes.
std::optional<std::string_view> balancedObject(std::string_view text) {
  const auto open = text.find('{');
  if (open == std::string_view::npos) return std::nullopt;
  int depth = 0;
  bool inString = false;
  bool escaped = false;
  for (std::size_t i = open; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      escaped = !escaped && c == '\\';
      if (c == '"' && !escaped) inString = false;
      if (c != '\\') escaped = false;
      continue;
    }
    if (c == '"') inString = true;
    if (c == '{') ++depth;
    if (c == '}' && --depth == 0) return text.substr(open, i - open + 1);
  }
  return text.substr(open);
}

[[noreturn]] void fail(const std::string& message) { throw PlanParseError({"(answer): " + message}); }

}  // namespace

nlohmann::json extractJsonDocument(std::string_view text, const JsonLimits& limits) {
  if (text.size() > limits.maxBytes) {
    fail("the answer has " + std::to_string(text.size()) + " bytes, more than the limit of " +
         std::to_string(limits.maxBytes) + " bytes; answer with a short JSON plan");
  }
  const std::string_view body = trimmed(text);
  if (body.empty()) fail("empty answer; expected a JSON plan");
  std::string_view candidate = body;
  if (body.front() != '{' && body.front() != '[') {
    if (auto fenced = fencedBlock(body)) {
      candidate = trimmed(*fenced);
    } else if (auto object = balancedObject(body)) {
      candidate = *object;
    } else {
      fail("no JSON object found in the answer (it starts with \"" + std::string(utf8Prefix(body, 40)) +
           "\")");
    }
  }
  if (candidate.empty()) fail("empty JSON block in the answer");
  if (candidate.front() != '[') {
    if (auto object = balancedObject(candidate)) candidate = *object;
  }
  if (const auto violation = findJsonLimitViolation(candidate, limits)) {
    fail(describeJsonLimitViolation(*violation, "the JSON document") + "; a plan needs only a few levels");
  }
  try {
    // Any nlohmann failure (syntax, numbers out of range such as 1e400, invalid UTF-8) and a key
    // given twice in one object.
    return parseJsonWithinLimits(candidate, limits, "answer");
  } catch (const InputError& error) {
    fail(std::string(error.what()).substr(std::string("answer: ").size()));
  }
}

}  // namespace lang2manip
