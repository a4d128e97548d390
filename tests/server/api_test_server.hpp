#pragma once
/// @file A real ApiServer on a free loopback port for one test, and requests to it through a real
/// HTTP client (cpp-httplib).

// Eigen (through api_server.hpp) before httplib.h: glibc's <resolv.h>, which httplib includes,
// defines the macro _res that Eigen uses as a parameter name.
#include "lang2manip/server/api_server.hpp"

#include <httplib.h>

#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include <string>
#include <thread>

namespace lang2manip::test {

class ApiTestServer {
 public:
  explicit ApiTestServer(ServerOptions options = {}) : server_(withFreePort(std::move(options))), thread_([this] { server_.serve(); }) {
    // serve() may not be listening yet: wait until it answers.
    httplib::Client probe = client();
    for (int i = 0; i < 200 && !probe.Get("/api/health", {{"Authorization", "Bearer " + token()}}); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  ~ApiTestServer() {
    server_.stop();
    thread_.join();
  }
  ApiTestServer(const ApiTestServer&) = delete;
  ApiTestServer& operator=(const ApiTestServer&) = delete;

  [[nodiscard]] int port() const { return server_.port(); }
  [[nodiscard]] ApiServer& server() { return server_; }
  [[nodiscard]] httplib::Client client() const {
    httplib::Client http("127.0.0.1", server_.port());
    http.set_read_timeout(120, 0);
    return http;
  }

  /// POST `body` (a JSON text) to `path`.
  httplib::Result post(const std::string& path, const std::string& body = "{}") const {
    return client().Post(path.c_str(), headers(), body, "application/json");
  }
  httplib::Result postJson(const std::string& path, const nlohmann::json& body) const { return post(path, body.dump()); }
  httplib::Result get(const std::string& path) const { return client().Get(path.c_str(), headers()); }
  httplib::Result del(const std::string& path) const { return client().Delete(path.c_str(), headers()); }

  /// The token the requests above send (empty: none).
  void setToken(std::string token) { token_ = std::move(token); }
  [[nodiscard]] const std::string& token() const { return token_; }

 private:
  static ServerOptions withFreePort(ServerOptions options) {
    options.port = 0;
    return options;
  }
  [[nodiscard]] httplib::Headers headers() const {
    if (token_.empty()) return {};
    return {{"Authorization", "Bearer " + token_}};
  }

  std::string token_;
  ApiServer server_;
  std::thread thread_;
};

/// Sends `request` as raw bytes to 127.0.0.1:`port` (requests cpp-httplib's own client would not
/// write; send "Connection: close"), then `more` bytes of `filler` while the server reads, and
/// returns what the server answered until it closed or `timeoutSeconds` passed.
inline std::string rawExchange(int port, const std::string& request, std::size_t more = 0, char filler = 'x', int timeoutSeconds = 10) {
  const int socket = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  timeval timeout{timeoutSeconds, 0};
  ::setsockopt(socket, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
  ::setsockopt(socket, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof(timeout));
  std::string answer;
  if (::connect(socket, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) == 0) {
    ::send(socket, request.data(), request.size(), MSG_NOSIGNAL);
    const std::string block(65536, filler);
    for (std::size_t sent = 0; sent < more;) {
      const ssize_t n = ::send(socket, block.data(), std::min(block.size(), more - sent), MSG_NOSIGNAL);
      if (n <= 0) break;
      sent += static_cast<std::size_t>(n);
    }
    char buffer[4096];
    for (ssize_t n; (n = ::recv(socket, buffer, sizeof(buffer), 0)) > 0;) answer.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(socket);
  return answer;
}

/// The status of a raw HTTP answer (0 when there is none).
inline int rawStatus(const std::string& answer) { return answer.rfind("HTTP/1.1 ", 0) == 0 ? std::stoi(answer.substr(9, 3)) : 0; }

/// The JSON body of a raw HTTP answer (null when it is not JSON).
inline nlohmann::json rawBody(const std::string& answer) {
  const std::size_t start = answer.find("\r\n\r\n");
  return start == std::string::npos ? nlohmann::json() : nlohmann::json::parse(answer.substr(start + 4), nullptr, false);
}

/// The JSON body of a response (null when it is not JSON).
inline nlohmann::json bodyOf(const httplib::Result& result) {
  if (!result) return nullptr;
  return nlohmann::json::parse(result->body, nullptr, false);
}

/// The error message of a JSON error response.
inline std::string errorOf(const httplib::Result& result) {
  const nlohmann::json body = bodyOf(result);
  if (!body.is_object() || !body.contains("error")) return "<not an error body: " + (result ? result->body.substr(0, 200) : std::string("no response")) + ">";
  return body["error"].value("message", "");
}

}  // namespace lang2manip::test
