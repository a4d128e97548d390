#pragma once
/// @file The HTTP proxy an LLM request goes through, from the environment as curl reads it:
/// `https_proxy`/`HTTPS_PROXY` for https endpoints, `http_proxy` for http ones (the upper-case
/// HTTP_PROXY is ignored, as curl does: a web server's CGI sets it from a request header), then
/// `all_proxy`/`ALL_PROXY`; `no_proxy`/`NO_PROXY` lists hosts reached directly.

#include <array>
#include <optional>
#include <string>

#include "lang2manip/llm/http_transport.hpp"

namespace lang2manip {

/// An HTTP proxy: requests to http endpoints are sent to it in absolute form, https ones tunnel
/// through it with CONNECT.
struct HttpProxy {
  std::string host;
  int port = 1080;  ///< curl's default when the URL names none
  std::string user;      ///< percent-decoded; empty: no credentials
  std::string password;  ///< percent-decoded
  /// The environment variable it came from ("HTTPS_PROXY"), for messages.
  std::string source;

  /// "http://host:port" (never the credentials).
  [[nodiscard]] std::string origin() const;
};

/// Parses a proxy URL as the environment gives it: "http://[user[:password]@]host[:port][/]" or
/// "host[:port]". Throws LlmError(kConfiguration) naming `source` for another scheme (https://
/// and socks proxies are not supported), an empty host or a bad port.
HttpProxy parseProxyUrl(const std::string& url, const std::string& source);

/// True when the no-proxy list `list` (comma- or space-separated; "*" for every host; a name
/// matches itself and its subdomains, with or without a leading dot; an entry may end in
/// ":port"; IP addresses match exactly; case-insensitive) says `host`:`port` is reached directly.
bool noProxyMatches(const std::string& list, const std::string& host, int port);

/// The environment variables a proxy is chosen from, in the order they are looked at.
inline constexpr std::array<const char*, 7> kProxyVariableNames = {"https_proxy", "HTTPS_PROXY", "http_proxy", "all_proxy",
                                                                   "ALL_PROXY",   "no_proxy",    "NO_PROXY"};

/// The proxy for `endpoint` given the proxy variables that are set (name -> value, see the file
/// comment), or nullopt for a direct connection. Throws as parseProxyUrl() for a malformed one.
std::optional<HttpProxy> proxyFor(const HttpEndpoint& endpoint, const ProxyVariables& variables);

}  // namespace lang2manip
