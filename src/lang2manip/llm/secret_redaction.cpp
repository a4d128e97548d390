#include "lang2manip/llm/secret_redaction.hpp"

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>

#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {
namespace {

/// How `secret` appears inside a JSON string ("a\"b" for a"b), without the quotes.
std::string jsonEscaped(const std::string& secret) {
  const std::string quoted =
      nlohmann::json(secret).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return quoted.substr(1, quoted.size() - 2);
}

}  // namespace

bool isSecretHeader(const std::string& name) {
  static const std::vector<std::string> kSecretHeaders = {
      "authorization", "proxy-authorization", "x-api-key", "x-goog-api-key", "api-key", "cookie"};
  const std::string lower = lowercase(name);
  return std::find(kSecretHeaders.begin(), kSecretHeaders.end(), lower) != kSecretHeaders.end();
}

SecretRedactor::SecretRedactor(const std::vector<std::string>& secrets) {
  for (const std::string& secret : secrets) add(secret);
  // Longest first, so that a secret containing another is replaced whole.
  std::sort(secrets_.begin(), secrets_.end(),
            [](const std::string& a, const std::string& b) { return a.size() > b.size(); });
}

void SecretRedactor::collectSecretHeaderValues(const HttpHeaders& headers, std::vector<std::string>& secrets) {
  for (const auto& [name, value] : headers) {
    if (!isSecretHeader(name)) continue;
    secrets.push_back(value);
    // "Bearer TOKEN", "Basic TOKEN": the token alone may be echoed too.
    const std::size_t space = value.find(' ');
    if (space != std::string::npos) secrets.push_back(value.substr(space + 1));
  }
}

void SecretRedactor::add(const std::string& secret) {
  if (secret.size() < kMinRedactedSecretLength) return;
  for (const std::string& form : {secret, jsonEscaped(secret)}) {
    if (std::find(secrets_.begin(), secrets_.end(), form) == secrets_.end()) secrets_.push_back(form);
  }
}

std::string SecretRedactor::redact(std::string text) const {
  const std::string replacement = kRedactedText;
  for (const std::string& secret : secrets_) {
    for (std::size_t at = text.find(secret); at != std::string::npos; at = text.find(secret, at + replacement.size())) {
      text.replace(at, secret.size(), replacement);
    }
  }
  return text;
}

HttpHeaders SecretRedactor::redact(HttpHeaders headers) const {
  for (auto& [name, value] : headers) {
    name = redact(std::move(name));
    value = redact(std::move(value));
  }
  return headers;
}

}  // namespace lang2manip
