#include "lang2manip/cli/chromium_session.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <thread>
#include <vector>

#include "lang2manip/core/error.hpp"

extern char** environ;

namespace lang2manip {
namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

/// A message larger than this is not the browser's answer to anything asked here (a screenshot of
/// 7680 x 4320 pixels is well below it).
constexpr std::size_t kMaxMessageBytes = std::size_t{512} << 20;

int millisecondsUntil(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return static_cast<int>(std::max<long long>(0, std::min<long long>(left, 1000)));
}

int decodedValue(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

/// Ignores SIGPIPE while it lives (a write to a browser that died fails instead of ending us).
class PipeSignalIgnored {
 public:
  PipeSignalIgnored() {
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    ::sigaction(SIGPIPE, &ignore, &saved_);
  }
  ~PipeSignalIgnored() { ::sigaction(SIGPIPE, &saved_, nullptr); }
  PipeSignalIgnored(const PipeSignalIgnored&) = delete;
  PipeSignalIgnored& operator=(const PipeSignalIgnored&) = delete;

 private:
  struct sigaction saved_ {};
};

}  // namespace

std::string base64Decoded(const std::string& text) {
  std::string bytes;
  bytes.reserve(text.size() / 4 * 3);
  unsigned int bits = 0;
  int count = 0;
  for (const char c : text) {
    if (c == '=') break;
    const int value = decodedValue(c);
    if (value < 0) throw InputError("base64: unexpected character in the data");
    bits = (bits << 6U) | static_cast<unsigned int>(value);
    count += 6;
    if (count >= 8) {
      count -= 8;
      bytes.push_back(static_cast<char>((bits >> static_cast<unsigned int>(count)) & 0xFFU));
    }
  }
  return bytes;
}

ChromiumSession::ChromiumSession(const std::string& program, const std::filesystem::path& profile, double timeoutSeconds)
    : program_(program), timeoutSeconds_(timeoutSeconds) {
  std::array<int, 2> toPipe{};
  std::array<int, 2> fromPipe{};
  if (::pipe2(toPipe.data(), O_CLOEXEC) != 0 || ::pipe2(fromPipe.data(), O_CLOEXEC) != 0) fail("cannot be started: no pipe");
  // The browser's ends above 4 first, so that placing them on 3 and 4 cannot overwrite each other.
  const int browserReads = ::fcntl(toPipe[0], F_DUPFD_CLOEXEC, 10);
  const int browserWrites = ::fcntl(fromPipe[1], F_DUPFD_CLOEXEC, 10);
  ::close(toPipe[0]);
  ::close(fromPipe[1]);
  toBrowser_ = toPipe[1];
  fromBrowser_ = fromPipe[0];
  std::vector<std::string> arguments{program,
                                     "--headless",
                                     "--use-angle=swiftshader",
                                     "--enable-unsafe-swiftshader",
                                     "--hide-scrollbars",
                                     "--mute-audio",
                                     "--no-first-run",
                                     "--no-default-browser-check",
                                     "--user-data-dir=" + profile.string(),
                                     "--remote-debugging-pipe",
                                     "about:blank"};
  if (::geteuid() == 0) arguments.insert(arguments.begin() + 1, "--no-sandbox");  // Chromium refuses root otherwise
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, browserReads, 3);
  posix_spawn_file_actions_adddup2(&actions, browserWrites, 4);
  const int spawned = ::posix_spawn(&child_, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(browserReads);
  ::close(browserWrites);
  if (spawned != 0) {
    child_ = -1;
    fail("cannot be started: " + std::string(std::strerror(spawned)));
  }
  try {
    const json target = call("Target.createTarget", {{"url", "about:blank"}}, false);
    const json attached = call("Target.attachToTarget", {{"targetId", target.value("targetId", "")}, {"flatten", true}}, false);
    sessionId_ = attached.value("sessionId", "");
    if (sessionId_.empty()) fail("gave no page to draw in");
  } catch (...) {
    shutDown();
    throw;
  }
}

ChromiumSession::~ChromiumSession() { shutDown(); }

void ChromiumSession::shutDown() noexcept {
  if (child_ > 0) {
    const PipeSignalIgnored ignored;
    const std::string close = json{{"id", nextId_++}, {"method", "Browser.close"}}.dump() + '\0';
    [[maybe_unused]] const ssize_t written = ::write(toBrowser_, close.data(), close.size());
  }
  if (toBrowser_ >= 0) ::close(toBrowser_);
  if (fromBrowser_ >= 0) ::close(fromBrowser_);
  toBrowser_ = fromBrowser_ = -1;
  if (child_ <= 0) return;
  int status = 0;
  bool exited = false;
  for (int i = 0; i < 100 && !exited; ++i) {
    exited = ::waitpid(child_, &status, WNOHANG) == child_;
    if (!exited) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!exited) {
    ::kill(child_, SIGKILL);
    ::waitpid(child_, &status, 0);
  }
  child_ = -1;
}

void ChromiumSession::open(const std::string& url, int width, int height) {
  call("Emulation.setDeviceMetricsOverride", {{"width", width}, {"height", height}, {"deviceScaleFactor", 1}, {"mobile", false}});
  // Through a blank page: the same page with another #hash would not be loaded again.
  call("Page.navigate", {{"url", "about:blank"}});
  const json navigated = call("Page.navigate", {{"url", url}});
  if (navigated.contains("errorText")) fail("cannot open the page: " + navigated.value("errorText", ""));
}

json ChromiumSession::evaluate(const std::string& expression) {
  const json result = call("Runtime.evaluate", {{"expression", expression}, {"awaitPromise", true}, {"returnByValue", true}});
  if (result.contains("exceptionDetails")) {
    const json& details = result["exceptionDetails"];
    const std::string text = details.contains("exception") ? details["exception"].value("description", "") : details.value("text", "");
    throw InputError("render: the page failed: " + text.substr(0, 500));
  }
  return result.contains("result") ? result["result"].value("value", json()) : json();
}

std::string ChromiumSession::screenshot() {
  const json shot = call("Page.captureScreenshot", {{"format", "png"}});
  std::string png = base64Decoded(shot.value("data", ""));
  if (png.size() < 100) fail("drew no picture");
  return png;
}

json ChromiumSession::call(const std::string& method, const json& parameters, bool inPage) {
  const PipeSignalIgnored ignored;
  const long id = nextId_++;
  json message{{"id", id}, {"method", method}, {"params", parameters}};
  if (inPage) message["sessionId"] = sessionId_;
  const std::string text = message.dump() + '\0';
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeoutSeconds_));
  for (std::size_t sent = 0; sent < text.size();) {
    pollfd entry{toBrowser_, POLLOUT, 0};
    if (Clock::now() > deadline) fail("did not take the request " + method + " (within " + std::to_string(static_cast<int>(timeoutSeconds_)) + " s)");
    if (::poll(&entry, 1, millisecondsUntil(deadline)) <= 0) continue;
    const ssize_t n = ::write(toBrowser_, text.data() + sent, text.size() - sent);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("has gone (writing " + method + ")");
    sent += static_cast<std::size_t>(n);
  }
  for (;;) {
    const json reply = nextMessage(deadline);
    if (reply.value("id", -1L) != id) continue;  // events and other answers
    if (reply.contains("error")) fail("refused " + method + ": " + reply["error"].value("message", reply["error"].dump()));
    return reply.value("result", json::object());
  }
}

json ChromiumSession::nextMessage(Clock::time_point deadline) {
  for (;;) {
    if (const std::size_t end = received_.find('\0'); end != std::string::npos) {
      json message = json::parse(received_.substr(0, end), nullptr, false);
      received_.erase(0, end + 1);
      if (message.is_discarded() || !message.is_object()) fail("sent a message that is not JSON");
      return message;
    }
    if (received_.size() > kMaxMessageBytes) fail("sent a message of more than 512 MiB");
    if (Clock::now() > deadline) fail("did not answer (within " + std::to_string(static_cast<int>(timeoutSeconds_)) + " s)");
    pollfd entry{fromBrowser_, POLLIN, 0};
    if (::poll(&entry, 1, millisecondsUntil(deadline)) <= 0) continue;
    char buffer[65536];
    const ssize_t n = ::read(fromBrowser_, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("has gone (it closed its end of the pipe)");
    received_.append(buffer, static_cast<std::size_t>(n));
  }
}

void ChromiumSession::fail(const std::string& what) const { throw InputError("render: " + program_ + " " + what); }

}  // namespace lang2manip
