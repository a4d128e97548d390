// `lang2manip bench kautham`: a Kautham <Benchmark> file run as Kautham runs it (every problem it
// lists with its own planner and first query, runCount times within maxTime), with OMPL's log.

#include <chrono>
#include <cstdio>
#include <sstream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <ompl/util/RandomNumbers.h>

#include "lang2manip/cli/bench_commands.hpp"
#include "lang2manip/cli/bench_statistics.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/output_files.hpp"
#include "lang2manip/model/kautham_benchmark.hpp"
#include "lang2manip/planning/benchmark_log.hpp"
#include "lang2manip/planning/planning_session.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

struct KauthamBenchOptions {
  std::string file;
  int runs = 0;
  double timeLimit = 0.0;
  std::string log;
  long seed = 1;
  bool json = false;
};

/// The runs of one problem of the benchmark.
BenchmarkPlannerRuns runProblem(const KauthamBenchmark::Entry& entry, const KauthamBenchmark& benchmark, json& figures) {
  PlanningSession session;
  try {
    session.openProblem(entry.problem);
  } catch (const InputError& error) {
    throw InputError(entry.where, std::string("benchmark problem: ") + error.what());
  }
  session.setPlannerParameter("_Max Planning Time", std::to_string(benchmark.maxTime));
  const std::string planner = session.plannerSettings().planner();
  const std::string alias = entry.alias.empty() ? planner : entry.alias;
  BenchmarkPlannerRuns runs{"geometric_" + alias, {}, {}};
  for (const auto& [name, value] : session.plannerSettings().omplParameters()) runs.common[name] = value;
  std::vector<double> milliseconds;
  int solved = 0;
  for (int run = 0; run < benchmark.runCount; ++run) {
    const MotionPlan& plan = session.solve();
    runs.runs.push_back(benchmarkRunOf(plan));
    milliseconds.push_back(plan.statistics.planningSeconds * 1e3);
    solved += plan.solved() ? 1 : 0;
  }
  figures = {{"problem", entry.problem.filename().string()}, {"alias", alias}, {"planner", planner},
             {"runs", benchmark.runCount}, {"solved", solved}, {"median_ms", percentile(milliseconds, 0.5)},
             {"p95_ms", percentile(milliseconds, 0.95)}, {"mean_ms", mean(milliseconds)}};
  return runs;
}

void runBenchmark(const KauthamBenchOptions& options, std::ostream& out) {
  KauthamBenchmark benchmark = readKauthamBenchmarkFile(options.file);
  if (options.runs > 0) benchmark.runCount = options.runs;
  if (options.timeLimit > 0.0) benchmark.maxTime = options.timeLimit;
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(options.seed));
  BenchmarkExperiment experiment = startBenchmarkExperiment(benchmark.name.empty() ? options.file : benchmark.name);
  experiment.setupInfo = "lang2manip bench kautham " + options.file + ": each problem's own planner and first query, FCL exact checker, paths re-verified\n";
  experiment.seed = static_cast<unsigned long>(options.seed);
  experiment.maxTime = benchmark.maxTime;
  experiment.maxMemoryMb = benchmark.maxMemoryMb;
  experiment.runCount = static_cast<unsigned int>(benchmark.runCount);
  json report{{"benchmark", options.file}, {"run_count", benchmark.runCount}, {"max_time_s", benchmark.maxTime},
              {"ignored_parameters", benchmark.ignoredParameters}, {"problems", json::array()}};
  const auto started = std::chrono::steady_clock::now();
  for (const KauthamBenchmark::Entry& entry : benchmark.problems) {
    json figures;
    experiment.planners.push_back(runProblem(entry, benchmark, figures));
    report["problems"].push_back(figures);
  }
  experiment.totalDuration = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  // Only where asked: the file's own log name would write into whatever directory this runs in.
  const std::string& log = options.log;
  if (!log.empty()) {
    std::ostringstream text;
    writeOmplBenchmarkLog(experiment, text);
    writeFileAtomically(log, text.str(), "bench kautham: --log");
    report["log"] = log;
  } else if (!benchmark.logFile.empty()) {
    report["log_not_written"] = benchmark.logFile;
  }
  if (options.json) {
    out << report.dump(2) << '\n';
    return;
  }
  out << "Kautham benchmark " << options.file << ": " << benchmark.runCount << " runs per problem, " << benchmark.maxTime << " s each\n";
  out << "problem                                    planner          solved  median_ms     p95_ms\n";
  for (const json& f : report["problems"]) {
    char line[256];
    std::snprintf(line, sizeof line, "%-42s %-16s %3d/%-3d %10.2f %10.2f\n", f["problem"].get<std::string>().c_str(),
                  f["alias"].get<std::string>().c_str(), f["solved"].get<int>(), f["runs"].get<int>(), f["median_ms"].get<double>(),
                  f["p95_ms"].get<double>());
    out << line;
  }
  if (!benchmark.ignoredParameters.empty()) {
    std::string names;
    for (const std::string& name : benchmark.ignoredParameters) names += (names.empty() ? "" : ", ") + name;
    out << "accepted with no effect: " << names << "\n";
  }
  if (report.contains("log")) out << "wrote OMPL's benchmark log " << log << "\n";
  if (report.contains("log_not_written")) {
    out << "the benchmark file names the log " << benchmark.logFile << "; pass --log FILE to write it\n";
  }
}

}  // namespace

void addBenchKauthamCommand(CLI::App& bench, std::ostream& out) {
  auto options = std::make_shared<KauthamBenchOptions>();
  CLI::App* command = bench.add_subcommand("kautham", "A Kautham <Benchmark> file: every problem it lists, with OMPL's benchmark log");
  command->add_option("FILE", options->file, "Kautham benchmark file (<Benchmark> root)")->required();
  command->add_option("--runs", options->runs, "Runs per problem (default: the file's runCount)")->check(CLI::PositiveNumber);
  command->add_option("--time-limit", options->timeLimit, "Seconds per run (default: the file's maxTime)")->check(CLI::PositiveNumber);
  command->add_option("--log", options->log, "Write OMPL's benchmark log to FILE (the benchmark file's own log name is only reported, never written unasked)");
  command->add_option("--seed", options->seed, "Random seed")->capture_default_str();
  command->add_flag("--json", options->json, "Print JSON");
  command->callback([options, &out] { runBenchmark(*options, out); });
}

}  // namespace lang2manip
