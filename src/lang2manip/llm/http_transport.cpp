#include "lang2manip/llm/http_transport.hpp"

#include <httplib.h>
#include <openssl/x509.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <thread>

#include "lang2manip/llm/llm_support.hpp"
#include "lang2manip/llm/llm_client.hpp"

namespace lang2manip {

namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kSystemCaBundle = "/etc/ssl/certs/ca-certificates.crt";
constexpr auto kWatchInterval = std::chrono::milliseconds(5);

bool equalsIgnoringCase(const std::string& a, const std::string& b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

LlmError badUrl(const std::string& what, const std::string& url, const std::string& problem) {
  return LlmError(LlmErrorKind::kConfiguration,
                  what + ": bad base URL \"" + url + "\": " + problem +
                      " (expected e.g. https://host[:port][/path])");
}

int parsePort(const std::string& text, const std::string& what, const std::string& url) {
  if (text.empty() || text.size() > 5 ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    throw badUrl(what, url, "port \"" + text + "\" is not a number");
  }
  const int port = std::stoi(text);
  if (port < 1 || port > 65535) throw badUrl(what, url, "port " + text + " is out of range");
  return port;
}

/// Splits seconds into the (seconds, microseconds) pair cpp-httplib takes.
std::pair<time_t, time_t> splitSeconds(double seconds) {
  const double clamped = std::clamp(seconds, 0.001, 1.0e6);
  const auto whole = static_cast<time_t>(std::floor(clamped));
  const auto micro = static_cast<time_t>((clamped - static_cast<double>(whole)) * 1.0e6);
  return {whole, micro};
}

/// Stops the client's request from another thread when the attempt's time runs out or the stop
/// condition fires; cpp-httplib's stop() shuts the socket down, which ends a blocked read.
class AttemptWatchdog {
 public:
  enum class Fired { kNone, kStopCondition, kTimeLimit };

  AttemptWatchdog(httplib::Client& client, const StopCondition& stop, Clock::time_point deadline)
      : thread_([this, &client, stop, deadline] { watch(client, stop, deadline); }) {}

  ~AttemptWatchdog() { finish(); }
  AttemptWatchdog(const AttemptWatchdog&) = delete;
  AttemptWatchdog& operator=(const AttemptWatchdog&) = delete;

  /// Ends the watch; afterwards fired() is final.
  void finish() {
    {
      std::lock_guard lock(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

  [[nodiscard]] Fired fired() const { return fired_; }

 private:
  void watch(httplib::Client& client, const StopCondition& stop, Clock::time_point deadline) {
    std::unique_lock lock(mutex_);
    while (!done_) {
      if (stop.shouldStop()) {
        fired_ = Fired::kStopCondition;
      } else if (Clock::now() >= deadline) {
        fired_ = Fired::kTimeLimit;
      }
      if (fired_ != Fired::kNone) {
        client.stop();
        return;
      }
      wake_.wait_for(lock, kWatchInterval);
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  Fired fired_ = Fired::kNone;
  std::thread thread_;
};

void configureClient(httplib::Client& client, const HttpEndpoint& endpoint,
                     const HttpOptions& options) {
  const auto [connectSeconds, connectMicros] = splitSeconds(options.connectTimeoutSeconds);
  const auto [requestSeconds, requestMicros] = splitSeconds(options.requestTimeoutSeconds);
  client.set_connection_timeout(connectSeconds, connectMicros);
  client.set_read_timeout(requestSeconds, requestMicros);
  client.set_write_timeout(requestSeconds, requestMicros);
  client.set_tcp_nodelay(true);
  client.set_keep_alive(false);
  client.set_follow_location(false);
  if (endpoint.scheme == "https") {
    client.enable_server_certificate_verification(true);
    if (!options.caCertFile.empty()) {
      client.set_ca_cert_path(options.caCertFile);
    } else if (std::filesystem::exists(kSystemCaBundle)) {
      client.set_ca_cert_path(kSystemCaBundle);
    }
  }
}

LlmError transportError(httplib::Error error, const httplib::Client& client,
                        const HttpEndpoint& endpoint, const HttpOptions& options,
                        double elapsedSeconds) {
  const std::string where = endpoint.origin();
  switch (error) {
    case httplib::Error::ConnectionTimeout:
      return LlmError(LlmErrorKind::kTimeout,
                      "no connection to " + where + " within " +
                          formatSeconds(options.connectTimeoutSeconds) + " s");
    case httplib::Error::Connection:
      return LlmError(LlmErrorKind::kTransport, "cannot connect to " + where);
    case httplib::Error::SSLServerVerification: {
      const long result = client.get_openssl_verify_result();
      return LlmError(LlmErrorKind::kTransport,
                      "TLS certificate of " + where + " failed verification: " +
                          X509_verify_cert_error_string(result) +
                          (options.caCertFile.empty() ? "" : " (CA file " + options.caCertFile + ")"));
    }
    case httplib::Error::SSLConnection:
      return LlmError(LlmErrorKind::kTransport, "TLS handshake with " + where + " failed");
    case httplib::Error::SSLLoadingCerts:
      return LlmError(LlmErrorKind::kTransport,
                      "cannot load CA certificates" +
                          (options.caCertFile.empty() ? std::string()
                                                      : " from " + options.caCertFile));
    case httplib::Error::Read:
      if (elapsedSeconds >= 0.95 * options.requestTimeoutSeconds) {
        return LlmError(LlmErrorKind::kTimeout,
                        "no answer from " + where + " within " +
                            formatSeconds(options.requestTimeoutSeconds) + " s");
      }
      return LlmError(LlmErrorKind::kTransport, "connection to " + where + " lost while reading");
    default:
      return LlmError(LlmErrorKind::kTransport,
                      "request to " + where + " failed: " + httplib::to_string(error));
  }
}

LlmError stoppedError(const StopCondition& stop, const HttpEndpoint& endpoint) {
  if (stop.secondsLeft() <= 0.0) {
    return LlmError(LlmErrorKind::kTimeout,
                    "time budget ran out waiting for " + endpoint.origin());
  }
  return LlmError(LlmErrorKind::kCancelled, "cancelled while waiting for " + endpoint.origin());
}

}  // namespace

std::string HttpEndpoint::origin() const {
  return scheme + "://" + host + ":" + std::to_string(port);
}

std::string HttpEndpoint::toString() const { return origin() + basePath; }

HttpEndpoint parseBaseUrl(const std::string& url, const std::string& what) {
  const std::size_t schemeEnd = url.find("://");
  if (schemeEnd == std::string::npos) throw badUrl(what, url, "no scheme (http:// or https://)");
  HttpEndpoint endpoint;
  endpoint.scheme = url.substr(0, schemeEnd);
  std::transform(endpoint.scheme.begin(), endpoint.scheme.end(), endpoint.scheme.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (endpoint.scheme != "http" && endpoint.scheme != "https") {
    throw badUrl(what, url, "scheme \"" + endpoint.scheme + "\" is not http or https");
  }
  const std::string rest = url.substr(schemeEnd + 3);
  if (rest.find_first_of("?#") != std::string::npos) {
    throw badUrl(what, url, "query strings and fragments are not allowed");
  }
  const std::size_t pathStart = rest.find('/');
  const std::string authority = rest.substr(0, pathStart);
  endpoint.basePath = pathStart == std::string::npos ? "" : rest.substr(pathStart);
  while (!endpoint.basePath.empty() && endpoint.basePath.back() == '/') endpoint.basePath.pop_back();
  if (authority.find('@') != std::string::npos) {
    throw badUrl(what, url, "credentials in the URL are not allowed");
  }
  const std::size_t colon = authority.rfind(':');
  const bool bracketed = !authority.empty() && authority.front() == '[';
  const bool hasPort = colon != std::string::npos && (!bracketed || colon > authority.find(']'));
  endpoint.host = hasPort ? authority.substr(0, colon) : authority;
  if (endpoint.host.empty()) throw badUrl(what, url, "no host");
  endpoint.port = hasPort ? parsePort(authority.substr(colon + 1), what, url)
                          : (endpoint.scheme == "https" ? 443 : 80);
  return endpoint;
}

std::string findHeader(const HttpHeaders& headers, const std::string& name) {
  for (const auto& [key, value] : headers) {
    if (equalsIgnoringCase(key, name)) return value;
  }
  return {};
}

HttpResponse postJson(const HttpEndpoint& endpoint, const HttpRequest& request,
                      const HttpOptions& options, const StopCondition& stop) {
  if (stop.shouldStop()) throw stoppedError(stop, endpoint);
  httplib::Client client(endpoint.origin());
  configureClient(client, endpoint, options);
  httplib::Headers headers;
  for (const auto& [name, value] : request.headers) headers.emplace(name, value);

  const Clock::time_point start = Clock::now();
  const auto limit = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(options.requestTimeoutSeconds));
  httplib::Result result = [&] {
    AttemptWatchdog watchdog(client, stop, start + limit);
    httplib::Result sent =
        client.Post(endpoint.basePath + request.path, headers, request.body, "application/json");
    watchdog.finish();
    if (watchdog.fired() == AttemptWatchdog::Fired::kStopCondition) {
      throw stoppedError(stop, endpoint);
    }
    if (watchdog.fired() == AttemptWatchdog::Fired::kTimeLimit && !sent) {
      throw LlmError(LlmErrorKind::kTimeout,
                     "no answer from " + endpoint.origin() + " within " +
                         formatSeconds(options.requestTimeoutSeconds) + " s");
    }
    return sent;
  }();
  const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  if (!result) throw transportError(result.error(), client, endpoint, options, elapsed);

  HttpResponse response;
  response.status = result->status;
  response.body = std::move(result->body);
  for (const auto& [name, value] : result->headers) response.headers.emplace_back(name, value);
  return response;
}

}  // namespace lang2manip
