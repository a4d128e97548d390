// `lang2manip bench families`: the instruction families of the published benchmarks
// (instruction_families.hpp) on generated tabletops of every built-in robot, through the
// offline planner, the executor and verification; and the same instances with the plan a capable
// planner would give (grounding alone). Per family: understood (a plan, not a refusal), executed
// and verified against the family's own check in the first round and after repair, and with the
// plan given; the time per instruction.

#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include <ompl/util/RandomNumbers.h>

#include "lang2manip/cli/bench_commands.hpp"
#include "lang2manip/cli/bench_statistics.hpp"
#include "lang2manip/cli/instruction_families.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/cli/tabletop_scenes.hpp"
#include "lang2manip/cli/task_run.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/symbolic/given_plan_planner.hpp"

namespace lang2manip {
namespace families_bench {
namespace {

using Clock = std::chrono::steady_clock;

struct BenchFamiliesOptions {
  std::vector<std::string> families;
  std::vector<std::string> problems;
  int scenesPerProblem = 4;
  long seed = 1;
  bool given = true;
  int failuresShown = 10;
  bool json = false;
};

/// What became of one instance.
struct InstanceOutcome {
  std::string family;
  std::string problem;
  std::string instruction;
  bool understood = false;
  bool firstRound = false;
  bool afterRepair = false;
  bool givenPlan = false;
  double seconds = 0.0;
  std::string why{};
  std::string givenWhy{};
};

/// Runs `planner` on the instance; true when the run succeeded and the family's check holds on
/// its final world. `why` says what failed.
bool runAndCheck(const FamilyInstance& instance, TaskPlanner& planner, long seed, TaskRun& run, std::string& why) {
  ExecutionSettings settings;
  settings.seed = static_cast<std::uint64_t>(seed);
  TaskExecutor executor(instance.scene, settings);
  run = planExecuteAndVerify(planner, executor, instance.instruction, RepairOptions{}.maxRounds);
  // The family's check is the truth, not the goals the planner understood.
  if (!run.repair.succeeded()) {
    why = run.repair.failure;
    return false;
  }
  const ExecutionVerification& verified = run.verification;
  if (!verified.collision.empty()) why = "collision: " + verified.collision;
  if (!verified.disturbedObjects.empty()) why = "disturbed: " + verified.disturbedObjects.front();
  if (!why.empty()) return false;
  const GoalCheck check = instance.check(executor.executions().back().finalScene, instance.scene);
  if (!check.holds) why = "the family's check fails: " + check.explanation;
  return check.holds;
}

InstanceOutcome runInstance(const FamilyInstance& instance, const std::string& problem, long seed, bool given) {
  InstanceOutcome outcome{instance.family, problem, instance.instruction};
  const auto began = Clock::now();
  OfflineTaskPlanner offline;
  TaskRun run;
  outcome.afterRepair = runAndCheck(instance, offline, seed, run, outcome.why);
  outcome.seconds = secondsSince(began);
  outcome.understood = !run.repair.rounds.empty() && run.repair.rounds.front().attempt.plan.has_value();
  outcome.firstRound = outcome.afterRepair && run.repair.rounds.size() == 1;
  if (given) {
    GivenPlanTaskPlanner planner(instance.plan, "family's reference plan");
    TaskRun givenRun;
    outcome.givenPlan = runAndCheck(instance, planner, seed, givenRun, outcome.givenWhy);
  }
  return outcome;
}

struct FamilyTally {
  int instances = 0, understood = 0, firstRound = 0, afterRepair = 0, givenPlan = 0;
  std::vector<double> seconds;
};

double percentOf(int part, int whole) { return whole == 0 ? 0.0 : 100.0 * part / whole; }

void addTo(FamilyTally& f, const InstanceOutcome& o) {
  ++f.instances;
  f.understood += o.understood ? 1 : 0;
  f.firstRound += o.firstRound ? 1 : 0;
  f.afterRepair += o.afterRepair ? 1 : 0;
  f.givenPlan += o.givenPlan ? 1 : 0;
  f.seconds.push_back(o.seconds);
}

std::string row(const std::string& name, const FamilyTally& f, bool given) {
  char givenText[32] = "-";
  if (given) std::snprintf(givenText, sizeof givenText, "%.1f%%", percentOf(f.givenPlan, f.instances));
  char line[256];
  std::snprintf(line, sizeof line, "%-30s %5d  %9.1f%%  %10.1f%%  %11.1f%%  %10s  %9.1f\n", name.c_str(), f.instances,
                percentOf(f.understood, f.instances), percentOf(f.firstRound, f.instances), percentOf(f.afterRepair, f.instances), givenText,
                1000.0 * percentile(f.seconds, 0.5));
  return line;
}

std::vector<std::string> problemsToRun(const BenchFamiliesOptions& options) {
  if (!options.problems.empty()) return options.problems;
  std::vector<std::string> names;
  for (const BuiltinProblem& problem : builtinProblems()) names.push_back(problem.shortName);
  return names;
}

std::vector<const InstructionFamily*> familiesToRun(const BenchFamiliesOptions& options) {
  std::vector<const InstructionFamily*> chosen;
  std::set<std::string> known;
  for (const InstructionFamily& family : instructionFamilies()) {
    known.insert(family.name);
    if (options.families.empty() || std::find(options.families.begin(), options.families.end(), family.name) != options.families.end()) {
      chosen.push_back(&family);
    }
  }
  for (const std::string& name : options.families) {
    if (!known.count(name)) {
      std::string names;
      for (const std::string& k : known) names += (names.empty() ? "" : ", ") + k;
      throw InputError("bench families: unknown family \"" + name + "\" (families: " + names + ")");
    }
  }
  return chosen;
}

/// An instance of `family` on a tabletop of `desk`: draws until the family accepts the scene.
/// Nullopt when no draw of kDraws fits the part of the desk the robot's arm reaches (a short arm).
/// Draws are cheap (objects are built once their footprints fit), so families whose scenes are
/// rare (a corner clear of the bowl closest to it) still get theirs.
constexpr int kDraws = 2000;
std::optional<FamilyInstance> drawInstance(const InstructionFamily& family, const Scene& desk, Random& random) {
  for (int attempt = 0; attempt < kDraws; ++attempt) {
    if (std::optional<FamilyInstance> instance = family.make(desk, random)) return instance;
  }
  return std::nullopt;
}

/// A family no scene of which fits a robot's reach: left out of the figures, and said so.
struct SkippedFamily {
  std::string family;
  std::string problem;
  std::string why;
};

nlohmann::json outcomesJson(const std::map<std::string, FamilyTally>& figures, const std::vector<InstanceOutcome>& outcomes,
                            const std::vector<SkippedFamily>& skipped) {
  nlohmann::json families = nlohmann::json::object();
  for (const auto& [name, f] : figures) {
    families[name] = {{"instances", f.instances}, {"understood", f.understood}, {"executed_first_round", f.firstRound},
                      {"executed_after_repair", f.afterRepair}, {"plan_given", f.givenPlan},
                      {"seconds_median", percentile(f.seconds, 0.5)}, {"seconds_p95", percentile(f.seconds, 0.95)}};
  }
  nlohmann::json failures = nlohmann::json::array();
  for (const InstanceOutcome& o : outcomes) {
    if (o.afterRepair && o.givenPlan) continue;
    failures.push_back({{"family", o.family}, {"problem", o.problem}, {"instruction", o.instruction},
                        {"offline", o.afterRepair ? "" : o.why}, {"plan_given", o.givenPlan ? "" : o.givenWhy}});
  }
  nlohmann::json left = nlohmann::json::array();
  for (const SkippedFamily& s : skipped) left.push_back({{"family", s.family}, {"problem", s.problem}, {"why", s.why}});
  return {{"families", families}, {"failures", failures}, {"skipped", left}};
}

void runBench(const BenchFamiliesOptions& options, std::ostream& out) {
  if (options.scenesPerProblem < 1) throw InputError("bench families: --scenes must be >= 1");
  if (options.seed < 0) throw InputError("bench families: --seed must be >= 0");
  const std::vector<const InstructionFamily*> families = familiesToRun(options);
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(options.seed));
  std::vector<InstanceOutcome> outcomes;
  std::vector<SkippedFamily> skipped;
  for (const std::string& name : problemsToRun(options)) {
    const LoadedProblem loaded = loadProblem(name, "", SceneOptions{});
    for (const InstructionFamily* family : families) {
      Random random(static_cast<std::uint64_t>(options.seed) * 7919u + std::hash<std::string>{}(family->name) % 1000u);
      for (int i = 0; i < options.scenesPerProblem; ++i) {
        const std::optional<FamilyInstance> instance = drawInstance(*family, loaded.problem.scene, random);
        if (!instance) {
          const AlignedBox3 reach = deskReach(loaded.problem.scene);
          char size[64];
          std::snprintf(size, sizeof size, "%.0f x %.0f cm", reach.sizes().x() * 100.0, reach.sizes().y() * 100.0);
          skipped.push_back({family->name, loaded.name, "no draw of " + std::to_string(kDraws) + " on the " + std::string(size) + " of the desk " +
                                                             actingArm(loaded.problem.scene) + " reaches gives a scene to ask it on"});
          break;
        }
        outcomes.push_back(runInstance(*instance, loaded.name, options.seed, options.given));
      }
    }
  }
  std::map<std::string, FamilyTally> figures;
  FamilyTally all;
  for (const InstanceOutcome& o : outcomes) {
    addTo(figures[o.family], o);
    addTo(all, o);
  }
  if (options.json) {
    out << outcomesJson(figures, outcomes, skipped).dump(2) << '\n';
    return;
  }
  out << "bench families: " << families.size() << " families x " << problemsToRun(options).size() << " problem(s) x "
      << options.scenesPerProblem << " generated scenes (seed " << options.seed << ")\n";
  out << "family                         cases  understood  first round  after repair  plan given  median ms\n";
  for (const InstructionFamily* family : families) out << row(family->name, figures[family->name], options.given);
  out << row("all", all, options.given);
  for (const SkippedFamily& s : skipped) out << "  left out: " << s.family << " on " << s.problem << ": " << s.why << '\n';
  int shown = 0;
  for (const InstanceOutcome& o : outcomes) {
    if (o.afterRepair || shown++ >= options.failuresShown) continue;
    out << "  " << o.problem << " [" << o.family << "] \"" << o.instruction << "\": " << o.why.substr(0, 240) << '\n';
  }
  shown = 0;
  for (const InstanceOutcome& o : outcomes) {
    if (!options.given || o.givenPlan || shown++ >= options.failuresShown) continue;
    out << "  plan given: " << o.problem << " [" << o.family << "] \"" << o.instruction << "\": " << o.givenWhy.substr(0, 240) << '\n';
  }
}

}  // namespace
}  // namespace families_bench

void addBenchFamiliesCommand(CLI::App& bench, std::ostream& out) {
  using namespace families_bench;
  auto options = std::make_shared<BenchFamiliesOptions>();
  CLI::App* command = bench.add_subcommand(
      "families", "The instruction families of Code as Policies' tabletop and CLIPort/Ravens on generated tabletops of every built-in "
                  "robot: per family the share understood, executed and verified (first round, after repair) and with the plan given");
  command->add_option("--families", options->families, "Only these families (default: all)")->delimiter(',');
  command->add_option("--problems", options->problems, "Desk problems to generate on (default: every built-in problem)")->delimiter(',');
  command->add_option("--scenes", options->scenesPerProblem, "Generated scenes per family and problem")->capture_default_str();
  command->add_option("--seed", options->seed, "Random seed")->capture_default_str();
  command->add_flag("!--no-given", options->given, "Skip the runs with the plan given");
  command->add_option("--failures", options->failuresShown, "Failures to list")->capture_default_str();
  command->add_flag("--json", options->json, "Print the figures and every failure as JSON");
  command->callback([options, &out] { runBench(*options, out); });
}

}  // namespace lang2manip
