#include "lang2manip/server/api_server.hpp"

// After Eigen (api_server.hpp): glibc's <resolv.h>, which httplib includes, defines _res.
#include "lang2manip/server/guarded_http_server.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdint>
#include <regex>

#include <sys/socket.h>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/json_limits.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/server/client_watch.hpp"
#include "lang2manip/server/run_registry.hpp"
#include "lang2manip/server/server_routes.hpp"
#include "lang2manip/server/session_registry.hpp"
#include "lang2manip/server/static_files.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

constexpr int kListenBacklog = 1024;

ConnectionLimits connectionLimits(const ServerOptions& options) {
  ConnectionLimits limits;
  limits.maxConnections = options.maxConnections;
  limits.maxHeadBytes = options.maxHeadBytes;
  limits.headSeconds = options.headSeconds;
  limits.requestSeconds = options.requestReadSeconds;
  return limits;
}

/// "/api/sessions/{client}/solve" -> "/api/sessions/([^/]+)/solve" (dots escaped).
std::string routePattern(const std::string& path) {
  std::string pattern;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i] == '{') {
      i = path.find('}', i);
      pattern += "([^/]+)";
    } else {
      if (std::string_view(".+*?()[]^$|\\").find(path[i]) != std::string_view::npos) pattern += '\\';
      pattern += path[i];
    }
  }
  return pattern;
}

void setError(httplib::Response& response, int status, const std::string& code, const std::string& message) {
  response.status = status;
  response.set_content(apiErrorBody(status, code, message).dump(-1, ' ', false, json::error_handler_t::replace), "application/json");
}

const char* statusCode(int status) {
  switch (status) {
    case 400: return "bad_request";
    case 401: return "unauthorized";
    case 403: return "forbidden";
    case 404: return "not_found";
    case 405: return "method_not_allowed";
    case 411: return "length_required";
    case 413: return "payload_too_large";
    case 415: return "unsupported_media_type";
    case 503: return "service_unavailable";
    default: return status >= 500 ? "internal_error" : "error";
  }
}

/// Constant-time comparison, so that the token cannot be guessed byte by byte from timings.
bool sameSecret(const std::string& given, const std::string& expected) {
  unsigned char difference = given.size() == expected.size() ? 0 : 1;
  for (std::size_t i = 0; i < expected.size(); ++i) difference |= static_cast<unsigned char>(expected[i] ^ (i < given.size() ? given[i] : 0));
  return difference == 0;
}

/// The host of a Host header or URL authority ("127.0.0.1:8080" -> "127.0.0.1", "[::1]:80" -> "::1").
std::string hostPart(const std::string& authority) {
  if (!authority.empty() && authority.front() == '[') {
    const std::size_t close = authority.find(']');
    return close == std::string::npos ? authority : authority.substr(1, close - 1);
  }
  return authority.substr(0, authority.find(':'));
}

