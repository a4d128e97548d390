#pragma once
/// @file One headless Chromium driven over the Chrome DevTools Protocol on a pipe
/// (--remote-debugging-pipe: JSON messages ended by NUL on the browser's descriptors 3 and 4):
/// a page is loaded once and drawn into as many PNG pictures as wanted, instead of a browser
/// start per picture.

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace lang2manip {

class ChromiumSession {
 public:
  /// Starts `program` headless with a fresh profile in `profile`; every later step may take
  /// `timeoutSeconds`. Throws InputError when it cannot be started or does not answer.
  ChromiumSession(const std::string& program, const std::filesystem::path& profile, double timeoutSeconds);
  /// Closes the browser (killed if it does not leave within a second).
  ~ChromiumSession();
  ChromiumSession(const ChromiumSession&) = delete;
  ChromiumSession& operator=(const ChromiumSession&) = delete;

  /// Opens `url` in a page of `width` x `height` CSS pixels (a new document each time).
  void open(const std::string& url, int width, int height);

  /// The value of the JavaScript `expression` in the page, a promise awaited. Throws InputError
  /// with the page's exception text when it throws or rejects.
  nlohmann::json evaluate(const std::string& expression);

  /// The page as drawn now, as PNG bytes.
  std::string screenshot();

 private:
  nlohmann::json call(const std::string& method, const nlohmann::json& parameters, bool inPage = true);
  nlohmann::json nextMessage(std::chrono::steady_clock::time_point deadline);
  [[noreturn]] void fail(const std::string& what) const;
  /// Asks the browser to close, waits a second, kills it; closes the pipes. Idempotent.
  void shutDown() noexcept;

  std::string program_;
  double timeoutSeconds_;
  pid_t child_ = -1;
  int toBrowser_ = -1;
  int fromBrowser_ = -1;
  std::string received_;
  long nextId_ = 1;
  std::string sessionId_;
};

/// Bytes of RFC 4648 base64 text (padding optional); throws InputError on other characters.
std::string base64Decoded(const std::string& text);

}  // namespace lang2manip
