// LLM requests through an HTTP proxy as the environment names it (curl's variables), against a
// proxy on loopback that tunnels CONNECT and forwards absolute-form requests.
#include <arpa/inet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <mutex>
#include <thread>

#include "fake_llm_server.hpp"
#include "lang2manip/llm/http_proxy.hpp"
#include "lang2manip/llm/llm_client_factory.hpp"
#include "llm_test_support.hpp"
#include "test_certificate.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;

int listenOnLoopback(int& port) {
  const int socket = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof address;
  if (::bind(socket, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 || ::listen(socket, 16) != 0 ||
      ::getsockname(socket, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    ADD_FAILURE() << "cannot listen on loopback";
  }
  port = ntohs(address.sin_port);
  return socket;
}

int connectToLoopback(int port) {
  const int socket = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::connect(socket, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    ::close(socket);
    return -1;
  }
  return socket;
}

bool sendAll(int socket, const std::string& bytes) {
  for (std::size_t sent = 0; sent < bytes.size();) {
    const ssize_t n = ::send(socket, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return false;
    sent += static_cast<std::size_t>(n);
  }
  return true;
}

/// Copies bytes both ways until either side closes.
void pump(int a, int b) {
  char buffer[16384];
  pollfd fds[2] = {{a, POLLIN, 0}, {b, POLLIN, 0}};
  while (::poll(fds, 2, 5000) > 0) {
    for (int i = 0; i < 2; ++i) {
      if ((fds[i].revents & (POLLIN | POLLHUP | POLLERR)) == 0) continue;
      const ssize_t n = ::recv(fds[i].fd, buffer, sizeof buffer, 0);
      if (n <= 0 || !sendAll(fds[1 - i].fd, std::string(buffer, static_cast<std::size_t>(n)))) return;
    }
  }
}

/// An HTTP proxy on loopback: CONNECT host:port is tunnelled to 127.0.0.1:port; an absolute-form
/// request "METHOD http://host:port/path" is sent to 127.0.0.1:port in origin form. Every
/// request line and Proxy-Authorization header it saw is kept.
class LoopbackProxy {
 public:
  LoopbackProxy() : listener_(listenOnLoopback(port_)), thread_([this] { serve(); }) {}
  ~LoopbackProxy() {
    stopping_ = true;
    ::shutdown(listener_, SHUT_RDWR);
    thread_.join();
    ::close(listener_);
  }
  LoopbackProxy(const LoopbackProxy&) = delete;
  LoopbackProxy& operator=(const LoopbackProxy&) = delete;

  [[nodiscard]] std::string url() const { return "http://127.0.0.1:" + std::to_string(port_); }
  [[nodiscard]] std::vector<std::string> seen() const {
    const std::lock_guard lock(mutex_);
    return seen_;
  }

 private:
  void serve() {
    while (!stopping_) {
      const int client = ::accept(listener_, nullptr, nullptr);
      if (client < 0) return;
      handle(client);  // one connection at a time: the client makes one request per attempt
      ::close(client);
    }
  }

  void handle(int client) {
    std::string head;
    char c = 0;
    while (head.find("\r\n\r\n") == std::string::npos && head.size() < 65536 && ::recv(client, &c, 1, 0) == 1) head += c;
    const std::string line = head.substr(0, head.find("\r\n"));
    {
      const std::lock_guard lock(mutex_);
      seen_.push_back(line);
      const std::size_t auth = head.find("Proxy-Authorization: ");
      if (auth != std::string::npos) seen_.push_back(head.substr(auth, head.find("\r\n", auth) - auth));
    }
    const std::size_t space = line.find(' ');
    const std::string target = line.substr(space + 1, line.rfind(' ') - space - 1);
    const bool tunnel = line.rfind("CONNECT ", 0) == 0;
    const std::string authority = tunnel ? target : target.substr(7, target.find('/', 7) - 7);
    const int server = connectToLoopback(std::stoi(authority.substr(authority.rfind(':') + 1)));
    if (server < 0) return (void)sendAll(client, "HTTP/1.1 502 Bad Gateway\r\nContent-Length: 0\r\n\r\n");
    if (tunnel) {
      sendAll(client, "HTTP/1.1 200 Connection established\r\n\r\n");
    } else {
      const std::string originForm = line.substr(0, space + 1) + target.substr(target.find('/', 7)) + line.substr(line.rfind(' '));
      sendAll(server, originForm + head.substr(line.size()));
    }
    pump(client, server);
    ::close(server);
  }

  int port_ = 0;
  int listener_;
  std::atomic<bool> stopping_{false};
  mutable std::mutex mutex_;
  std::vector<std::string> seen_;
  std::thread thread_;
};

EnvironmentLookup environmentOf(std::map<std::string, std::string> variables) {
  return [variables = std::move(variables)](const std::string& name) {
    const auto found = variables.find(name);
    return found == variables.end() ? std::optional<std::string>() : std::optional<std::string>(found->second);
  };
}

LlmReply call(const FakeLlmServer& server, const LlmClientOptions& options) {
  return makeLlmClient(server.spec(), options)->complete(planRequest(), StopCondition::never());
}

TEST(HttpProxy, PlainHttpGoesThroughTheProxyInAbsoluteFormWithItsCredentials) {
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  server.enqueueAnswer(kPlanAnswer);
  const LoopbackProxy proxy;
  LlmClientOptions options = fastOptions(server);
  options.environment = environmentOf({{"http_proxy", "http://user:p%40ss@127.0.0.1:" + proxy.url().substr(17)}});
  EXPECT_EQ(call(server, options).finish, FinishReason::kStop);
  const std::vector<std::string> seen = proxy.seen();
  ASSERT_EQ(seen.size(), 2U);
  EXPECT_EQ(seen[0], "POST http://127.0.0.1:" + std::to_string(server.port()) + "/v1/chat/completions HTTP/1.1");
  EXPECT_EQ(seen[1], "Proxy-Authorization: Basic dXNlcjpwQHNz");  // user:p@ss
}

TEST(HttpProxy, HttpsTunnelsThroughConnectAndTheServerCertificateIsStillVerified) {
  const TempDirectory directory;
  const FakeTlsFiles tls = writeSelfSignedCertificate(directory.path(), "server", "IP:127.0.0.1");
  FakeLlmServer server(FakeLlmProtocol::kAnthropic, tls);
  server.enqueueAnswer(kPlanAnswer);
  const LoopbackProxy proxy;
  LlmClientOptions options = fastOptions(server);
  options.retry.maxAttempts = 1;
  options.environment = environmentOf({{"HTTPS_PROXY", proxy.url()}, {"http_proxy", "http://127.0.0.1:1"}});
  const LlmError untrusted = expectLlmError([&] { call(server, options); });
  EXPECT_THAT(untrusted.what(), HasSubstr("failed verification"));
  options.http.caCertFile = tls.certificateFile;
  EXPECT_EQ(call(server, options).finish, FinishReason::kStop);
  const std::vector<std::string> seen = proxy.seen();
  ASSERT_EQ(seen.size(), 2U);
  EXPECT_EQ(seen[1], "CONNECT 127.0.0.1:" + std::to_string(server.port()) + " HTTP/1.1");
}

TEST(HttpProxy, NoProxyHostsAreReachedDirectlyAndARefusingProxyIsNamed) {
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  server.enqueueAnswer(kPlanAnswer);
  const LoopbackProxy proxy;
  LlmClientOptions options = fastOptions(server);
  options.environment = environmentOf({{"all_proxy", proxy.url()}, {"NO_PROXY", "example.com, 127.0.0.1"}});
  EXPECT_EQ(call(server, options).finish, FinishReason::kStop);
  EXPECT_TRUE(proxy.seen().empty());
  int closedPort = 0;
  ::close(listenOnLoopback(closedPort));
  options.retry.maxAttempts = 1;
  options.environment = environmentOf({{"http_proxy", "127.0.0.1:" + std::to_string(closedPort)}});
  const LlmError refused = expectLlmError([&] { call(server, options); });
  EXPECT_EQ(refused.kind(), LlmErrorKind::kTransport);
  EXPECT_THAT(refused.what(), HasSubstr("through proxy http://127.0.0.1:" + std::to_string(closedPort) + " (from http_proxy)"));
}

TEST(HttpProxy, VariablesAreReadAsCurlReadsThemAndBadOnesAreConfigurationErrors) {
  const HttpEndpoint https = parseBaseUrl("https://api.example.com/v1", "url");
  const HttpEndpoint http = parseBaseUrl("http://llm.lab.example.org:8080", "url");
  EXPECT_FALSE(proxyFor(http, {{"HTTP_PROXY", "http://proxy:3128"}}).has_value()) << "HTTP_PROXY is a CGI header";
  const auto chosen = proxyFor(https, {{"https_proxy", "http://proxy.lab:3128/"}, {"http_proxy", "http://other:1"}});
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(chosen->origin(), "http://proxy.lab:3128");
  EXPECT_EQ(chosen->source, "https_proxy");
  EXPECT_EQ(proxyFor(http, {{"all_proxy", "proxy"}})->port, 1080);
  EXPECT_TRUE(noProxyMatches("*", "anything", 1));
  EXPECT_TRUE(noProxyMatches(".example.org", "llm.lab.example.org", 8080));
  EXPECT_TRUE(noProxyMatches("example.org:8080", "LLM.example.org", 8080));
  EXPECT_FALSE(noProxyMatches("example.org:443", "llm.example.org", 8080));
  EXPECT_FALSE(noProxyMatches("ample.org", "example.org", 80));
  EXPECT_TRUE(noProxyMatches("[::1]", "[::1]", 80));
  EXPECT_TRUE(noProxyMatches("::1", "::1", 80));
  for (const auto& [url, why] : std::vector<std::pair<std::string, std::string>>{
           {"socks5://proxy:1080", "a socks5:// proxy is not supported"},
           {"https://proxy:443", "a https:// proxy is not supported"},
           {"http://:3128", "no host"},
           {"http://pro xy:3128", "the host has a character no host name or address has"},
           {"http://proxy:99999", "port \"99999\" is not a number from 1 to 65535"},
           {"http://proxy:3128/path", "a proxy URL has no path"}}) {
    SCOPED_TRACE(url);
    const LlmError error = expectLlmError([&] { (void)parseProxyUrl(url, "HTTPS_PROXY"); });
    EXPECT_EQ(error.kind(), LlmErrorKind::kConfiguration);
    EXPECT_THAT(error.what(), HasSubstr("HTTPS_PROXY=\"" + url + "\": " + why));
  }
  // Bytes no host has are refused, and shown escaped.
  const LlmError control = expectLlmError([] { (void)parseProxyUrl(std::string("[\0\0]:80", 7), "HTTPS_PROXY"); });
  EXPECT_THAT(control.what(), HasSubstr("HTTPS_PROXY=\"[\\x00\\x00]:80\": the host has a character no host name or address has"));
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  LlmClientOptions options = fastOptions(server);
  options.environment = environmentOf({{"http_proxy", "socks5://proxy:1080"}});
  const LlmError atCreation = expectLlmError([&] { (void)makeLlmClient(server.spec(), options); });
  EXPECT_THAT(atCreation.what(), HasSubstr("http_proxy=\"socks5://proxy:1080\": a socks5:// proxy is not supported"));
}

}  // namespace
}  // namespace lang2manip::test
