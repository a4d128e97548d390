#include "lang2manip/core/types.hpp"  // Eigen before httplib (see the header)
#include "lang2manip/server/guarded_http_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <string>
#include <system_error>
#include <thread>

#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/server/api_types.hpp"

namespace lang2manip {
namespace {

using Clock = std::chrono::steady_clock;

thread_local int tCurrentSocket = -1;

/// Waits up to `milliseconds` for `events` on `sock`; true when they (or a hang-up) came.
bool waitFor(int sock, short events, int milliseconds) {
  pollfd entry{sock, events, 0};
  for (;;) {
    const int ready = ::poll(&entry, 1, std::max(milliseconds, 0));
    if (ready < 0 && errno == EINTR) continue;
    return ready > 0;
  }
}

int millisecondsOf(double seconds) {
  return static_cast<int>(std::clamp(std::ceil(seconds * 1e3), 0.0, 3.6e6));
}

std::string addressText(const sockaddr_storage& address, int& port) {
  char text[INET6_ADDRSTRLEN] = {};
  if (address.ss_family == AF_INET) {
    const auto& in = reinterpret_cast<const sockaddr_in&>(address);
    ::inet_ntop(AF_INET, &in.sin_addr, text, sizeof text);
    port = ntohs(in.sin_port);
  } else if (address.ss_family == AF_INET6) {
    const auto& in6 = reinterpret_cast<const sockaddr_in6&>(address);
    ::inet_ntop(AF_INET6, &in6.sin6_addr, text, sizeof text);
    port = ntohs(in6.sin6_port);
  }
  return text;
}

/// Writes a whole short answer, as far as the client takes it within a second.
void sendAll(int sock, const std::string& text) {
  std::size_t sent = 0;
  while (sent < text.size() && waitFor(sock, POLLOUT, 1000)) {
    const ssize_t n = ::send(sock, text.data() + sent, text.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return;
    sent += static_cast<std::size_t>(n);
  }
}

/// An error answer written by the connection itself (the request never reaches httplib).
std::string closingAnswer(int status, const std::string& reason, const std::string& code, const std::string& message) {
  const std::string body = apiErrorBody(status, code, message).dump() + "\n";
  return "HTTP/1.1 " + std::to_string(status) + " " + reason +
         "\r\nContent-Type: application/json\r\nConnection: close\r\nX-Content-Type-Options: nosniff\r\nContent-Length: " +
         std::to_string(body.size()) + "\r\n\r\n" + body;
}

/// A connection's byte stream as httplib reads and writes it, cutting a request whose head is
/// too long or that arrives too slowly (answering 431 or 408 itself; later reads and writes fail).
class GuardedSocketStream final : public httplib::Stream {
 public:
  GuardedSocketStream(int sock, const ConnectionLimits& limits, double readTimeout, double writeTimeout)
      : sock_(sock), limits_(limits), readTimeout_(readTimeout), writeTimeout_(writeTimeout) {}

  using httplib::Stream::write;

  /// Waits up to `seconds` for the next request's first byte; false on silence, hang-up or `stop`.
  template <typename Stop>
  bool waitForRequest(double seconds, Stop stop) {
    if (position_ < filled_) return true;
    const auto until = Clock::now() + std::chrono::duration<double>(seconds);
    while (!stop()) {
      const double left = std::chrono::duration<double>(until - Clock::now()).count();
      if (left <= 0.0) return false;
      if (waitFor(sock_, POLLIN, std::min(millisecondsOf(left), 100))) return true;
    }
    return false;
  }

  /// The next request starts: its head is counted and its deadlines run from now.
  void beginRequest() {
    requestStart_ = Clock::now();
    headBytes_ = 0;
    lineChars_ = 0;
    headComplete_ = false;
  }

  [[nodiscard]] bool refused() const noexcept { return refused_; }

  bool is_readable() const override {
    return position_ < filled_ || waitFor(sock_, POLLIN, millisecondsOf(readWaitSeconds()));
  }

  bool is_writable() const override {
    return !refused_ && waitFor(sock_, POLLOUT, millisecondsOf(writeTimeout_));
  }

  ssize_t read(char* ptr, size_t size) override {
    if (refused_) return -1;
    if (position_ == filled_ && !fill()) return eof_ && !refused_ ? 0 : -1;
    const std::size_t n = std::min(size, filled_ - position_);
    if (!headComplete_ && !countHead(buffer_ + position_, n)) return -1;
    std::memcpy(ptr, buffer_ + position_, n);
    position_ += n;
    return static_cast<ssize_t>(n);
  }

  ssize_t write(const char* ptr, size_t size) override {
    if (refused_ || !is_writable()) return -1;
    return ::send(sock_, ptr, size, MSG_NOSIGNAL);
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    sockaddr_storage address{};
    socklen_t length = sizeof address;
    if (::getpeername(sock_, reinterpret_cast<sockaddr*>(&address), &length) == 0) ip = addressText(address, port);
  }

  void get_local_ip_and_port(std::string& ip, int& port) const override {
    sockaddr_storage address{};
    socklen_t length = sizeof address;
    if (::getsockname(sock_, reinterpret_cast<sockaddr*>(&address), &length) == 0) ip = addressText(address, port);
  }

  socket_t socket() const override { return sock_; }

 private:
  /// Seconds a read may wait: the read timeout, and no longer than the request's deadline.
  [[nodiscard]] double readWaitSeconds() const {
    const double elapsed = std::chrono::duration<double>(Clock::now() - requestStart_).count();
    const double deadline = headComplete_ ? limits_.requestSeconds : limits_.headSeconds;
    return std::min(readTimeout_, std::max(0.0, deadline - elapsed));
  }

  /// Refills the empty buffer; false (after answering 408 when a deadline passed) when nothing came.
  bool fill() {
    position_ = 0;
    filled_ = 0;
    if (!waitFor(sock_, POLLIN, millisecondsOf(readWaitSeconds()))) {
      if (readWaitSeconds() <= 0.0) {
        refuse(closingAnswer(408, "Request Timeout", "request_timeout",
                             headComplete_ ? "the request did not arrive within " + numberText(limits_.requestSeconds) + " s"
                                           : "the request's headers did not arrive within " + numberText(limits_.headSeconds) + " s"));
      }
      return false;
    }
    const ssize_t got = ::recv(sock_, buffer_, sizeof buffer_, 0);
    if (got <= 0) {
      eof_ = got == 0;
      return false;
    }
    filled_ = static_cast<std::size_t>(got);
    return true;
  }

  /// Counts `n` head bytes about to be delivered; false (after answering 431) beyond the limit.
  bool countHead(const char* bytes, std::size_t n) {
    for (std::size_t i = 0; i < n && !headComplete_; ++i) {
      if (++headBytes_ > limits_.maxHeadBytes) {
        refuse(closingAnswer(431, "Request Header Fields Too Large", "request_header_fields_too_large",
                             "the request line and headers are longer than " + std::to_string(limits_.maxHeadBytes) +
                                 " bytes"));
        return false;
      }
      if (bytes[i] == '\n') {
        headComplete_ = lineChars_ == 0 && headBytes_ > 2;
        lineChars_ = 0;
      } else if (bytes[i] != '\r') {
        ++lineChars_;
      }
    }
    return true;
  }

  void refuse(const std::string& answer) {
    refused_ = true;
    sendAll(sock_, answer);
  }

  int sock_;
  const ConnectionLimits& limits_;
  double readTimeout_;
  double writeTimeout_;
  char buffer_[4096] = {};
  std::size_t position_ = 0;
  std::size_t filled_ = 0;
  bool eof_ = false;
  bool refused_ = false;
  Clock::time_point requestStart_ = Clock::now();
  std::size_t headBytes_ = 0;
  std::size_t lineChars_ = 0;
  bool headComplete_ = false;
};

/// Closes a connection whose client may still be sending (a refused request): what it sends for
/// up to a second is read and dropped first, so that closing does not reset the connection and
/// destroy the answer before the client reads it (Apache's lingering close).
void lingerAndClose(int sock) {
  ::shutdown(sock, SHUT_WR);
  char sink[4096];
  const auto until = Clock::now() + std::chrono::seconds(1);
  for (std::size_t dropped = 0; dropped < (std::size_t{1} << 24) && Clock::now() < until;) {
    if (!waitFor(sock, POLLIN, 100)) continue;
    const ssize_t n = ::recv(sock, sink, sizeof sink, 0);
    if (n <= 0) break;
    dropped += static_cast<std::size_t>(n);
  }
  ::close(sock);
}

double secondsOf(time_t seconds, time_t microseconds) {
  return static_cast<double>(seconds) + static_cast<double>(microseconds) * 1e-6;
}

}  // namespace

void ConnectionThreads::enqueue(std::function<void()> work) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    ++running_;
  }
  const auto done = [this] {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (--running_ == 0) finished_.notify_all();
  };
  try {
    std::thread([work, done] {
      work();
      done();
    }).detach();
  } catch (const std::system_error&) {
    // No thread to be had: served here, so that the connection is answered and closed.
    work();
    done();
  }
}

