#include "lang2manip/llm/llm_support.hpp"

#include <cstdio>

#include "lang2manip/llm/llm_client.hpp"

namespace lang2manip {

namespace {
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

nlohmann::json parseResponseJson(const std::string& body, const std::string& who) {
  nlohmann::json parsed = nlohmann::json::parse(body, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded()) {
    throw LlmError(LlmErrorKind::kBadResponse,
                   who + ": answer body is not JSON: \"" + abbreviated(body, 120) + "\"");
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

long optionalCount(const nlohmann::json& object, const std::string& key) {
  if (!object.is_object()) return 0;
  const auto found = object.find(key);
  return found != object.end() && found->is_number() ? found->get<long>() : 0;
}

std::string errorMessageFromBody(const std::string& body) {
  const nlohmann::json parsed = nlohmann::json::parse(body, nullptr, false);
  if (parsed.is_object() && parsed.contains("error")) {
    const nlohmann::json& error = parsed["error"];
    if (error.is_string()) return error.get<std::string>();
    const std::string message = optionalString(error, "message");
    if (!message.empty()) return message;
  }
  if (parsed.is_object()) {
    const std::string message = optionalString(parsed, "message");
    if (!message.empty()) return message;
  }
  return abbreviated(body);
}

std::string abbreviated(const std::string& text, std::size_t limit) {
  return text.size() <= limit ? text : text.substr(0, limit) + "...";
}

}  // namespace lang2manip
