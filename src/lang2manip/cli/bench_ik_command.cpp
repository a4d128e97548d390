// `lang2manip bench ik`: the TRAC-IK protocol of docs/benchmarks.md. Random configurations
// within the limits -> FK -> target; each solver starts from the mid-limit seed with the same
// budget; success = position and orientation errors <= 1e-5 within the limits, re-checked here
// with our own FK. KDL NR_JL (single shot and with restarts) runs in the same process as every
// other solver, and the ratio of medians against KDL with restarts is printed. The budget is
// wall time, as in the protocol; on a shared machine a solve can fail only because the thread
// was not running, so failures that ran out of wall time while their thread CPU time stayed
// under half the budget are counted apart ("descheduled") as a diagnostic.

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "lang2manip/cli/bench_commands.hpp"
#include "lang2manip/cli/bench_statistics.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/random.hpp"
#include "lang2manip/kinematics/ik_solver.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {
namespace {

constexpr double kTolerance = 1e-5;
constexpr const char* kBaseline = "kdl_restarts";

struct BenchIkOptions {
  std::string robot = "panda";
  int samples = 10000;
  std::uint64_t seed = 1;
  double timeoutMs = 5.0;
  bool json = false;
};

/// Benchmark robot name -> built-in robot and manipulator.
const std::map<std::string, std::pair<std::string, std::string>>& benchRobots() {
  static const std::map<std::string, std::pair<std::string, std::string>> robots = {
      {"panda", {"panda", ""}},           {"ur5", {"ur5", ""}},
      {"iiwa", {"iiwa14", ""}},           {"tx90", {"tx90", ""}},
      {"yumi_right", {"yumi", "right_arm"}}, {"yumi_left", {"yumi", "left_arm"}}};
  return robots;
}

struct SolverFigures {
  std::string name;
  std::vector<double> milliseconds;
  double successMsSum = 0.0;
  int successes = 0;
  /// Failures past the budget during which the thread ran for less than half of it.
  int descheduledFailures = 0;
};

/// CPU time of the calling thread (ms).
double threadCpuMs() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) * 1e3 + static_cast<double>(now.tv_nsec) * 1e-6;
}

/// Our own re-check: errors within the protocol's tolerance and joints within the limits.
bool meetsProtocol(const RobotModel& model, const IkRequest& request, const IkResult& result,
                   const KinematicChain& chain) {
  if (result.status != IkStatus::kSuccess || result.solutions.empty()) return false;
  const VectorX& q = result.solutions.front();
  if ((q.array() < model.lowerLimits().array()).any() ||
      (q.array() > model.upperLimits().array()).any()) {
    return false;
  }
  VectorX qc(chain.dof());
  chain.gather(q, qc);
  double position = 0.0;
  double orientation = 0.0;
  ikTargetError(request.target, chain.pose(qc), position, orientation);
  return position <= kTolerance && orientation <= kTolerance;
}

nlohmann::json figuresJson(const SolverFigures& figures, int samples, double baselineMedian) {
  const double median = percentile(figures.milliseconds, 0.5);
  return {{"name", figures.name},
          {"success_rate", static_cast<double>(figures.successes) / samples},
          {"median_ms", median},
          {"p95_ms", percentile(figures.milliseconds, 0.95)},
          {"mean_success_ms",
           figures.successes > 0 ? figures.successMsSum / figures.successes : 0.0},
          {"median_speedup_vs_kdl_restarts", median > 0.0 ? baselineMedian / median : 0.0},
          {"descheduled_failures", figures.descheduledFailures}};
}

