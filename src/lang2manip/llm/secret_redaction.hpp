#pragma once
/// @file Keeps credentials out of everything an LLM client lets through: a server that echoes the
/// API key (in an answer, an error body, a Location header) must not get it quoted in error
/// messages, log lines, answers or record files.

#include <string>
#include <vector>

#include "lang2manip/llm/http_transport.hpp"

namespace lang2manip {

/// What a secret is replaced with.
inline constexpr const char* kRedactedText = "[redacted]";

/// Secrets shorter than this are not searched for: replacing every "x" of an answer would
/// destroy it, and no real credential is that short.
inline constexpr std::size_t kMinRedactedSecretLength = 8;

/// True for headers whose values are credentials (case-insensitive): Authorization,
/// Proxy-Authorization, x-api-key, x-goog-api-key, api-key, Cookie.
bool isSecretHeader(const std::string& name);

/// Replaces configured secrets in text. Each secret is also searched for as it appears inside a
/// JSON string (escaped), and a header value "Bearer TOKEN" yields TOKEN too. Immutable after
/// construction; thread-safe.
class SecretRedactor {
 public:
  SecretRedactor() = default;
  /// `secrets`: API keys and the like; empty and too short ones are ignored.
  explicit SecretRedactor(const std::vector<std::string>& secrets);

  /// Adds the values of the secret headers (isSecretHeader) of `headers` to `secrets`.
  static void collectSecretHeaderValues(const HttpHeaders& headers, std::vector<std::string>& secrets);

  /// `text` with every secret replaced by kRedactedText.
  [[nodiscard]] std::string redact(std::string text) const;
  /// redact() applied to every value (and name) of `headers`.
  [[nodiscard]] HttpHeaders redact(HttpHeaders headers) const;

  [[nodiscard]] bool empty() const noexcept { return secrets_.empty(); }

 private:
  void add(const std::string& secret);
  std::vector<std::string> secrets_;
};

}  // namespace lang2manip
