#pragma once
/// @file `lang2manip serve`: the HTTP/JSON API. Kautham's planning-session verbs per client
/// (/api/sessions/{client}/...), observe, plan and runs (with progress as server-sent events and
/// cancellation), the OpenAPI document at /api/openapi.json, and the web viewer's files. Bound to
/// loopback unless told otherwise; request heads, bodies, JSON depth, connections and the time a
/// request may take limited; work stops when its client leaves; an optional bearer token.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "lang2manip/server/api_types.hpp"

namespace lang2manip {

struct ServerOptions {
  std::string host = "127.0.0.1";
  /// 0: any free port (see ApiServer::port()).
  int port = 8080;
  /// When not empty, every request must carry "Authorization: Bearer <token>".
  std::string token;
  /// Problem, robot and obstacle files named by requests must lie under this directory
  /// (built-in problem and robot names are always allowed). Empty: the current directory.
  std::filesystem::path dataRoot;
  /// The viewer's files (index.html, viewer.js), served at / ; empty: no viewer.
  std::filesystem::path viewerDirectory;
  /// A request body may have this many bytes and JSON nesting levels at most.
  std::size_t maxBodyBytes = std::size_t{1} << 20;
  std::size_t maxJsonDepth = 32;
  /// Planning sessions held at once (one per client id) and the idle time after which one may be
  /// evicted for a new client.
  std::size_t maxSessions = 256;
  int sessionIdleSeconds = 600;
  /// Runs waiting or running at once (they run one after another), and finished runs kept.
  std::size_t maxQueuedRuns = 8;
  std::size_t maxKeptRuns = 64;
  /// Connections served at once, each by its own thread (a slow client holds only its own); more
  /// are answered 503.
  std::size_t maxConnections = 256;
  /// A request's line and headers may have this many bytes (more: 431); they must arrive within
  /// headSeconds of the request's first byte, and the whole request within requestReadSeconds
  /// (else 408). The connection is closed after either answer.
  std::size_t maxHeadBytes = std::size_t{64} << 10;
  double headSeconds = 10.0;
  double requestReadSeconds = 60.0;
  /// The longest a request's work may take (a session's solve, a plan); it stops earlier when its
  /// client closes the connection or the server stops. Runs (POST /api/runs) are not requests'
  /// work: they go on in the background until finished or cancelled.
  double maxRequestSeconds = 300.0;
  /// Run event streams (GET /api/runs/{run}/events) open at once; each holds a connection for
  /// the whole run, so at most half the connections go to streams (see eventStreamLimit()). More
  /// are answered 503 with Retry-After.
  std::size_t maxEventStreams = 16;
  /// The problem opened by sessions and runs that name none (the operator's `serve PROBLEM`):
  /// a built-in name or a file, loaded when the server starts and allowed outside dataRoot;
  /// empty: the paper's scene.
  std::string defaultProblem;
};

/// Throws InputError for options out of range (port, limits, a token with spaces, a data root or
/// viewer directory that is not a directory).
void checkServerOptions(const ServerOptions& options);

/// The event streams served at once: maxEventStreams, and at most half of maxConnections, so
/// that other requests always find a connection.
std::size_t eventStreamLimit(const ServerOptions& options);

/// One endpoint as the OpenAPI document describes it.
struct ApiEndpoint {
  std::string method;
  /// As OpenAPI writes it: "/api/sessions/{client}/solve".
  std::string path;
  /// The request body's fields it accepts (none: it takes no body).
  std::vector<std::string> bodyFields;
};

class ApiServer {
 public:
  /// Checks the options and the default problem, and binds the socket (throws InputError for bad
  /// options, a default problem that cannot be loaded, a host or port that cannot be bound).
  explicit ApiServer(ServerOptions options);
  ~ApiServer();
  ApiServer(const ApiServer&) = delete;
  ApiServer& operator=(const ApiServer&) = delete;

  /// The bound port.
  [[nodiscard]] int port() const noexcept;
  /// Serves until stop() (blocking; call from one thread).
  void serve();
  /// Ends serve(): cancels runs, closes connections. Thread-safe; idempotent.
  void stop();
  /// Every endpoint it answers; the OpenAPI document's test compares them with the document.
  [[nodiscard]] std::vector<ApiEndpoint> endpoints() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The OpenAPI 3 document served at /api/openapi.json.
const std::string& openApiDocument();

}  // namespace lang2manip
