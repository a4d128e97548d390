#pragma once
/// @file Internal to the server module: httplib's server with what cpp-httplib 0.11 lacks for a
/// server facing misbehaving clients. Each connection has its own thread (a slow client holds
/// only its own), up to a number of connections; a request's head (request line and headers) is
/// limited in bytes and must arrive within a deadline from its first byte, and the whole request
/// (body included) within another; the connection being served is known to the handler's
/// thread, so that work can stop when its client leaves (ClientWatch).
// After Eigen: glibc's <resolv.h>, which httplib includes, defines _res.
#include <httplib.h>

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <mutex>

namespace lang2manip {

/// What a connection may take before it is cut.
struct ConnectionLimits {
  /// Connections served at once; more are answered 503 and closed.
  std::size_t maxConnections = 256;
  /// Bytes of a request's line and headers; more are answered 431 and the connection closed.
  std::size_t maxHeadBytes = std::size_t{64} << 10;
  /// Seconds from a request's first byte until its head is complete, and until all of it (body
  /// included) is read; past either it is answered 408 and the connection closed.
  double headSeconds = 10.0;
  double requestSeconds = 60.0;
};

/// A thread per connection; shutdown() waits for every one to end.
class ConnectionThreads final : public httplib::TaskQueue {
 public:
  void enqueue(std::function<void()> work) override;
  void shutdown() override;

 private:
  std::mutex mutex_;
  std::condition_variable finished_;
  std::size_t running_ = 0;
};

class GuardedHttpServer final : public httplib::Server {
 public:
  explicit GuardedHttpServer(const ConnectionLimits& limits);

  /// The socket of the connection the calling thread serves; -1 outside a request.
  [[nodiscard]] static int currentClientSocket() noexcept;
  /// Connections open now.
  [[nodiscard]] std::size_t openConnections() const noexcept { return open_.load(); }

 private:
  bool process_and_close_socket(socket_t sock) override;
  /// Serves the connection's requests; `refused` tells whether one was cut (431, 408).
  [[nodiscard]] bool serveRequests(socket_t sock, bool& refused);

  ConnectionLimits limits_;
  std::atomic<std::size_t> open_{0};
};

}  // namespace lang2manip
