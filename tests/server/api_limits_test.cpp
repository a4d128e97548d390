// The server against misbehaving clients: header floods, clients that trickle their requests,
// more connections than it serves, and clients that leave while their work runs.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <poll.h>

#include <chrono>
#include <memory>
#include <vector>

#include "server/api_test_server.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;
using test::ApiTestServer;
using ::testing::HasSubstr;
using Clock = std::chrono::steady_clock;

/// A raw client connection to 127.0.0.1:port, closed when destroyed.
class RawConnection {
 public:
  explicit RawConnection(int port) : socket_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(socket_, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) == 0;
  }
  ~RawConnection() { close(); }
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;

  [[nodiscard]] bool connected() const { return connected_; }
  /// False once the server stopped taking bytes (it answered and closed).
  bool send(const std::string& bytes) {
    return ::send(socket_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(bytes.size());
  }
  /// True when the server has answered something (or closed) within `milliseconds`.
  [[nodiscard]] bool answered(int milliseconds) const {
    pollfd entry{socket_, POLLIN, 0};
    return ::poll(&entry, 1, milliseconds) > 0;
  }
  /// What the server sends until it closes, or `seconds` pass.
  std::string answer(int seconds = 10) {
    std::string text;
    char buffer[4096];
    const auto until = Clock::now() + std::chrono::seconds(seconds);
    while (Clock::now() < until && answered(100)) {
      const ssize_t n = ::recv(socket_, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      text.append(buffer, static_cast<std::size_t>(n));
    }
    return text;
  }
  void close() {
    if (socket_ >= 0) ::close(socket_);
    socket_ = -1;
  }

 private:
  int socket_;
  bool connected_ = false;
};

const std::string kHealthHead = "GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n";

TEST(ApiLimits, AHeaderFloodIsAnswered431OnceItPassesTheLimit) {
  ServerOptions options;
  options.maxHeadBytes = 16 << 10;
  ApiTestServer server(options);
  RawConnection flood(server.port());
  ASSERT_TRUE(flood.connected());
  ASSERT_TRUE(flood.send(kHealthHead));
  std::string lines;
  for (int i = 0; i < 100; ++i) lines += "X-Flood-" + std::to_string(i) + ": yes\r\n";
  std::size_t sent = 0;
  // Up to 200 MB of header lines, until the server answers.
  while (sent < (std::size_t{200} << 20) && !flood.answered(0) && flood.send(lines)) sent += lines.size();
  const std::string answer = flood.answer();
  EXPECT_EQ(test::rawStatus(answer), 431) << answer.substr(0, 300);
  EXPECT_THAT(test::rawBody(answer)["error"].value("message", ""), HasSubstr("longer than 16384 bytes"));
  // Loopback buffers hold some megabytes the client may push before it sees the answer.
  EXPECT_LT(sent, std::size_t{64} << 20) << "the server read far past its limit before answering";
  EXPECT_EQ(server.get("/api/health")->status, 200);
}

TEST(ApiLimits, ARequestWhoseHeadTricklesIsCutAtItsDeadline) {
  ServerOptions options;
  options.headSeconds = 0.5;
  options.requestReadSeconds = 1.0;
  ApiTestServer server(options);
  RawConnection slow(server.port());
  ASSERT_TRUE(slow.send(kHealthHead));
  const auto started = Clock::now();
  // One header line every 100 ms: each read is quick, the head never ends.
  while (!slow.answered(100) && Clock::now() - started < std::chrono::seconds(10)) slow.send("X-Slow: 1\r\n");
  const std::string answer = slow.answer();
  EXPECT_EQ(test::rawStatus(answer), 408) << answer.substr(0, 300);
  EXPECT_THAT(test::rawBody(answer)["error"].value("message", ""), HasSubstr("did not arrive within 0.5 s"));
  EXPECT_LT(Clock::now() - started, std::chrono::seconds(5));

  // A body that trickles is cut at the request's deadline.
  RawConnection body(server.port());
  ASSERT_TRUE(body.send("POST /api/sessions/t/openProblem HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
                        "Content-Length: 1000\r\n\r\n{"));
  const auto bodyStarted = Clock::now();
  while (!body.answered(100) && Clock::now() - bodyStarted < std::chrono::seconds(10)) body.send(" ");
  EXPECT_EQ(test::rawStatus(body.answer()), 408);
  EXPECT_LT(Clock::now() - bodyStarted, std::chrono::seconds(5));
}

TEST(ApiLimits, ClientsThatTrickleTheirRequestsDoNotHoldOthersUp) {
  ApiTestServer server;
  // More trickling clients than the threads httplib's pool had (32): each holds only its own.
  std::vector<std::unique_ptr<RawConnection>> trickling;
  for (int i = 0; i < 40; ++i) {
    trickling.push_back(std::make_unique<RawConnection>(server.port()));
    ASSERT_TRUE(trickling.back()->send("GET /api/health HTTP/1.1\r\n"));
  }
  httplib::Client client = server.client();
  client.set_read_timeout(3, 0);
  const auto started = Clock::now();
  const auto health = client.Get("/api/health");
  ASSERT_TRUE(health) << "no answer while 40 clients trickle";
  EXPECT_EQ(health->status, 200);
  EXPECT_LT(Clock::now() - started, std::chrono::seconds(2));
}

TEST(ApiLimits, ConnectionsBeyondTheLimitAreAnswered503) {
  ServerOptions options;
  options.maxConnections = 4;
  ApiTestServer server(options);
  std::vector<std::unique_ptr<RawConnection>> held;
  for (int i = 0; i < 4; ++i) {
    held.push_back(std::make_unique<RawConnection>(server.port()));
    held.back()->send("GET /api/health HTTP/1.1\r\n");
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  RawConnection extra(server.port());
  extra.send(kHealthHead + "Connection: close\r\n\r\n");
  const std::string answer = extra.answer();
  EXPECT_EQ(test::rawStatus(answer), 503) << answer.substr(0, 300);
  EXPECT_THAT(test::rawBody(answer)["error"].value("message", ""), HasSubstr("4 connections at once"));
  held.clear();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(server.get("/api/health")->status, 200) << "served again once connections closed";
}

TEST(ApiLimits, ASolveStopsWhenItsClientLeaves) {
  ApiTestServer server;
  const std::string base = "/api/sessions/leaver";
  ASSERT_EQ(server.postJson(base + "/openProblem", {{"problem", "panda_desk"}})->status, 200);
  // RRT* optimizing plans until its time limit: 20 s unless something stops it.
  ASSERT_EQ(server.postJson(base + "/setPlanner", {{"name", "RRTstar"}})->status, 200);
  ASSERT_EQ(server.postJson(base + "/setPlannerParameter", {{"name", "_Optimize (0/1)"}, {"value", "1"}})->status, 200);
  const auto whole = Clock::now();
  ASSERT_EQ(server.postJson(base + "/solve", {{"time_limit", 1}})->status, 200);
  ASSERT_GT(Clock::now() - whole, std::chrono::milliseconds(700)) << "a client that stays waits for the whole solve";
  const std::string body = R"({"time_limit": 20})";
  RawConnection leaver(server.port());
  ASSERT_TRUE(leaver.send("POST " + base + "/solve HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: " +
                          std::to_string(body.size()) + "\r\n\r\n" + body));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const auto left = Clock::now();
  leaver.close();
  // The session answers once the solve has stopped.
  const auto state = server.get(base);
  ASSERT_TRUE(state);
  EXPECT_EQ(state->status, 200);
  EXPECT_LT(Clock::now() - left, std::chrono::seconds(8)) << "the solve went on after its client left";
}

TEST(ApiLimits, ASolveLongerThanTheServersLongestRequestIsRefused) {
  ServerOptions options;
  options.maxRequestSeconds = 30;
  ApiTestServer server(options);
  const std::string base = "/api/sessions/long";
  ASSERT_EQ(server.postJson(base + "/openProblem", {{"problem", "panda_desk"}})->status, 200);
  const auto refused = server.postJson(base + "/solve", {{"time_limit", 31}});
  EXPECT_EQ(refused->status, 400);
  EXPECT_THAT(test::errorOf(refused), HasSubstr("expected 0 to 30 seconds"));
}

}  // namespace
}  // namespace lang2manip
