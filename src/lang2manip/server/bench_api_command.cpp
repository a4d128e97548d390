// `lang2manip bench api`: concurrent clients of the HTTP API against the library in process.

#include "lang2manip/server/api_server.hpp"

// After Eigen (api_server.hpp): glibc's <resolv.h>, which httplib includes, defines _res.
#include <httplib.h>

#include <chrono>
#include <cstdio>
#include <mutex>
#include <thread>

#include "lang2manip/cli/bench_statistics.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/planning/planning_session.hpp"
#include "lang2manip/server/api_server.hpp"
#include "lang2manip/server/serve_command.hpp"

namespace lang2manip {
namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

struct BenchApiOptions {
  std::string problem;
  int clients = 100;
  int solves = 3;
  int baselineSolves = 30;
  bool json = false;
};

/// What the clients saw.
struct ClientResults {
  std::mutex mutex;
  std::vector<double> solveSeconds;
  /// getPath round trips: the API's cost of a request that plans nothing.
  std::vector<double> pathSeconds;
  std::vector<std::string> errors;
};

std::vector<double> inProcessSolves(const std::string& problem, int count) {
  PlanningSession session;
  session.openProblem(loadProblem(problem, "").problem);
  std::vector<double> seconds;
  for (int i = 0; i < count; ++i) {
    const auto began = Clock::now();
    const MotionPlan& plan = session.solve();
    seconds.push_back(secondsSince(began));
    if (!plan.solved()) throw InputError("bench api: the problem's query is not solved in process: " + plan.message);
  }
  return seconds;
}

/// One client: its own session; open, then `solves` times solve and get the path.
void runClient(int port, int index, const BenchApiOptions& options, ClientResults& results) {
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(120, 0);
  const std::string base = "/api/sessions/bench-" + std::to_string(index);
  const auto fail = [&](const std::string& what, const httplib::Result& result) {
    const std::lock_guard lock(results.mutex);
    results.errors.push_back("client " + std::to_string(index) + " " + what + ": " +
                             (result ? std::to_string(result->status) + " " + result->body.substr(0, 200) : httplib::to_string(result.error())));
  };
  const json open{{"problem", options.problem}};
  auto opened = client.Post((base + "/openProblem").c_str(), open.dump(), "application/json");
  if (!opened || opened->status != 200) return fail("openProblem", opened);
  for (int i = 0; i < options.solves; ++i) {
    const auto began = Clock::now();
    auto solved = client.Post((base + "/solve").c_str(), "{}", "application/json");
    const double seconds = secondsSince(began);
    if (!solved || solved->status != 200 || !json::parse(solved->body).value("solved", false)) return fail("solve", solved);
    const auto asked = Clock::now();
    auto path = client.Get((base + "/getPath").c_str());
    const double pathSeconds = secondsSince(asked);
    if (!path || path->status != 200) return fail("getPath", path);
    const std::lock_guard lock(results.mutex);
    results.solveSeconds.push_back(seconds);
    results.pathSeconds.push_back(pathSeconds);
  }
  auto closed = client.Delete(base.c_str());
  if (!closed || closed->status != 200) fail("DELETE", closed);
}

void runClients(int port, const BenchApiOptions& options, int clients, ClientResults& results) {
  std::vector<std::thread> threads;
  for (int i = 0; i < clients; ++i) threads.emplace_back([&, i] { runClient(port, i, options, results); });
  for (std::thread& thread : threads) thread.join();
}

json figures(const std::vector<double>& seconds) {
  return {{"count", seconds.size()}, {"median_ms", percentile(seconds, 0.5) * 1e3}, {"p95_ms", percentile(seconds, 0.95) * 1e3}};
}

void benchApi(const BenchApiOptions& options, std::ostream& out) {
  if (options.clients < 1 || options.clients > 1000) throw InputError("bench api: --clients must be 1 to 1000");
  if (options.solves < 1 || options.baselineSolves < 1) throw InputError("bench api: --solves and --baseline-solves must be at least 1");
  const std::vector<double> baseline = inProcessSolves(options.problem, options.baselineSolves);
  ServerOptions serverOptions;
  serverOptions.port = 0;
  serverOptions.dataRoot = "/";  // the user's own files, named on the command line
  serverOptions.maxConnections = static_cast<std::size_t>(std::max(8, std::min(options.clients + 8, 4096)));
  serverOptions.maxSessions = static_cast<std::size_t>(options.clients) + 1;
  ApiServer server(serverOptions);
  std::thread serving([&server] { server.serve(); });
  BenchApiOptions sequential = options;
  sequential.solves = options.baselineSolves;
  ClientResults alone;
  runClients(server.port(), sequential, 1, alone);
  ClientResults concurrent;
  runClients(server.port(), options, options.clients, concurrent);
  server.stop();
  serving.join();
  const double baselineMedian = percentile(baseline, 0.5);
  json report{{"problem", options.problem.empty() ? "default" : options.problem},
              {"in_process_solve", figures(baseline)},
              {"api_solve_one_client", figures(alone.solveSeconds)},
              {"api_overhead_ratio", baselineMedian > 0.0 ? percentile(alone.solveSeconds, 0.5) / baselineMedian : 0.0},
              {"api_get_path_one_client", figures(alone.pathSeconds)},
              {"clients", options.clients},
              {"api_solve_concurrent", figures(concurrent.solveSeconds)},
              {"errors", alone.errors.size() + concurrent.errors.size()}};
  if (options.json) {
    out << report.dump(2) << '\n';
  } else {
    char text[512];
    std::snprintf(text, sizeof text,
                  "solve round trips (median / p95):\n  in process         %8.2f / %8.2f ms (%zu solves, the baseline)\n"
                  "  API, one client    %8.2f / %8.2f ms  median ratio to in process %.2f\n"
                  "  API getPath alone  %8.2f / %8.2f ms (a request that plans nothing: the API's own cost)\n"
                  "  API, %d clients %8.2f / %8.2f ms (%zu solves; the clients share the machine's cores)\n",
                  report["in_process_solve"]["median_ms"].get<double>(), report["in_process_solve"]["p95_ms"].get<double>(), baseline.size(),
                  report["api_solve_one_client"]["median_ms"].get<double>(), report["api_solve_one_client"]["p95_ms"].get<double>(),
                  report["api_overhead_ratio"].get<double>(), report["api_get_path_one_client"]["median_ms"].get<double>(),
                  report["api_get_path_one_client"]["p95_ms"].get<double>(), options.clients, report["api_solve_concurrent"]["median_ms"].get<double>(),
                  report["api_solve_concurrent"]["p95_ms"].get<double>(), concurrent.solveSeconds.size());
    out << text << "errors: " << report["errors"].get<std::size_t>() << '\n';
  }
  std::vector<std::string> errors = alone.errors;
  errors.insert(errors.end(), concurrent.errors.begin(), concurrent.errors.end());
  if (!errors.empty()) throw InputError("bench api: " + std::to_string(errors.size()) + " client errors, the first: " + errors.front());
}

}  // namespace

void addBenchApiCommand(CLI::App& bench, std::ostream& out) {
  auto options = std::make_shared<BenchApiOptions>();
  CLI::App* command = bench.add_subcommand(
      "api", "Concurrent clients of the HTTP API on loopback (each its own session: open, solve, get path) against solving in process");
  command->add_option("PROBLEM", options->problem, "Problem with a query (default: the paper's scene)");
  command->add_option("--clients", options->clients, "Concurrent clients")->capture_default_str();
  command->add_option("--solves", options->solves, "Solves per concurrent client")->capture_default_str();
  command->add_option("--baseline-solves", options->baselineSolves, "Solves in process and by one client alone")->capture_default_str();
  command->add_flag("--json", options->json, "Print JSON");
  command->callback([options, &out] { benchApi(*options, out); });
}

}  // namespace lang2manip
