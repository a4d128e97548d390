// `lang2manip bench task`: the paper's task-level experiment (docs/benchmarks.md) at scale: N
// trials with the movable objects of the scene shifted and turned at random (seeded), each
// planned offline, grounded, executed and verified. Prints task success with its Wilson
// interval, motion feasibility, first-round plan acceptance and time per trial (median, p95),
// for lang2manip's configuration and, on the same trials in the same process, the paper's
// configuration (KDL Newton-Raphson IK), with the ratio of the median times.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <ompl/util/RandomNumbers.h>

#include "lang2manip/cli/bench_commands.hpp"
#include "lang2manip/cli/bench_statistics.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/cli/progress_display.hpp"
#include "lang2manip/cli/scene_randomization.hpp"
#include "lang2manip/cli/task_run.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/random.hpp"
#include "lang2manip/core/rotation.hpp"
#include "lang2manip/execution/execution_verification.hpp"
#include "lang2manip/execution/task_executor.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/symbolic/repair_loop.hpp"

namespace lang2manip {
namespace {

using Clock = std::chrono::steady_clock;

struct BenchTaskOptions {
  std::string problem;
  std::string robot;  ///< empty: the Panda for MoveIt scenes
  SceneOptions scene;
  std::string arm;
  std::string task = "put the marker and eraser in the holder";
  int trials = 100;
  double spread = 0.05;
  double turn = 0.5;
  long seed = 1;
  std::string baselineIk = "kdl";
  bool json = false;
};

struct Figures {
  std::string label;
  int trials = 0;
  int successes = 0;
  int firstRoundAccepted = 0;
  int plannerCalls = 0;
  int plannerSolved = 0;
  std::vector<double> seconds;
  /// "trial 7: <why>" for each trial that did not succeed.
  std::vector<std::string> failures;
};

/// Why a trial failed: the repair loop's failure, or what verification found.
std::string trialFailure(const RepairResult& repair, const ExecutionVerification& verification) {
  if (!repair.succeeded()) {
    return repair.failure;  // every round's failure
  }
  if (!verification.collision.empty()) return "collision: " + verification.collision;
  if (!verification.disturbedObjects.empty()) return "disturbed: " + verification.disturbedObjects.front();
  for (const GoalOutcome& goal : verification.goals) {
    if (!goal.holds) return "goal " + describeGoal(goal.goal) + " does not hold: " + goal.explanation;
  }
  return "not verified";
}

void runTrial(const Scene& scene, const BenchTaskOptions& options, const std::string& ik, Figures& figures) {
  ExecutionSettings settings;
  settings.manipulator = options.arm;
  settings.ikSolver = ik;
  settings.seed = static_cast<std::uint64_t>(options.seed);
  const auto began = Clock::now();
  TaskExecutor executor(scene, settings);
  OfflineTaskPlanner planner;
  const TaskRun run = planExecuteAndVerify(planner, executor, options.task, RepairOptions{}.maxRounds);
  const RepairResult& repair = run.repair;
  const bool success = run.success();
  if (!success) figures.failures.push_back("trial " + std::to_string(figures.trials + 1) + ": " + trialFailure(repair, run.verification));
  figures.seconds.push_back(secondsSince(began));
  ++figures.trials;
  figures.successes += success ? 1 : 0;
  figures.firstRoundAccepted += !repair.rounds.empty() && repair.rounds.front().outcome == RoundOutcome::kAccepted ? 1 : 0;
  for (const ExecutionRecord& record : executor.executions()) {
    figures.plannerCalls += record.counters.plannerCalls;
    figures.plannerSolved += record.counters.plannerSolved;
  }
}

/// The 95% Wilson score interval of `k` successes in `n` trials.
std::pair<double, double> wilson(int k, int n) {
  if (n == 0) return {0.0, 1.0};
  const double z = 1.96, p = static_cast<double>(k) / n, nn = n;
  const double centre = (p + z * z / (2 * nn)) / (1 + z * z / nn);
  const double half = z * std::sqrt(p * (1 - p) / nn + z * z / (4 * nn * nn)) / (1 + z * z / nn);
  return {centre - half, centre + half};
}

nlohmann::json figuresJson(const Figures& f) {
  const auto [low, high] = wilson(f.successes, f.trials);
  return {{"configuration", f.label},
          {"trials", f.trials},
          {"task_success", f.successes},
          {"task_success_wilson95", {low, high}},
          {"first_round_accepted", f.firstRoundAccepted},
          {"motion_queries", f.plannerCalls},
          {"motion_queries_solved", f.plannerSolved},
          {"seconds_median", percentile(f.seconds, 0.5)},
          {"seconds_p95", percentile(f.seconds, 0.95)},
          {"seconds_mean", mean(f.seconds)},
          {"failures", f.failures}};
}

void printFigures(const Figures& f, std::ostream& out) {
  const auto [low, high] = wilson(f.successes, f.trials);
  char line[400];
  std::snprintf(line, sizeof line,
                "%-28s task success %d/%d (%.1f%%, Wilson 95%% [%.1f%%, %.1f%%]); motion feasibility %d/%d (%.1f%%); "
                "plans accepted in round 1: %d/%d; time per trial median %.1f ms, p95 %.1f ms\n",
                f.label.c_str(), f.successes, f.trials, 100.0 * f.successes / std::max(1, f.trials), 100.0 * low, 100.0 * high,
                f.plannerSolved, f.plannerCalls, 100.0 * f.plannerSolved / std::max(1, f.plannerCalls), f.firstRoundAccepted,
                f.trials, 1000.0 * percentile(f.seconds, 0.5), 1000.0 * percentile(f.seconds, 0.95));
  out << line;
  for (std::size_t i = 0; i < f.failures.size() && i < 5; ++i) out << "    " << f.failures[i].substr(0, 300) << '\n';
}

void checkOptions(const BenchTaskOptions& options) {
  if (options.trials < 1) throw InputError("bench task: --trials must be at least 1");
  if (!(options.spread >= 0.0 && std::isfinite(options.spread))) throw InputError("bench task: --spread must be a length >= 0");
  if (!(options.turn >= 0.0 && std::isfinite(options.turn))) throw InputError("bench task: --turn must be an angle >= 0");
  if (options.seed < 0) throw InputError("bench task: --seed must be >= 0");
  (void)makeIkSolver(options.baselineIk);
}

void runBench(const BenchTaskOptions& options, std::ostream& out) {
  checkOptions(options);
  const LoadedProblem loaded = loadProblem(options.problem, options.robot, options.scene);
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(options.seed));
  Figures ours, paper;
  ours.label = "lang2manip (dls IK)";
  paper.label = "paper configuration (" + options.baselineIk + " IK)";
  Random random(static_cast<std::uint64_t>(options.seed));
  int skipped = 0;
  ProgressDisplay progress("bench task", static_cast<std::size_t>(options.trials), "trials");
  for (int i = 0; i < options.trials; ++i) {
    const std::optional<Scene> scene = randomizedScene(loaded.problem.scene, options.spread, options.turn, random);
    if (scene) {
      runTrial(*scene, options, defaultIkSolverName(), ours);
      runTrial(*scene, options, options.baselineIk, paper);
    } else {
      ++skipped;
    }
    progress.advance();
  }
  progress.finish();
  const double ratio = percentile(paper.seconds, 0.5) / std::max(1e-12, percentile(ours.seconds, 0.5));
  if (options.json) {
    out << nlohmann::json({{"problem", loaded.name}, {"task", options.task}, {"spread", options.spread}, {"turn", options.turn},
                           {"skipped_scenes", skipped}, {"results", {figuresJson(ours), figuresJson(paper)}},
                           {"median_time_ratio", ratio}})
               .dump(2)
        << '\n';
    return;
  }
  out << "bench task: \"" << options.task << "\" on " << loaded.name << ", " << ours.trials << " trials (objects shifted up to "
      << options.spread << " m, turned up to " << options.turn << " rad; seed " << options.seed << ")\n";
  printFigures(ours, out);
  printFigures(paper, out);
  char line[160];
  std::snprintf(line, sizeof line, "median time ratio (paper configuration / lang2manip): %.2fx\n", ratio);
  out << line;
  if (skipped > 0) out << skipped << " random scenes had overlapping objects after 100 tries and were skipped\n";
  out << "published (paper, 20 trials): task success 85%, motion feasibility 92%\n";
}

}  // namespace

