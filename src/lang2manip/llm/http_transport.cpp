#include "lang2manip/llm/http_transport.hpp"

#include <httplib.h>
#include <openssl/x509.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <thread>

#include "lang2manip/llm/http_proxy.hpp"
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
                        double elapsedSeconds, const std::optional<HttpProxy>& proxy) {
  const std::string where =
      endpoint.origin() + (proxy ? " through proxy " + proxy->origin() + " (from " + proxy->source + ")" : "");
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

/// Gathers a response body up to a limit, refusing it as soon as the limit is passed (or when
/// the declared Content-Length already passes it).
class BodyCollector {
 public:
  BodyCollector(std::size_t maxBytes, std::string& body) : maxBytes_(maxBytes), body_(body) {}

  bool accept(const httplib::Response& head) {
    status_ = head.status;
    reason_ = head.reason;
    const std::string declared = head.get_header_value("Content-Length");
    if (!declared.empty() && declared.size() <= 19 &&
        std::all_of(declared.begin(), declared.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      const unsigned long long length = std::stoull(declared);
      if (length > maxBytes_) {
        declaredBytes_ = length;
        overLimit_ = true;
        return false;
      }
    }
    return true;
  }

  bool append(const char* data, std::size_t length) {
    if (length > maxBytes_ - body_.size()) {
      receivedBytes_ = body_.size() + length;
      overLimit_ = true;
      return false;
    }
    body_.append(data, length);
    return true;
  }

  [[nodiscard]] bool overLimit() const { return overLimit_; }
  [[nodiscard]] int status() const { return status_; }
  [[nodiscard]] const std::string& reason() const { return reason_; }
  /// "Content-Length 52428800" or "more than N bytes received".
  [[nodiscard]] std::string sizeText() const {
    if (declaredBytes_ > 0) return "Content-Length " + std::to_string(declaredBytes_);
    return "at least " + std::to_string(receivedBytes_) + " bytes sent";
  }

 private:
  std::size_t maxBytes_;
  std::string& body_;
  int status_ = 0;
  std::string reason_;
  bool overLimit_ = false;
  unsigned long long declaredBytes_ = 0;
  std::size_t receivedBytes_ = 0;
};

/// The standard reason phrase of the statuses LLM servers and proxies send.
std::string standardReason(int status) {
  switch (status) {
    case 200: return "OK";
    case 201: return "Created";
    case 204: return "No Content";
    case 301: return "Moved Permanently";
    case 302: return "Found";
    case 303: return "See Other";
    case 304: return "Not Modified";
    case 307: return "Temporary Redirect";
    case 308: return "Permanent Redirect";
    case 400: return "Bad Request";
    case 401: return "Unauthorized";
    case 402: return "Payment Required";
    case 403: return "Forbidden";
    case 404: return "Not Found";
    case 405: return "Method Not Allowed";
    case 408: return "Request Timeout";
    case 409: return "Conflict";
    case 413: return "Content Too Large";
    case 415: return "Unsupported Media Type";
    case 422: return "Unprocessable Content";
    case 425: return "Too Early";
    case 429: return "Too Many Requests";
    case 500: return "Internal Server Error";
    case 501: return "Not Implemented";
    case 502: return "Bad Gateway";
    case 503: return "Service Unavailable";
    case 504: return "Gateway Timeout";
    default: return "";
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

std::string httpStatusText(int status, const std::string& reason) {
  const std::string phrase = reason.find_first_not_of(" \t") != std::string::npos ? reason : standardReason(status);
  return "HTTP " + std::to_string(status) + (phrase.empty() ? "" : " " + phrase);
}

HttpResponse postJson(const HttpEndpoint& endpoint, const HttpRequest& request,
                      const HttpOptions& options, const StopCondition& stop) {
  if (stop.shouldStop()) throw stoppedError(stop, endpoint);
  httplib::Client client(endpoint.origin());
  configureClient(client, endpoint, options);
  const std::optional<HttpProxy> proxy = proxyFor(endpoint, options.proxyVariables);
  if (proxy) {
    client.set_proxy(proxy->host, proxy->port);
    if (!proxy->user.empty()) client.set_proxy_basic_auth(proxy->user, proxy->password);
  }

  HttpResponse response;
  BodyCollector collector(options.maxResponseBytes, response.body);
  httplib::Request post;
  post.method = "POST";
  post.path = endpoint.basePath + request.path;
  for (const auto& [name, value] : request.headers) post.headers.emplace(name, value);
  post.headers.emplace("Content-Type", "application/json");
  post.body = request.body;
  post.response_handler = [&collector](const httplib::Response& head) { return collector.accept(head); };
  post.content_receiver = [&collector](const char* data, std::size_t length, std::uint64_t /*offset*/,
                                       std::uint64_t /*total*/) { return collector.append(data, length); };

  const Clock::time_point start = Clock::now();
  const auto limit = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(options.requestTimeoutSeconds));
  httplib::Result result = [&] {
    AttemptWatchdog watchdog(client, stop, start + limit);
    httplib::Result sent = client.send(post);
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
  if (collector.overLimit()) {
    throw LlmError(LlmErrorKind::kBadResponse,
                   httpStatusText(collector.status(), collector.reason()) + " answer from " + endpoint.origin() +
                       " is larger than the response size limit of " + std::to_string(options.maxResponseBytes) +
                       " bytes (" + collector.sizeText() + "); not read further (--llm-max-response-bytes)",
                   collector.status());
  }
  const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  if (!result) throw transportError(result.error(), client, endpoint, options, elapsed, proxy);

  response.status = result->status;
  response.reason = result->reason;
  for (const auto& [name, value] : result->headers) response.headers.emplace_back(name, value);
  return response;
}

}  // namespace lang2manip
