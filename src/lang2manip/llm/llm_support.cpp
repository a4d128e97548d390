#include "lang2manip/llm/llm_support.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "lang2manip/llm/llm_client.hpp"

namespace lang2manip {

namespace {
/// A server's error message is quoted up to this many bytes.
constexpr std::size_t kMaxServerMessageBytes = 500;

LlmError missing(const std::string& what, const std::string& who) {
  return LlmError(LlmErrorKind::kBadResponse, who + ": answer has no " + what);
}
std::string joined(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}
}  // namespace

std::string formatSeconds(double seconds) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, seconds >= 100.0 ? "%.0f" : "%.3g", seconds);
  return buffer;
}

nlohmann::json parseResponseJson(const std::string& body, const std::string& who,
                                 const JsonLimits& limits) {
  if (const auto violation = findJsonLimitViolation(body, limits)) {
    throw LlmError(LlmErrorKind::kBadResponse, describeJsonLimitViolation(*violation, who + ": answer body"));
  }
  nlohmann::json parsed;
  try {
    parsed = nlohmann::json::parse(body);
  } catch (const nlohmann::json::exception& error) {
    throw LlmError(LlmErrorKind::kBadResponse, who + ": answer body is not JSON (" + jsonErrorText(error) +
                                                   "): \"" + abbreviated(body, 120) + "\"");
  }
  if (!parsed.is_object()) {
    throw LlmError(LlmErrorKind::kBadResponse, who + ": answer body is not a JSON object");
  }
  return parsed;
}

const nlohmann::json& requireMember(const nlohmann::json& object, const std::string& key,
                                    const std::string& path, const std::string& who) {
  if (!object.is_object()) throw missing(joined(path, key) + " (" + path + " is not an object)", who);
  const auto found = object.find(key);
  if (found == object.end() || found->is_null()) throw missing(joined(path, key), who);
  return *found;
}

std::string requireString(const nlohmann::json& object, const std::string& key,
                          const std::string& path, const std::string& who) {
  const nlohmann::json& value = requireMember(object, key, path, who);
  if (!value.is_string()) {
    throw LlmError(LlmErrorKind::kBadResponse,
                   who + ": answer field " + joined(path, key) + " is not a string");
  }
  return value.get<std::string>();
}

const nlohmann::json& requireFirstElement(const nlohmann::json& object, const std::string& key,
                                          const std::string& path, const std::string& who) {
  const nlohmann::json& array = requireMember(object, key, path, who);
  if (!array.is_array() || array.empty()) throw missing(joined(path, key) + "[0]", who);
  return array.front();
}

std::string optionalString(const nlohmann::json& object, const std::string& key) {
  if (!object.is_object()) return {};
  const auto found = object.find(key);
  return found != object.end() && found->is_string() ? found->get<std::string>() : std::string();
}

std::optional<long> tokenCount(const nlohmann::json& object, const std::string& key) {
  if (!object.is_object()) return std::nullopt;
  const auto found = object.find(key);
  if (found == object.end()) return std::nullopt;
  const nlohmann::json& value = *found;
  if (value.is_number_unsigned()) {
    const auto count = value.get<std::uint64_t>();
    if (count <= static_cast<std::uint64_t>(kMaxTokenCount)) return static_cast<long>(count);
  } else if (value.is_number_integer()) {
    const auto count = value.get<std::int64_t>();
    if (count >= 0 && count <= kMaxTokenCount) return static_cast<long>(count);
  } else if (value.is_number_float()) {
    const double count = value.get<double>();
    if (std::isfinite(count) && count >= 0.0 && count <= static_cast<double>(kMaxTokenCount) &&
        std::floor(count) == count) {
      return static_cast<long>(count);
    }
  }
  return std::nullopt;
}

std::optional<long> tokenCountOrZero(const nlohmann::json& object, const std::string& key) {
  if (!object.is_object()) return std::nullopt;
  const auto found = object.find(key);
  if (found == object.end() || found->is_null()) return 0L;
  return tokenCount(object, key);
}

std::string errorMessageFromBody(const std::string& body) {
  if (body.find_first_not_of(" \t\r\n") == std::string::npos) return {};
  const nlohmann::json parsed = findJsonLimitViolation(body, {}) ? nlohmann::json()
                                                                 : nlohmann::json::parse(body, nullptr, false);
  if (parsed.is_object() && parsed.contains("error")) {
    const nlohmann::json& error = parsed["error"];
    if (error.is_string()) return abbreviated(error.get<std::string>(), kMaxServerMessageBytes);
    const std::string message = optionalString(error, "message");
    if (!message.empty()) return abbreviated(message, kMaxServerMessageBytes);
  }
  if (parsed.is_object()) {
    const std::string message = optionalString(parsed, "message");
    if (!message.empty()) return abbreviated(message, kMaxServerMessageBytes);
  }
  return abbreviated(body);
}

std::string abbreviated(const std::string& text, std::size_t limit) {
  return text.size() <= limit ? text : std::string(utf8Prefix(text, limit)) + "...";
}

}  // namespace lang2manip
