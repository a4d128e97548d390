// `lang2manip bench mbm`: the MotionBenchMaker Panda problems (docs/benchmarks.md) solved with
// the built-in Panda, the exact FCL checker and an OMPL planner; every solution re-verified.
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <ompl/util/RandomNumbers.h>

#include "lang2manip/cli/bench_commands.hpp"
#include "lang2manip/cli/bench_statistics.hpp"
#include "lang2manip/cli/parameter_assignment.hpp"
#include "lang2manip/cli/progress_display.hpp"
#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/output_files.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/moveit_scene_reader.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "lang2manip/planning/benchmark_log.hpp"
#include "lang2manip/planning/motion_planner.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

struct MbmOptions {
  std::string directory;
  std::string family;
  int limit = 0;
  std::string planner = "RRTConnect";
  std::vector<std::string> parameters;
  double timeLimit = 10.0;
  double resolution = MotionPlanningOptions{}.resolution;
  long seed = 1;
  bool json = false;
  std::string log;
};

struct FamilyFigures {
  std::string name;
  int problems = 0;
  int valid = 0;
  int solved = 0;
  int rejectedPaths = 0;
  std::vector<double> planningMs;
  std::vector<double> simplifyMs;
  std::vector<double> lengthBefore;
  std::vector<double> lengthAfter;
};

std::map<std::string, std::vector<std::filesystem::path>> findScenes(const MbmOptions& options) {
  const std::filesystem::path root(options.directory);
  if (!std::filesystem::is_directory(root)) throw InputError(options.directory + ": not a directory");
  std::map<std::string, std::vector<std::filesystem::path>> families;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("scene", 0) != 0 || entry.path().extension() != ".yaml") continue;
    families[entry.path().parent_path().filename().string()].push_back(entry.path());
  }
  if (families.empty()) throw InputError(options.directory + ": no MotionBenchMaker sceneNNNN.yaml files");
  if (!options.family.empty()) {
    if (!families.count(options.family)) {
      std::string names;
      for (const auto& [name, files] : families) names += (names.empty() ? "" : ", ") + name;
      throw InputError("--family " + options.family + ": unknown family; families: " + names);
    }
    families = {{options.family, families[options.family]}};
  }
  for (auto& [name, files] : families) {
    std::sort(files.begin(), files.end());
    if (options.limit > 0 && static_cast<int>(files.size()) > options.limit) files.resize(static_cast<std::size_t>(options.limit));
  }
  return families;
}

json figuresJson(const FamilyFigures& figures) {
  return {{"name", figures.name},
          {"problems", figures.problems},
          {"valid", figures.valid},
          {"solved", figures.solved},
          {"median_ms", percentile(figures.planningMs, 0.5)},
          {"mean_ms", mean(figures.planningMs)},
          {"p95_ms", percentile(figures.planningMs, 0.95)},
          {"max_ms", maximum(figures.planningMs)},
          {"simplify_median_ms", percentile(figures.simplifyMs, 0.5)},
          {"length_before_median", percentile(figures.lengthBefore, 0.5)},
          {"length_after_median", percentile(figures.lengthAfter, 0.5)},
          {"rejected_paths", figures.rejectedPaths}};
}

void addTo(FamilyFigures& figures, const MotionPlan& plan) {
  figures.planningMs.push_back(plan.statistics.planningSeconds * 1e3);
  figures.rejectedPaths += plan.statistics.rejectedPaths;
  if (!plan.solved()) return;
  ++figures.solved;
  figures.simplifyMs.push_back(plan.statistics.simplifySeconds * 1e3);
  figures.lengthBefore.push_back(plan.statistics.lengthBeforeSimplification);
  figures.lengthAfter.push_back(plan.statistics.lengthAfterSimplification);
}

/// One MotionBenchMaker problem: its plan (none when its start or goal is invalid for our model)
/// and the run as OMPL's log has it.
struct MbmOutcome {
  std::optional<MotionPlan> plan;
  BenchmarkRun logged;
};

/// The scene's number in its family ("scene0042.yaml" -> 42), the problem's id in the log; -1
/// when the name has none that fits.
long sceneNumber(const std::filesystem::path& scene) {
  const std::string stem = scene.stem().string();
  long number = -1;
  if (stem.size() > 5) std::from_chars(stem.data() + 5, stem.data() + stem.size(), number);
  return number;
}