void addBenchTaskCommand(CLI::App& bench, std::ostream& out) {
  auto options = std::make_shared<BenchTaskOptions>();
  CLI::App* command = bench.add_subcommand("task", "Randomized trials of a task: success, motion feasibility, time; "
                                                   "the paper's IK configuration as the baseline");
  command->add_option("PROBLEM", options->problem, "Built-in problem or Kautham problem file (default: " + defaultProblemName() + ")");
  command->add_option("--task", options->task, "The instruction")->capture_default_str();
  command->add_option("--robot", options->robot, "Robot of a MoveIt scene: a built-in name or a .urdf/.xacro file (default: panda)");
  addSceneOptions(*command, options->scene);
  command->add_option("--arm", options->arm, "The arm that executes the task");
  command->add_option("--trials", options->trials, "Randomized scenes")->capture_default_str();
  command->add_option("--spread", options->spread, "Largest shift of each movable object in x and y (m)")->capture_default_str();
  command->add_option("--turn", options->turn, "Largest turn of each movable object about z (rad)")->capture_default_str();
  command->add_option("--seed", options->seed, "Random seed")->capture_default_str();
  command->add_option("--baseline-ik", options->baselineIk, "IK solver of the baseline run")->capture_default_str();
  command->add_flag("--json", options->json, "Print the figures as JSON");
  command->callback([options, &out] { runBench(*options, out); });
}

}  // namespace lang2manip
