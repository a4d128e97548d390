#include "lang2manip/llm/http_proxy.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include "lang2manip/llm/llm_client.hpp"

namespace lang2manip {
namespace {

std::string lowerCase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

[[noreturn]] void badProxy(const std::string& source, const std::string& url, const std::string& why) {
  std::string shown;  // control bytes escaped: the value is shown, never sent to the terminal raw
  for (const char c : url.substr(0, 200)) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      shown += escaped;
    } else {
      shown += c;
    }
  }
  throw LlmError(LlmErrorKind::kConfiguration, source + "=\"" + shown + "\": " + why);
}

std::string percentDecoded(const std::string& text) {
  std::string decoded;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '%' && i + 2 < text.size() && std::isxdigit(static_cast<unsigned char>(text[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(text[i + 2]))) {
      decoded += static_cast<char>(std::stoi(text.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      decoded += text[i];
    }
  }
  return decoded;
}

/// The first of `names` set to something other than "", with its name.
std::optional<std::pair<std::string, std::string>> firstSet(const ProxyVariables& variables, std::initializer_list<const char*> names) {
  for (const char* name : names) {
    if (const auto found = variables.find(name); found != variables.end() && !found->second.empty()) return *found;
  }
  return std::nullopt;
}

/// `host` without IPv6 brackets, lower case.
std::string bareHost(const std::string& host) {
  const std::string lower = lowerCase(host);
  return lower.size() >= 2 && lower.front() == '[' && lower.back() == ']' ? lower.substr(1, lower.size() - 2) : lower;
}

bool entryMatches(std::string entry, const std::string& host, int port) {
  const std::size_t colon = entry.rfind(':');
  const bool bracketed = !entry.empty() && entry.front() == '[';
  const bool ipv6 = std::count(entry.begin(), entry.end(), ':') > 1 && !bracketed;
  if (colon != std::string::npos && !ipv6 && (!bracketed || colon > entry.find(']'))) {
    if (entry.substr(colon + 1) != std::to_string(port)) return false;
    entry.resize(colon);
  }
  entry = bareHost(entry);
  if (!entry.empty() && entry.front() == '.') entry.erase(0, 1);
  if (entry.empty()) return false;
  return host == entry || (host.size() > entry.size() && host.compare(host.size() - entry.size(), entry.size(), entry) == 0 &&
                           host[host.size() - entry.size() - 1] == '.');
}

}  // namespace

std::string HttpProxy::origin() const {
  const bool ipv6 = host.find(':') != std::string::npos;
  return "http://" + (ipv6 ? "[" + host + "]" : host) + ":" + std::to_string(port);
}

HttpProxy parseProxyUrl(const std::string& url, const std::string& source) {
  HttpProxy proxy;
  proxy.source = source;
  std::string rest = url;
  if (const std::size_t scheme = rest.find("://"); scheme != std::string::npos) {
    const std::string name = lowerCase(rest.substr(0, scheme));
    if (name != "http") badProxy(source, url, "a " + name + ":// proxy is not supported (only http:// proxies)");
    rest = rest.substr(scheme + 3);
  }
  if (const std::size_t slash = rest.find('/'); slash != std::string::npos) {
    if (rest.find_first_not_of('/', slash) != std::string::npos) badProxy(source, url, "a proxy URL has no path");
    rest.resize(slash);
  }
  if (const std::size_t at = rest.rfind('@'); at != std::string::npos) {
    const std::string credentials = rest.substr(0, at);
    const std::size_t colon = credentials.find(':');
    proxy.user = percentDecoded(credentials.substr(0, colon));
    proxy.password = colon == std::string::npos ? "" : percentDecoded(credentials.substr(colon + 1));
    rest = rest.substr(at + 1);
  }
  const bool bracketed = !rest.empty() && rest.front() == '[';
  const std::size_t colon = rest.rfind(':');
  const bool hasPort = colon != std::string::npos && (!bracketed || colon > rest.find(']'));
  proxy.host = bareHost(hasPort ? rest.substr(0, colon) : rest);
  if (proxy.host.empty()) badProxy(source, url, "no host");
  const bool hostName = std::all_of(proxy.host.begin(), proxy.host.end(), [](unsigned char c) {
    return std::isalnum(c) != 0 || c == '.' || c == '-' || c == '_' || c == ':';
  });
  if (!hostName) badProxy(source, url, "the host has a character no host name or address has");
  if (hasPort) {
    const std::string digits = rest.substr(colon + 1);
    if (digits.empty() || digits.size() > 5 || digits.find_first_not_of("0123456789") != std::string::npos ||
        std::stoi(digits) < 1 || std::stoi(digits) > 65535) {
      badProxy(source, url, "port \"" + digits.substr(0, 20) + "\" is not a number from 1 to 65535");
    }
    proxy.port = std::stoi(digits);
  }
  return proxy;
}

bool noProxyMatches(const std::string& list, const std::string& host, int port) {
  const std::string target = bareHost(host);
  std::string entry;
  for (std::size_t i = 0; i <= list.size(); ++i) {
    if (i == list.size() || list[i] == ',' || std::isspace(static_cast<unsigned char>(list[i]))) {
      if (entry == "*" || entryMatches(entry, target, port)) return true;
      entry.clear();
    } else {
      entry += list[i];
    }
  }
  return false;
}

std::optional<HttpProxy> proxyFor(const HttpEndpoint& endpoint, const ProxyVariables& variables) {
  const auto proxy = endpoint.scheme == "https" ? firstSet(variables, {"https_proxy", "HTTPS_PROXY", "all_proxy", "ALL_PROXY"})
                                                : firstSet(variables, {"http_proxy", "all_proxy", "ALL_PROXY"});
  if (!proxy) return std::nullopt;
  if (const auto direct = firstSet(variables, {"no_proxy", "NO_PROXY"}); direct && noProxyMatches(direct->second, endpoint.host, endpoint.port)) {
    return std::nullopt;
  }
  return parseProxyUrl(proxy->second, proxy->first);
}

}  // namespace lang2manip
