#pragma once
/// @file One HTTP(S) POST of a JSON body, over cpp-httplib with OpenSSL: certificate
/// verification against the system CA bundle, connect and per-attempt timeouts, cancellation
/// through a StopCondition. cpp-httplib stays out of this header (its class layout depends on
/// compile definitions only this module's sources get).

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "lang2manip/core/stop_condition.hpp"

namespace lang2manip {

/// Where requests go: "https://api.openai.com/v1" -> https, api.openai.com, 443, "/v1".
struct HttpEndpoint {
  std::string scheme;    ///< "http" or "https"
  std::string host;
  int port = 0;
  std::string basePath;  ///< without a trailing slash; "" for the root

  /// "scheme://host:port" (no path).
  [[nodiscard]] std::string origin() const;
  /// "scheme://host:port/basePath".
  [[nodiscard]] std::string toString() const;
};

/// Parses an http(s) base URL. Throws LlmError(kConfiguration) naming `what` (e.g. "OPENAI_BASE_URL")
/// for a missing scheme, an unsupported scheme, an empty host or a bad port. Query strings and
/// fragments are rejected.
HttpEndpoint parseBaseUrl(const std::string& url, const std::string& what);

/// Proxy environment variables that are set (name -> value); see http_proxy.hpp.
using ProxyVariables = std::map<std::string, std::string>;

/// Bytes an LLM response body may have by default: plans are a few kB, and a server answering
/// more is broken or hostile.
inline constexpr std::size_t kDefaultMaxResponseBytes = std::size_t{4} << 20;

/// Transport settings shared by every protocol.
struct HttpOptions {
  /// Limit for establishing the TCP (and TLS) connection.
  double connectTimeoutSeconds = 10.0;
  /// Limit for one whole attempt (send and receive), enforced even against a server that
  /// trickles bytes.
  double requestTimeoutSeconds = 120.0;
  /// PEM file of trusted certificates; empty: the system bundle
  /// (/etc/ssl/certs/ca-certificates.crt when present, else OpenSSL's default paths).
  std::string caCertFile;
  /// Largest response body accepted, whatever the status; enforced while receiving (after
  /// decompression), so a larger answer is never held in memory.
  std::size_t maxResponseBytes = kDefaultMaxResponseBytes;
  /// The proxy variables of the environment (https_proxy, no_proxy, ...): requests go through the
  /// proxy they name (see proxyFor()); empty: every connection is direct.
  ProxyVariables proxyVariables;
};

/// Case-insensitive name, value.
using HttpHeaders = std::vector<std::pair<std::string, std::string>>;

/// The value of header `name` (case-insensitive), "" when absent.
std::string findHeader(const HttpHeaders& headers, const std::string& name);

struct HttpRequest {
  std::string path;  ///< appended to the endpoint's basePath; starts with '/'
  HttpHeaders headers;
  std::string body;  ///< sent as application/json
};

struct HttpResponse {
  int status = 0;
  /// The reason phrase of the status line ("Found"); may be empty.
  std::string reason;
  HttpHeaders headers;
  std::string body;
};

/// "HTTP 302 Found" (the standard phrase when the server sent none; just "HTTP 599" for a
/// status without one).
std::string httpStatusText(int status, const std::string& reason);

/// POSTs `request` once; redirects are not followed. Any HTTP status is returned as a response.
/// Throws LlmError: kBadResponse when the body exceeds options.maxResponseBytes (stopping the
/// transfer at that point, or before it starts when Content-Length says so; the message names
/// the limit), kTimeout when the attempt exceeds its limit or the stop condition's deadline
/// passes, kCancelled when a cancel flag of `stop` is set (checked while waiting), kTransport for
/// connection, TLS and certificate failures. Thread-safe (each call has its own connection).
HttpResponse postJson(const HttpEndpoint& endpoint, const HttpRequest& request,
                      const HttpOptions& options, const StopCondition& stop);

}  // namespace lang2manip