/// `outcome`'s run with the family (an enum over the families) and the scene's number.
BenchmarkRun logRun(MbmOutcome outcome, int familyIndex, const std::filesystem::path& scene) {
  outcome.logged["family ENUM"] = std::to_string(familyIndex);
  outcome.logged["problem INTEGER"] = std::to_string(sceneNumber(scene));
  return std::move(outcome.logged);
}

class MbmRunner {
 public:
  explicit MbmRunner(const MbmOptions& options) : options_(options), panda_(readUrdfFile(builtinRobotUrdf("panda"))) {
    settings_.setPlanner(options.planner);
    for (const std::string& parameter : options.parameters) {
      const auto [name, value] = parseParameterAssignment(parameter);
      settings_.setParameter(name, value);
    }
    settings_.setParameter("_Max Planning Time", std::to_string(options.timeLimit));
    planningOptions_.resolution = options.resolution;
  }

  // Solves one problem; no plan when its start or goal is outside our model's limits or collides.
  MbmOutcome run(const std::filesystem::path& scene) {
    const MoveItProblem problem = readMoveItProblem(scene, requestFileForScene(scene), panda_);
    FclCheckerSettings checkerSettings;
    if (matrix_) checkerSettings.precomputedMatrices = {matrix_};
    auto checker = std::make_shared<FclCollisionChecker>(problem.scene, checkerSettings);
    matrix_ = checker->sharedAllowedCollisions(0);
    auto space = std::make_shared<JointPlanningSpace>(checker, std::vector<std::string>{problem.robot},
                                                      std::vector<std::vector<std::string>>{problem.goalJoints});
    std::vector<VectorX> configurations{problem.start};
    const VectorX start = space->pointFromConfigurations(configurations);
    configurations = {problem.goal};
    const VectorX goal = space->pointFromConfigurations(configurations);
    for (const VectorX* point : {&start, &goal}) {
      if (!withinLimits(*space, *point)) {
        ++outsideLimits_;
        return {std::nullopt, invalidBenchmarkRun(point == &start)};
      }
      if (!space->isValid(point->data())) {
        ++inCollision_;
        return {std::nullopt, invalidBenchmarkRun(point == &start)};
      }
    }
    MotionPlanner planner(space, planningOptions_);
    MotionPlan plan = planner.solve(start, {goal}, settings_, StopCondition::never());
    BenchmarkRun logged = benchmarkRunOf(plan);
    return {std::move(plan), std::move(logged)};
  }

  [[nodiscard]] const PlannerSettings& settings() const { return settings_; }
  /// Problems whose start or goal is outside our model's joint limits, or in collision.
  [[nodiscard]] int outsideLimits() const { return outsideLimits_; }
  [[nodiscard]] int inCollision() const { return inCollision_; }

 private:
  static bool withinLimits(const PlanningSpace& space, const VectorX& x) {
    return (x.array() >= space.lower().array()).all() && (x.array() <= space.upper().array()).all();
  }

  int outsideLimits_ = 0;
  int inCollision_ = 0;
  MbmOptions options_;
  RobotModelPtr panda_;
  PlannerSettings settings_;
  MotionPlanningOptions planningOptions_;
  std::shared_ptr<const AllowedCollisionMatrix> matrix_;
};

std::string figuresLine(const json& f) {
  char line[400];
  std::snprintf(line, sizeof line, "%-24s %5d %5d %6d %9.2f %9.2f %9.2f %9.1f %10.2f %7.2f %7.2f\n",
                f["name"].get<std::string>().c_str(), f["problems"].get<int>(), f["valid"].get<int>(),
                f["solved"].get<int>(), f["median_ms"].get<double>(), f["mean_ms"].get<double>(),
                f["p95_ms"].get<double>(), f["max_ms"].get<double>(), f["simplify_median_ms"].get<double>(),
                f["length_before_median"].get<double>(), f["length_after_median"].get<double>());
  return line;
}

