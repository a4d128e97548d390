// `lang2manip bench api-attacks`: a legitimate client's latency while others misuse the server
// (header floods, clients that trickle their requests, solves abandoned by their clients, bodies
// past the limit), against the same client with nobody else, in the same process.

#include "lang2manip/server/api_server.hpp"

// After Eigen (api_server.hpp): glibc's <resolv.h>, which httplib includes, defines _res.
#include <httplib.h>

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <functional>
#include <thread>

#include "lang2manip/cli/bench_statistics.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/server/serve_command.hpp"

namespace lang2manip {
namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

struct BenchAttackOptions {
  int probes = 40;
  int attackers = 40;
  bool json = false;
};

/// A connection to the server on loopback, closed when destroyed.
class AttackSocket {
 public:
  explicit AttackSocket(int port) : socket_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    timeval timeout{1, 0};
    ::setsockopt(socket_, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof timeout);
    open_ = ::connect(socket_, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
  }
  ~AttackSocket() { ::close(socket_); }
  AttackSocket(const AttackSocket&) = delete;
  AttackSocket& operator=(const AttackSocket&) = delete;

  /// False once the server stops taking bytes.
  bool send(const std::string& bytes) {
    open_ = open_ && ::send(socket_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(bytes.size());
    return open_;
  }

 private:
  int socket_;
  bool open_ = false;
};

/// Runs `attack(port, stop)` on `count` threads until the returned object is destroyed.
class Attack {
 public:
  Attack(int count, const std::function<void(const std::atomic<bool>&)>& attack) {
    for (int i = 0; i < count; ++i) threads_.emplace_back([this, attack] { attack(stop_); });
  }
  ~Attack() {
    stop_ = true;
    for (std::thread& thread : threads_) thread.join();
  }
  Attack(const Attack&) = delete;
  Attack& operator=(const Attack&) = delete;

