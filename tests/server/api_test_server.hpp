#pragma once
/// @file A real ApiServer on a free loopback port for one test, and requests to it through a real
/// HTTP client (cpp-httplib).

// Eigen (through api_server.hpp) before httplib.h: glibc's <resolv.h>, which httplib includes,
// defines the macro _res that Eigen uses as a parameter name.
#include "lang2manip/server/api_server.hpp"

#include <httplib.h>

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