nlohmann::json runBenchIk(const BenchIkOptions& options) {
  const auto found = benchRobots().find(options.robot);
  if (found == benchRobots().end()) {
    std::string names;
    for (const auto& entry : benchRobots()) names += (names.empty() ? "" : ", ") + entry.first;
    throw InputError("unknown benchmark robot \"" + options.robot + "\"; valid robots: " + names);
  }
  if (options.samples < 1) throw InputError("--samples must be >= 1");
  if (!(options.timeoutMs > 0.0)) throw InputError("--timeout-ms must be > 0");
  UrdfReadOptions read;
  read.loadMeshes = false;
  const RobotModelPtr model = readUrdfFile(builtinRobotUrdf(found->second.first), read);
  IkRequest request;
  request.model = model.get();
  request.manipulator = found->second.second;
  request.seed = model->middleConfiguration();
  request.timeoutSeconds = options.timeoutMs / 1000.0;
  const Manipulator& arm = request.manipulator.empty() ? model->semantics().manipulators.front()
      : *std::find_if(model->semantics().manipulators.begin(),
                      model->semantics().manipulators.end(),
                      [&](const Manipulator& m) { return m.name == request.manipulator; });
  const KinematicChain chain(*model, arm.baseLink, arm.toolFrame);

  // The baselines first, then every other registered solver.
  std::vector<std::string> names = {"kdl", kBaseline};
  for (const std::string& name : ikSolverNames()) {
    if (name != "kdl" && name != kBaseline) names.push_back(name);
  }
  std::vector<std::unique_ptr<IkSolver>> solvers;
  std::vector<SolverFigures> figures;
  for (const std::string& name : names) {
    solvers.push_back(makeIkSolver(name));
    figures.push_back({name, {}, 0.0, 0});
  }
  Random random(options.seed);
  VectorX q(model->variableCount());
  VectorX qc(chain.dof());
  for (int sample = 0; sample < options.samples; ++sample) {
    q = random.uniformVector(model->lowerLimits(), model->upperLimits());
    chain.gather(q, qc);
    request.target = IkTarget::pose(chain.pose(qc));
    request.randomSeed = options.seed * 1000003U + static_cast<std::uint64_t>(sample);
    for (std::size_t s = 0; s < solvers.size(); ++s) {
      const double cpuStart = threadCpuMs();
      const auto start = std::chrono::steady_clock::now();
      const IkResult result = solvers[s]->solve(request);
      const double ms = std::chrono::duration<double, std::milli>(
                            std::chrono::steady_clock::now() - start).count();
      const double cpuMs = threadCpuMs() - cpuStart;
      figures[s].milliseconds.push_back(ms);
      if (meetsProtocol(*model, request, result, chain)) {
        ++figures[s].successes;
        figures[s].successMsSum += ms;
      } else if (ms >= options.timeoutMs && cpuMs < 0.5 * options.timeoutMs) {
        ++figures[s].descheduledFailures;
      }
    }
  }
  const double baselineMedian = percentile(figures[1].milliseconds, 0.5);
  nlohmann::json report = {{"robot", options.robot},
                           {"samples", options.samples},
                           {"seed", options.seed},
                           {"timeout_ms", options.timeoutMs},
                           {"solvers", nlohmann::json::array()}};
  for (const SolverFigures& entry : figures) {
    report["solvers"].push_back(figuresJson(entry, options.samples, baselineMedian));
  }
  return report;
}

std::string reportText(const nlohmann::json& report) {
  char line[256];
  std::string text = "IK benchmark (TRAC-IK protocol): robot " +
                     report["robot"].get<std::string>() + ", " +
                     std::to_string(report["samples"].get<int>()) + " samples, budget " +
                     numberText(report["timeout_ms"].get<double>()) + " ms, seed " +
                     std::to_string(report["seed"].get<std::uint64_t>()) + "\n";
  std::snprintf(line, sizeof line, "%-14s %9s %10s %10s %16s %22s %12s\n", "solver", "success",
                "median ms", "p95 ms", "mean ms (succ.)", "median vs kdl_restarts",
                "descheduled");
  text += line;
  for (const nlohmann::json& s : report["solvers"]) {
    std::snprintf(line, sizeof line, "%-14s %8.2f%% %10.4f %10.4f %16.4f %21.1fx %12d\n",
                  s["name"].get<std::string>().c_str(), 100.0 * s["success_rate"].get<double>(),
                  s["median_ms"].get<double>(), s["p95_ms"].get<double>(),
                  s["mean_success_ms"].get<double>(),
                  s["median_speedup_vs_kdl_restarts"].get<double>(),
                  s["descheduled_failures"].get<int>());
    text += line;
  }
  text += "descheduled: failures past the budget during which the thread ran for less than half "
          "of it\n";
  return text;
}

}  // namespace

void addBenchIkCommand(CLI::App& bench, std::ostream& out) {
  auto options = std::make_shared<BenchIkOptions>();
  CLI::App* command = bench.add_subcommand(
      "ik", "IK success rate and times under the TRAC-IK protocol, every solver in one run");
  command->add_option("--robot", options->robot,
                      "panda, ur5, iiwa, tx90, yumi_right or yumi_left")
      ->capture_default_str();
  command->add_option("--samples", options->samples, "Random reachable targets")
      ->capture_default_str();
  command->add_option("--seed", options->seed, "Seed of the targets and of the solvers")
      ->capture_default_str();
  command->add_option("--timeout-ms", options->timeoutMs, "Time budget of each solve (ms)")
      ->capture_default_str();
  command->add_flag("--json", options->json, "Print JSON");
  command->callback([options, &out] {
    const nlohmann::json report = runBenchIk(*options);
    out << (options->json ? report.dump(2) + "\n" : reportText(report));
  });
}

}  // namespace lang2manip