 private:
  std::atomic<bool> stop_{false};
  std::vector<std::thread> threads_;
};

void sleepFor(double seconds, const std::atomic<bool>& stop) {
  const auto until = Clock::now() + std::chrono::duration<double>(seconds);
  while (!stop && Clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(20));
}

const std::string kRequestLine = "GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n";

/// Header lines without end, a new connection whenever the server cuts one.
void headerFlood(int port, const std::atomic<bool>& stop) {
  std::string lines;
  for (int i = 0; i < 200; ++i) lines += "X-Flood-" + std::to_string(i) + ": yes\r\n";
  while (!stop) {
    AttackSocket socket(port);
    if (!socket.send(kRequestLine)) return sleepFor(0.05, stop);
    while (!stop && socket.send(lines)) {
    }
  }
}

/// A header line a second, a new connection whenever the server cuts one.
void trickle(int port, const std::atomic<bool>& stop) {
  while (!stop) {
    AttackSocket socket(port);
    if (!socket.send(kRequestLine)) return sleepFor(0.05, stop);
    while (!stop && socket.send("X-Slow: 1\r\n")) sleepFor(1.0, stop);
  }
}

/// A body far past the limit, sent as fast as the server takes it.
void bodyFlood(int port, const std::atomic<bool>& stop) {
  const std::string block(1 << 16, ' ');
  while (!stop) {
    AttackSocket socket(port);
    if (!socket.send("POST /api/sessions/flood/openProblem HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
                     "Content-Length: 1000000000\r\n\r\n{")) {
      return sleepFor(0.05, stop);
    }
    while (!stop && socket.send(block)) {
    }
  }
}

/// A 60 s optimizing RRT* solve of the paper's query (it plans until its limit), its client gone
/// after 0.3 s; again and again.
void abandonedSolves(int port, int index, const std::atomic<bool>& stop) {
  httplib::Client client("127.0.0.1", port);
  const std::string base = "/api/sessions/abandon-" + std::to_string(index);
  client.Post((base + "/openProblem").c_str(), "{}", "application/json");
  client.Post((base + "/setPlanner").c_str(), R"({"name": "RRTstar"})", "application/json");
  client.Post((base + "/setPlannerParameter").c_str(), R"json({"name": "_Optimize (0/1)", "value": "1"})json", "application/json");
  const std::string body = R"({"time_limit": 60})";
  while (!stop) {
    AttackSocket socket(port);
    socket.send("POST " + base + "/solve HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: " +
                std::to_string(body.size()) + "\r\n\r\n" + body);
    sleepFor(0.3, stop);
  }
}

/// A legitimate client's round trips: health, then a solve of the paper's query in its session.
struct ProbeFigures {
  std::vector<double> healthSeconds;
  std::vector<double> solveSeconds;
  int failures = 0;
};

ProbeFigures probe(int port, int count) {
  ProbeFigures figures;
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(60, 0);
  client.Post("/api/sessions/probe/openProblem", "{}", "application/json");
  for (int i = 0; i < count; ++i) {
    const auto asked = Clock::now();
    const auto health = client.Get("/api/health");
    figures.healthSeconds.push_back(secondsSince(asked));
    const auto solving = Clock::now();
    const auto solved = client.Post("/api/sessions/probe/solve", "{}", "application/json");
    figures.solveSeconds.push_back(secondsSince(solving));
    if (!health || health->status != 200 || !solved || solved->status != 200) ++figures.failures;
  }
  return figures;
}

json figuresJson(const ProbeFigures& figures, const ProbeFigures& baseline) {
  const auto ratio = [](const std::vector<double>& values, const std::vector<double>& base) {
    const double median = percentile(base, 0.5);
    return median > 0.0 ? percentile(values, 0.5) / median : 0.0;
  };
  return {{"health_median_ms", percentile(figures.healthSeconds, 0.5) * 1e3},
          {"health_p95_ms", percentile(figures.healthSeconds, 0.95) * 1e3},
          {"health_ratio", ratio(figures.healthSeconds, baseline.healthSeconds)},
          {"solve_median_ms", percentile(figures.solveSeconds, 0.5) * 1e3},
          {"solve_p95_ms", percentile(figures.solveSeconds, 0.95) * 1e3},
          {"solve_ratio", ratio(figures.solveSeconds, baseline.solveSeconds)},
          {"failures", figures.failures}};
}

void benchAttacks(const BenchAttackOptions& options, std::ostream& out) {
  if (options.probes < 3 || options.probes > 10000) throw InputError("bench api-attacks: --probes must be 3 to 10000");
  if (options.attackers < 1 || options.attackers > 200) throw InputError("bench api-attacks: --attackers must be 1 to 200");
  ServerOptions serverOptions;
  serverOptions.port = 0;
  ApiServer server(serverOptions);
  std::thread serving([&server] { server.serve(); });
  const int port = server.port();
  const ProbeFigures baseline = probe(port, options.probes);
  json report{{"probes", options.probes}, {"attackers", options.attackers}, {"none", figuresJson(baseline, baseline)}};
  const std::vector<std::pair<std::string, std::function<std::unique_ptr<Attack>()>>> attacks = {
      {"header_flood", [&] { return std::make_unique<Attack>(4, [port](const auto& stop) { headerFlood(port, stop); }); }},
      {"slow_clients", [&] { return std::make_unique<Attack>(options.attackers, [port](const auto& stop) { trickle(port, stop); }); }},
      {"body_flood", [&] { return std::make_unique<Attack>(4, [port](const auto& stop) { bodyFlood(port, stop); }); }},
      {"abandoned_solves", [&] {
         auto index = std::make_shared<std::atomic<int>>(0);
         return std::make_unique<Attack>(2, [port, index](const auto& stop) { abandonedSolves(port, (*index)++, stop); });
       }}};
  for (const auto& [name, start] : attacks) {
    const std::unique_ptr<Attack> attack = start();
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    report[name] = figuresJson(probe(port, options.probes), baseline);
  }
  server.stop();
  serving.join();
  if (options.json) {
    out << report.dump(2) << '\n';
    return;
  }
  out << "a legitimate client's round trips under each attack (median / p95, ratio of medians to no attack):\n";
  for (const char* name : {"none", "header_flood", "slow_clients", "body_flood", "abandoned_solves"}) {
    const json& row = report[name];
    char text[256];
    std::snprintf(text, sizeof text, "  %-17s health %7.2f / %7.2f ms (x%.2f)   solve %8.2f / %8.2f ms (x%.2f)   failures %d\n", name,
                  row["health_median_ms"].get<double>(), row["health_p95_ms"].get<double>(), row["health_ratio"].get<double>(),
                  row["solve_median_ms"].get<double>(), row["solve_p95_ms"].get<double>(), row["solve_ratio"].get<double>(),
                  row["failures"].get<int>());
    out << text;
  }
}

}  // namespace

void addBenchAttacksCommand(CLI::App& bench, std::ostream& out) {
  auto options = std::make_shared<BenchAttackOptions>();
  CLI::App* command = bench.add_subcommand(
      "api-attacks", "A legitimate client's latency (health, a solve) while others flood headers or bodies, trickle requests or abandon solves");
  command->add_option("--probes", options->probes, "Round trips measured per attack")->capture_default_str();
  command->add_option("--attackers", options->attackers, "Trickling clients in the slow-client attack")->capture_default_str();
  command->add_flag("--json", options->json, "Print JSON");
  command->callback([options, &out] { benchAttacks(*options, out); });
}

}  // namespace lang2manip