bool isLoopbackHost(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

/// Why a request that a web page of another site made the operator's browser send is refused:
/// a Host naming anything but loopback on a loopback server (DNS rebinding), or an Origin other
/// than the server's own; empty when neither.
std::string crossSiteRefusal(const httplib::Request& request, const std::string& listeningHost) {
  const std::string host = request.get_header_value("Host");
  if (isLoopbackHost(listeningHost) && !host.empty() && !isLoopbackHost(hostPart(host))) {
    return "the Host \"" + host.substr(0, 80) + "\" is not this server's: it answers on loopback only";
  }
  const std::string origin = request.get_header_value("Origin");
  if (!origin.empty() && origin != "http://" + host) {
    return "requests from the page of another origin (\"" + origin.substr(0, 80) + "\") are refused";
  }
  return {};
}

/// The credentials of "Bearer TOKEN" (the scheme in any case, RFC 7235); "" for another scheme.
std::string bearerToken(const std::string& header) {
  const std::size_t space = header.find(' ');
  if (space == std::string::npos) return "";
  std::string scheme = header.substr(0, space);
  std::transform(scheme.begin(), scheme.end(), scheme.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (scheme != "bearer") return "";
  const std::size_t token = header.find_first_not_of(' ', space);
  return token == std::string::npos ? "" : header.substr(token);
}

std::string cookieValue(const httplib::Request& request, const std::string& name) {
  const std::string cookies = request.get_header_value("Cookie");
  const std::string key = name + "=";
  for (std::size_t start = 0; start < cookies.size();) {
    const std::size_t end = std::min(cookies.find(';', start), cookies.size());
    std::string_view item(cookies.data() + start, end - start);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    if (item.substr(0, key.size()) == key) return std::string(item.substr(key.size()));
    start = end + 1;
  }
  return "";
}

bool isChunked(const httplib::Request& request) {
  std::string encoding = request.get_header_value("Transfer-Encoding");
  std::transform(encoding.begin(), encoding.end(), encoding.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return encoding.find("chunked") != std::string::npos;
}

std::string tooLargeMessage(std::size_t maxBytes) { return "request body larger than " + std::to_string(maxBytes) + " bytes"; }

/// What an error httplib answers by itself (before any handler) means.
std::string libraryErrorMessage(int status, std::size_t maxBodyBytes) {
  if (status == 413) return tooLargeMessage(maxBodyBytes);
  if (status == 400) return "malformed HTTP request (a body needs Content-Length or chunked encoding)";
  if (status == 414) return "request URI too long";
  return "HTTP " + std::to_string(status);
}

/// The body of a POST or DELETE, read under the size limit as it arrives: httplib 0.11 reads a
/// chunked body whole before it checks its limit. A request with neither Content-Length nor
/// chunked encoding has no body (HTTP/1.1 section 3.3.3).
std::string readBody(const httplib::Request& request, const httplib::ContentReader& reader, std::size_t maxBytes) {
  const bool chunked = isChunked(request);
  if (!chunked && !request.has_header("Content-Length")) return "";
  std::string body;
  bool tooLarge = !chunked && request.get_header_value<std::uint64_t>("Content-Length") > maxBytes;
  if (tooLarge) throw ApiError(413, "payload_too_large", tooLargeMessage(maxBytes));
  const bool complete = reader([&](const char* data, std::size_t size) {
    tooLarge = body.size() + size > maxBytes;
    if (!tooLarge) body.append(data, size);
    return !tooLarge;
  });
  if (tooLarge) throw ApiError(413, "payload_too_large", tooLargeMessage(maxBytes));
  if (!complete) throw ApiError(400, "bad_request", "the request body ended early or its chunked encoding is broken");
  return body;
}

/// Counts one open event stream for as long as it lives.
class StreamSlot {
 public:
  explicit StreamSlot(std::atomic<std::size_t>& open) : open_(open) {}
  ~StreamSlot() { open_.fetch_sub(1); }
  StreamSlot(const StreamSlot&) = delete;
  StreamSlot& operator=(const StreamSlot&) = delete;

 private:
  std::atomic<std::size_t>& open_;
};

}  // namespace

std::size_t eventStreamLimit(const ServerOptions& options) {
  return std::min(options.maxEventStreams, std::max<std::size_t>(options.maxConnections / 2, 1));
}

struct ApiServer::Impl {
  explicit Impl(ServerOptions serverOptions)
      : options(std::move(serverOptions)),
        sessions(options.maxSessions, std::chrono::seconds(options.sessionIdleSeconds)),
        runs(options.maxQueuedRuns, options.maxKeptRuns),
        http(connectionLimits(options)) {}

  ServerOptions options;
  SessionRegistry sessions;
  RunRegistry runs;
  std::vector<ApiRoute> routes;
  GuardedHttpServer http;
  /// Cancels the work of a request whose client left.
  ClientWatch clientWatch;
  /// Set when the server stops: work in progress stops too.
  CancelFlag stopping = std::make_shared<std::atomic<bool>>(false);
  int port = 0;
  /// The listening socket (seen when httplib creates it), for its backlog.
  int listeningSocket = -1;
  std::atomic<bool> stopped{false};
  /// Event streams open now; each holds a thread for as long as it lasts.
  std::atomic<std::size_t> openStreams{0};

  /// One of the streams allowed at once (see eventStreamLimit()), given back when destroyed;
  /// none when the limit is reached.
  std::shared_ptr<StreamSlot> takeStreamSlot();

  void configure();
  void addRoute(const ApiRoute& route);
  void addEventStream();
  void addFixedRoutes();
  bool authorized(const httplib::Request& request, httplib::Response& response) const;
  [[nodiscard]] ApiRequest apiRequest(const httplib::Request& request, const std::string& body) const;
  void answerUnrouted(const httplib::Request& request, httplib::Response& response) const;
};

bool ApiServer::Impl::authorized(const httplib::Request& request, httplib::Response& response) const {
  if (options.token.empty()) return true;
  const std::string header = request.get_header_value("Authorization");
  const std::string bearer = bearerToken(header);
  const std::string query = request.get_param_value("token");
  if (sameSecret(bearer, options.token) || sameSecret(cookieValue(request, "lang2manip_token"), options.token)) return true;
  if (sameSecret(query, options.token)) {
    // The viewer is opened as /?token=...; the cookie lets the page load its script and data.
    response.set_header("Set-Cookie", "lang2manip_token=" + options.token + "; Path=/; HttpOnly; SameSite=Strict");
    return true;
  }
  response.set_header("WWW-Authenticate", "Bearer realm=\"lang2manip\"");
  setError(response, 401, "unauthorized",
           header.empty() && query.empty() ? "this server requires a token: send \"Authorization: Bearer <token>\""
                                           : "the token is not the server's");
  return false;
}

ApiRequest ApiServer::Impl::apiRequest(const httplib::Request& request, const std::string& body) const {
  ApiRequest api;
  for (std::size_t i = 1; i < request.matches.size(); ++i) api.pathParameters.push_back(request.matches[i].str());
  for (const auto& [name, value] : request.params) api.query.emplace(name, value);
  if (body.empty()) return api;
  // Only JSON with its type: a form or text/plain body is what a page of another site can send
  // without asking the browser first.
  const std::string type = request.get_header_value("Content-Type");
  if (type.rfind("application/json", 0) != 0) {
    throw ApiError(415, "unsupported_media_type",
                   "request bodies are JSON: send the header \"Content-Type: application/json\" (curl: -H 'Content-Type: application/json'), got " +
                       (type.empty() ? std::string("none") : type.substr(0, 80)));
  }
  JsonLimits limits;
  limits.maxBytes = options.maxBodyBytes;
  limits.maxDepth = options.maxJsonDepth;
  try {
    api.body = parseJsonWithinLimits(body, limits, "request body");
  } catch (const InputError& error) {
    throw ApiError(400, "bad_request", error.what());
  }
  if (!api.body.is_object()) throw ApiError(400, "bad_request", "request body: expected a JSON object, got " + boundedJsonDump(api.body));
  return api;
}

void ApiServer::Impl::addRoute(const ApiRoute& route) {
  // Bodies are read by the handler (readBody), under the limit and optional.
  const auto handler = [this, route](const httplib::Request& request, httplib::Response& response, const httplib::ContentReader* reader) {
    try {
      const std::string body = reader != nullptr ? readBody(request, *reader, options.maxBodyBytes) : request.body;
      auto clientLeft = std::make_shared<std::atomic<bool>>(false);
      const ClientWatch::Registration watched = clientWatch.watch(GuardedHttpServer::currentClientSocket(), clientLeft);
      const ApiResponse answer = guarded([&] {
        ApiRequest api = apiRequest(request, body);
        api.stop = StopCondition::onCancel(clientLeft)
                       .orElse(StopCondition::onCancel(stopping))
                       .orElse(StopCondition::afterSeconds(options.maxRequestSeconds));
        body::onlyFields(api.body, route.bodyFields);
        return route.handler(api);
      });
      response.status = answer.status;
      response.set_content(answer.body, answer.contentType);
    } catch (const ApiError& error) {
      // A body left unread would be taken for the next request.
      if (error.status() == 413 || error.status() == 400) response.set_header("Connection", "close");
      setError(response, error.status(), error.code(), withoutDataRoot(error.what(), options));
    }
  };
  const auto withBody = [handler](const httplib::Request& request, httplib::Response& response, const httplib::ContentReader& reader) {
    handler(request, response, &reader);
  };
  const std::string pattern = routePattern(route.path);
  if (route.method == "GET") http.Get(pattern, [handler](const httplib::Request& request, httplib::Response& response) { handler(request, response, nullptr); });
  if (route.method == "POST") http.Post(pattern, withBody);
  if (route.method == "DELETE") http.Delete(pattern, withBody);
}

std::shared_ptr<StreamSlot> ApiServer::Impl::takeStreamSlot() {
  if (openStreams.fetch_add(1) >= eventStreamLimit(options)) {
    openStreams.fetch_sub(1);
    return nullptr;
  }
  return std::make_shared<StreamSlot>(openStreams);
}

void ApiServer::Impl::addEventStream() {
  http.Get(routePattern("/api/runs/{run}/events"), [this](const httplib::Request& request, httplib::Response& response) {
    const std::string id = request.matches[1].str();
    std::size_t from = 0;
    std::shared_ptr<StreamSlot> slot = takeStreamSlot();
    if (!slot) {
      response.set_header("Retry-After", "5");
      const std::string limit = std::to_string(eventStreamLimit(options));
      return setError(response, 503, "service_unavailable",
                      "the limit of " + limit + " event streams open at once is reached; retry later or poll GET /api/runs/" + id.substr(0, 64));
    }
    try {
      (void)runs.status(id);
      const std::string last = request.get_header_value("Last-Event-ID");
      if (!last.empty()) from = std::stoul(last) + 1;
    } catch (const ApiError& error) {
      return setError(response, error.status(), error.code(), error.what());
    } catch (const std::exception&) {
      return setError(response, 400, "bad_request", "header Last-Event-ID: expected an event index");
    }
    auto next = std::make_shared<std::size_t>(from);
    response.set_header("Cache-Control", "no-cache");
    // The provider holds the slot: it is given back when the stream ends.
    response.set_chunked_content_provider("text/event-stream", [this, id, next, slot](std::size_t, httplib::DataSink& sink) {
      RunEventBatch batch;
      try {
        batch = runs.events(id, *next, std::chrono::milliseconds(500));
      } catch (const ApiError&) {
        batch.finished = true;  // forgotten meanwhile
      }
      std::string text = batch.events.empty() ? ": waiting\n\n" : "";
      for (const json& event : batch.events) {
        text += "id: " + std::to_string(*next) + "\nevent: " + event.value("type", "progress") + "\ndata: " +
                event.dump(-1, ' ', false, json::error_handler_t::replace) + "\n\n";
        ++*next;
      }
      // A failed write means the client went away; the run goes on.
      if (!sink.write(text.data(), text.size())) return false;
      if (batch.finished || stopped.load()) sink.done();
      return true;
    });
  });
}

void ApiServer::Impl::addFixedRoutes() {
  routes.push_back({"GET", "/api/health", [](const ApiRequest&) { return ApiResponse::json({{"ok", true}, {"version", "0.1.0"}}); }});
  routes.push_back({"GET", "/api/openapi.json", [](const ApiRequest&) { return ApiResponse{200, "application/json", openApiDocument()}; }});
}

void ApiServer::Impl::answerUnrouted(const httplib::Request& request, httplib::Response& response) const {
  std::vector<std::string> allowed;
  for (const ApiRoute& route : routes) {
    if (std::regex_match(request.path, std::regex(routePattern(route.path)))) allowed.push_back(route.method);
  }
  if (std::regex_match(request.path, std::regex(routePattern("/api/runs/{run}/events")))) allowed.push_back("GET");
  if (!allowed.empty()) {
    std::string list;
    for (const std::string& method : allowed) list += (list.empty() ? "" : ", ") + method;
    response.set_header("Allow", list);
    return setError(response, 405, "method_not_allowed", request.method + " " + request.path + ": allowed " + list);
  }
  setError(response, 404, "not_found", "no endpoint " + request.method + " " + request.path.substr(0, 200) + "; see /api/openapi.json");
}

void ApiServer::Impl::configure() {
  // Not httplib's default options: SO_REUSEPORT would let a second server bind a port in use.
  http.set_socket_options([this](socket_t socket) {
    int yes = 1;
    ::setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    listeningSocket = socket;
  });
  http.set_payload_max_length(options.maxBodyBytes);
  // Short: a client that opens a connection and sends nothing holds a thread meanwhile.
  http.set_read_timeout(5, 0);
  http.set_write_timeout(10, 0);
  http.set_keep_alive_timeout(2);
  http.set_keep_alive_max_count(1000);
  http.set_default_headers({{"X-Content-Type-Options", "nosniff"}});
  http.set_pre_routing_handler([this](const httplib::Request& request, httplib::Response& response) {
    if (const std::string refusal = crossSiteRefusal(request, options.host); !refusal.empty()) {
      setError(response, 403, "forbidden", refusal);
      return httplib::Server::HandlerResponse::Handled;
    }
    // Strict framing: a length given twice or not as digits could be read differently by a proxy
    // in front and by this server (request smuggling).
    if (const std::size_t lengths = request.get_header_value_count("Content-Length"); lengths > 0) {
      const std::string length = request.get_header_value("Content-Length");
      if (lengths > 1 || length.empty() || length.find_first_not_of("0123456789") != std::string::npos) {
        response.set_header("Connection", "close");
        setError(response, 400, "bad_request", "the request's Content-Length must be given once, as digits");
        return httplib::Server::HandlerResponse::Handled;
      }
    }
    // Health says only that the server is up, for probes that hold no token.
    const bool health = request.method == "GET" && request.path == "/api/health";
    if (!health && !authorized(request, response)) return httplib::Server::HandlerResponse::Handled;
    if (request.path.find('\0') != std::string::npos) {
      setError(response, 400, "bad_request", "the request path has a NUL byte (%00)");
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
  http.set_error_handler(httplib::Server::HandlerWithResponse([this](const httplib::Request& request, httplib::Response& response) {
    if (!response.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
    if (response.status == 404 || response.status == 405) {
      answerUnrouted(request, response);
    } else {
      setError(response, response.status, statusCode(response.status), libraryErrorMessage(response.status, options.maxBodyBytes));
    }
    return httplib::Server::HandlerResponse::Handled;
  }));
  addFixedRoutes();
  for (ApiRoute& route : sessionRoutes(sessions, options)) routes.push_back(std::move(route));
  for (ApiRoute& route : taskRoutes(runs, options)) routes.push_back(std::move(route));
  for (const ApiRoute& route : routes) addRoute(route);
  addEventStream();
  // Other POST and DELETE paths are answered without reading a body (httplib would wait for one
  // that has no length until the read timeout); the connection closes, as a body may follow.
  const auto unrouted = [this](const httplib::Request& request, httplib::Response& response, const httplib::ContentReader&) {
    response.set_header("Connection", "close");
    answerUnrouted(request, response);
  };
  http.Post("/(.*)", unrouted);
  http.Delete("/(.*)", unrouted);
  http.Get("/(.*)", [this](const httplib::Request& request, httplib::Response& response) {
    if (request.path.rfind("/api/", 0) == 0) return answerUnrouted(request, response);
    try {
      const StaticFile file = readStaticFile(options.viewerDirectory, request.path);
      response.set_content(file.content, file.contentType);
    } catch (const ApiError& error) {
      setError(response, error.status(), error.code(), error.what());
    }
  });
}

ApiServer::ApiServer(ServerOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {
  checkServerOptions(impl_->options);
  impl_->options.defaultProblem = checkedDefaultProblem(impl_->options.defaultProblem);
  impl_->configure();
  const ServerOptions& bound = impl_->options;
  impl_->port = bound.port == 0 ? impl_->http.bind_to_any_port(bound.host) : (impl_->http.bind_to_port(bound.host, bound.port) ? bound.port : -1);
  if (impl_->port <= 0) {
    throw InputError("serve: cannot listen on " + bound.host + ":" + std::to_string(bound.port) +
                     " (address in use, not an address of this machine, or a port that needs privileges)");
  }
  // httplib listens with a backlog of 5: a burst of clients would see connections reset. Linux
  // takes a second listen() on the socket as a new backlog.
  if (impl_->listeningSocket >= 0) ::listen(impl_->listeningSocket, kListenBacklog);
}

ApiServer::~ApiServer() { stop(); }

int ApiServer::port() const noexcept { return impl_->port; }

void ApiServer::serve() { impl_->http.listen_after_bind(); }

void ApiServer::stop() {
  if (impl_->stopped.exchange(true)) return;
  impl_->stopping->store(true);
  impl_->runs.shutdown();
  impl_->http.stop();
}

std::vector<ApiEndpoint> ApiServer::endpoints() const {
  std::vector<ApiEndpoint> list;
  for (const ApiRoute& route : impl_->routes) list.push_back({route.method, route.path, route.bodyFields});
  list.push_back({"GET", "/api/runs/{run}/events", {}});
  return list;
}

}  // namespace lang2manip