void ConnectionThreads::shutdown() {
  std::unique_lock<std::mutex> lock(mutex_);
  finished_.wait(lock, [this] { return running_ == 0; });
}

GuardedHttpServer::GuardedHttpServer(const ConnectionLimits& limits) : limits_(limits) {
  new_task_queue = [] { return new ConnectionThreads; };
}

int GuardedHttpServer::currentClientSocket() noexcept { return tCurrentSocket; }

bool GuardedHttpServer::process_and_close_socket(socket_t sock) {
  bool served = false;
  bool refused = false;
  if (++open_ > limits_.maxConnections) {
    sendAll(sock, closingAnswer(503, "Service Unavailable", "service_unavailable",
                                "the server serves " + std::to_string(limits_.maxConnections) +
                                    " connections at once; retry later"));
    refused = true;
  } else {
    tCurrentSocket = sock;
    served = serveRequests(sock, refused);
    tCurrentSocket = -1;
  }
  --open_;
  if (refused) {
    lingerAndClose(sock);
  } else {
    ::shutdown(sock, SHUT_RDWR);
    ::close(sock);
  }
  return served;
}

bool GuardedHttpServer::serveRequests(socket_t sock, bool& refused) {
  GuardedSocketStream stream(sock, limits_, secondsOf(read_timeout_sec_, read_timeout_usec_),
                            secondsOf(write_timeout_sec_, write_timeout_usec_));
  const auto stopping = [this] { return svr_sock_ == INVALID_SOCKET; };
  bool served = false;
  for (std::size_t left = keep_alive_max_count_; left > 0 && !stopping(); --left) {
    if (!stream.waitForRequest(static_cast<double>(keep_alive_timeout_sec_), stopping)) break;
    stream.beginRequest();
    bool closed = false;
    served = process_request(stream, left == 1, closed, nullptr);
    if (!served || closed || stream.refused()) break;
  }
  refused = stream.refused();
  return served;
}

}  // namespace lang2manip