void writeLog(const MbmOptions& options, const PlannerSettings& settings, std::vector<BenchmarkRun> runs,
              std::vector<std::string> familyNames, double seconds) {
  BenchmarkExperiment experiment = startBenchmarkExperiment(
      "lang2manip bench mbm: MotionBenchMaker panda, " + (options.family.empty() ? "all families" : "family " + options.family) +
      ", " + settings.planner() + ", " + numberText(options.timeLimit) + " s per problem");
  experiment.enumTypes.emplace_back("family", std::move(familyNames));
  experiment.setupInfo = "lang2manip bench mbm: built-in Panda, FCL exact checker, motion resolution " +
                         numberText(options.resolution) + " rad, paths re-verified\n";
  experiment.seed = static_cast<unsigned long>(options.seed);
  experiment.maxTime = options.timeLimit;
  experiment.totalDuration = seconds;
  BenchmarkPlannerRuns planner{"geometric_" + settings.planner(), {}, std::move(runs)};
  for (const auto& [name, value] : settings.omplParameters()) planner.common[name] = value;
  experiment.planners.push_back(std::move(planner));
  std::ostringstream text;
  writeOmplBenchmarkLog(experiment, text);
  writeFileAtomically(options.log, text.str(), "bench mbm: --log");
}

void runMbm(const MbmOptions& options, std::ostream& out) {
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(options.seed));
  const auto families = findScenes(options);
  MbmRunner runner(options);
  FamilyFigures overall;
  overall.name = "overall";
  json report{{"families", json::array()}};
  std::vector<BenchmarkRun> runs;
  const auto started = std::chrono::steady_clock::now();
  int familyIndex = 0;
  std::size_t sceneCount = 0;
  for (const auto& [name, scenes] : families) sceneCount += scenes.size();
  ProgressDisplay progress("bench mbm", sceneCount, "problems");
  for (const auto& [name, scenes] : families) {
    FamilyFigures figures;
    figures.name = name;
    for (const std::filesystem::path& scene : scenes) {
      ++figures.problems;
      ++overall.problems;
      MbmOutcome outcome = runner.run(scene);
      progress.advance();
      const std::optional<MotionPlan> plan = std::move(outcome.plan);
      runs.push_back(logRun(std::move(outcome), familyIndex, scene));
      if (!plan) continue;
      ++figures.valid;
      ++overall.valid;
      addTo(figures, *plan);
      addTo(overall, *plan);
    }
    report["families"].push_back(figuresJson(figures));
    ++familyIndex;
  }
  progress.finish();
  report["overall"] = figuresJson(overall);
  report["planner"] = runner.settings().planner();
  report["invalid_outside_limits"] = runner.outsideLimits();
  report["invalid_in_collision"] = runner.inCollision();
  report["time_limit_s"] = options.timeLimit;
  report["resolution"] = options.resolution;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::vector<std::string> familyNames;
  for (const auto& [name, scenes] : families) familyNames.push_back(name);
  if (!options.log.empty()) writeLog(options, runner.settings(), std::move(runs), std::move(familyNames), seconds);
  if (options.json) {
    out << report.dump(2) << '\n';
    return;
  }
  out << "MotionBenchMaker, built-in Panda, " << runner.settings().planner() << ", FCL exact checker, "
      << options.timeLimit << " s limit, every solution re-verified\n";
  out << "family                   probs valid solved median_ms   mean_ms    p95_ms    max_ms simplify_ms  len_in len_out\n";
  for (const json& family : report["families"]) out << figuresLine(family);
  out << figuresLine(report["overall"]);
  out << "not valid for the built-in Panda: " << runner.outsideLimits()
      << " with a start or goal outside its joint limits, " << runner.inCollision()
      << " with a start or goal in collision\n";
}

}  // namespace

void addBenchMbmCommand(CLI::App& bench, std::ostream& out) {
  auto options = std::make_shared<MbmOptions>();
  CLI::App* command = bench.add_subcommand("mbm", "MotionBenchMaker Panda problems with an OMPL planner");
  command->add_option("DIR", options->directory, "Directory of MotionBenchMaker families (e.g. ../shared/data/mbm/panda)")
      ->required();
  command->add_option("--family", options->family, "Only this family (e.g. box_panda)");
  command->add_option("--limit", options->limit, "At most N problems per family")->check(CLI::PositiveNumber);
  command->add_option("--planner", options->planner, "Planner name")->capture_default_str();
  command->add_option("--param", options->parameters, "Planner parameter NAME=VALUE (repeatable)");
  command->add_option("--time-limit", options->timeLimit, "Seconds per problem")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--resolution", options->resolution, "Motion-check step while planning (rad)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--seed", options->seed, "Random seed")->capture_default_str();
  command->add_flag("--json", options->json, "Print JSON");
  command->add_option("--log", options->log, "Write OMPL's benchmark log format to FILE");
  command->callback([options, &out] { runMbm(*options, out); });
}

}  // namespace lang2manip
