// `lang2manip bench instructions`: an instruction corpus (data/corpus/instructions.tsv) run on the
// desk of every built-in robot through the offline planner, the executor and verification. Per
// class: the share of "execute" instructions executed and verified in the first round and after
// repair, the share of "refuse" instructions refused with nothing moved, and the time per
// instruction (median, p95). The "any_pose" class runs on scenes with the objects moved and
// turned at random (seeded), the others on the scenes as they are.

#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
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
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/language/instruction_corpus.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/model/builtin_data.hpp"

namespace lang2manip {
namespace {

using Clock = std::chrono::steady_clock;

struct BenchInstructionsOptions {
  std::string corpus;
  std::vector<std::string> problems;
  std::string group;
  double spread = 0.15;
  double turn = 3.14;
  long seed = 1;
  int failuresShown = 10;
  bool json = false;
};

/// What became of one instruction on one problem.
struct InstructionOutcome {
  std::string problem;
  const CorpusInstruction* entry = nullptr;
  bool correct = false;
  bool firstRound = false;
  double seconds = 0.0;
  std::string why;
};

bool movedAnything(const TaskExecutor& executor) {
  for (const ExecutionRecord& record : executor.executions()) {
    for (const ActionExecution& action : record.actions) {
      if (action.status == ActionStatus::kSucceeded) return true;
    }
  }
  return false;
}

std::string failureOf(const TaskRun& run) {
  if (!run.repair.succeeded()) return run.repair.failure;
  if (!run.verification.collision.empty()) return "collision: " + run.verification.collision;
  if (!run.verification.disturbedObjects.empty()) return "disturbed: " + run.verification.disturbedObjects.front();
  for (const GoalOutcome& goal : run.verification.goals) {
    if (!goal.holds) return goal.explanation;
  }
  return "not verified";
}

InstructionOutcome runInstruction(const Scene& scene, const CorpusInstruction& entry, long seed) {
  InstructionOutcome outcome;
  outcome.entry = &entry;
  const auto began = Clock::now();
  ExecutionSettings settings;
  settings.seed = static_cast<std::uint64_t>(seed);
  TaskExecutor executor(scene, settings);
  OfflineTaskPlanner planner;
  const TaskRun run = planExecuteAndVerify(planner, executor, entry.instruction, RepairOptions{}.maxRounds);
  outcome.seconds = secondsSince(began);
  if (entry.expect == CorpusExpectation::kExecute) {
    outcome.correct = run.success();
    outcome.firstRound = outcome.correct && run.repair.rounds.size() == 1;
    if (!outcome.correct) outcome.why = failureOf(run);
  } else {
    outcome.correct = !run.success() && !movedAnything(executor);
    if (!outcome.correct) outcome.why = run.success() ? "executed and verified, but should be refused" : "moved objects before failing: " + failureOf(run);
  }
  return outcome;
}

/// Figures of one class.
struct ClassFigures {
  int execute = 0, executedFirstRound = 0, executedAfterRepair = 0;
  int refuse = 0, refusedCleanly = 0;
  std::vector<double> seconds;
};

std::map<std::string, ClassFigures> tally(const std::vector<InstructionOutcome>& outcomes) {
  std::map<std::string, ClassFigures> figures;
  for (const InstructionOutcome& outcome : outcomes) {
    ClassFigures& f = figures[outcome.entry->group];
    f.seconds.push_back(outcome.seconds);
    if (outcome.entry->expect == CorpusExpectation::kExecute) {
      ++f.execute;
      f.executedFirstRound += outcome.firstRound ? 1 : 0;
      f.executedAfterRepair += outcome.correct ? 1 : 0;
    } else {
      ++f.refuse;
      f.refusedCleanly += outcome.correct ? 1 : 0;
    }
  }
  return figures;
}

double share(int part, int whole) { return whole == 0 ? 0.0 : 100.0 * part / whole; }

void printTable(const std::map<std::string, ClassFigures>& figures, std::ostream& out) {
  out << "class            execute  first round  after repair   refuse  refused cleanly   median ms   p95 ms\n";
  ClassFigures all;
  for (const auto& [group, f] : figures) {
    char line[256];
    std::snprintf(line, sizeof line, "%-16s %7d  %10.1f%%  %11.1f%%  %7d  %14.1f%%  %10.1f  %7.1f\n", group.c_str(), f.execute,
                  share(f.executedFirstRound, f.execute), share(f.executedAfterRepair, f.execute), f.refuse,
                  share(f.refusedCleanly, f.refuse), 1000.0 * percentile(f.seconds, 0.5), 1000.0 * percentile(f.seconds, 0.95));
    out << line;
    all.execute += f.execute;
    all.executedFirstRound += f.executedFirstRound;
    all.executedAfterRepair += f.executedAfterRepair;
    all.refuse += f.refuse;
    all.refusedCleanly += f.refusedCleanly;
    all.seconds.insert(all.seconds.end(), f.seconds.begin(), f.seconds.end());
  }
  char line[256];
  std::snprintf(line, sizeof line, "%-16s %7d  %10.1f%%  %11.1f%%  %7d  %14.1f%%  %10.1f  %7.1f\n", "all", all.execute,
                share(all.executedFirstRound, all.execute), share(all.executedAfterRepair, all.execute), all.refuse,
                share(all.refusedCleanly, all.refuse), 1000.0 * percentile(all.seconds, 0.5), 1000.0 * percentile(all.seconds, 0.95));
  out << line;
}

nlohmann::json outcomesJson(const std::vector<InstructionOutcome>& outcomes, const std::map<std::string, ClassFigures>& figures) {
  nlohmann::json classes = nlohmann::json::object();
  for (const auto& [group, f] : figures) {
    classes[group] = {{"execute", f.execute},
                      {"executed_first_round", f.executedFirstRound},
                      {"executed_after_repair", f.executedAfterRepair},
                      {"refuse", f.refuse},
                      {"refused_cleanly", f.refusedCleanly},
                      {"seconds_median", percentile(f.seconds, 0.5)},
                      {"seconds_p95", percentile(f.seconds, 0.95)}};
  }
  nlohmann::json failures = nlohmann::json::array();
  for (const InstructionOutcome& outcome : outcomes) {
    if (outcome.correct) continue;
    failures.push_back({{"problem", outcome.problem},
                        {"line", outcome.entry->line},
                        {"class", outcome.entry->group},
                        {"expect", corpusExpectationName(outcome.entry->expect)},
                        {"instruction", outcome.entry->instruction},
                        {"why", outcome.why}});
  }
  return {{"classes", classes}, {"failures", failures}};
}

std::vector<std::string> problemsToRun(const BenchInstructionsOptions& options) {
  if (!options.problems.empty()) return options.problems;
  std::vector<std::string> names;
  for (const BuiltinProblem& problem : builtinProblems()) names.push_back(problem.shortName);
  return names;
}

void runBench(const BenchInstructionsOptions& options, std::ostream& out) {
  if (!(options.spread >= 0.0) || !(options.turn >= 0.0)) throw InputError("bench instructions: --spread and --turn must be >= 0");
  if (options.seed < 0) throw InputError("bench instructions: --seed must be >= 0");
  const std::string file = options.corpus.empty() ? (builtinDataDirectory() / "corpus" / "instructions.tsv").string() : options.corpus;
  std::vector<CorpusInstruction> corpus = readInstructionCorpus(file);
  if (!options.group.empty()) {
    std::erase_if(corpus, [&](const CorpusInstruction& entry) { return entry.group != options.group; });
    if (corpus.empty()) throw InputError("bench instructions: no instruction of class \"" + options.group + "\" in " + file);
  }
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(options.seed));
  std::vector<InstructionOutcome> outcomes;
  ProgressDisplay progress("bench instructions", corpus.size() * problemsToRun(options).size(), "instructions");
  for (const std::string& name : problemsToRun(options)) {
    const LoadedProblem loaded = loadProblem(name, "", SceneOptions{});
    Random random(static_cast<std::uint64_t>(options.seed));
    for (const CorpusInstruction& entry : corpus) {
      std::optional<Scene> scene = loaded.problem.scene;
      if (entry.group == "any_pose") scene = randomizedScene(loaded.problem.scene, options.spread, options.turn, random);
      if (!scene) throw InputError("bench instructions: no random scene without overlaps for " + name);
      outcomes.push_back(runInstruction(*scene, entry, options.seed));
      outcomes.back().problem = loaded.name;
      progress.advance();
    }
  }
  progress.finish();
  const std::map<std::string, ClassFigures> figures = tally(outcomes);
  if (options.json) {
    out << outcomesJson(outcomes, figures).dump(2) << '\n';
    return;
  }
  out << "bench instructions: " << corpus.size() << " instructions of " << file << " on " << problemsToRun(options).size()
      << " problem(s); any_pose scenes: objects shifted up to " << options.spread << " m and turned up to " << options.turn
      << " rad (seed " << options.seed << ")\n";
  printTable(figures, out);
  int shown = 0;
  for (const InstructionOutcome& outcome : outcomes) {
    if (outcome.correct || shown++ >= options.failuresShown) continue;
    out << "  " << outcome.problem << " line " << outcome.entry->line << " [" << outcome.entry->group << ", "
        << corpusExpectationName(outcome.entry->expect) << "] \"" << outcome.entry->instruction << "\": " << outcome.why.substr(0, 240) << '\n';
  }
}

}  // namespace

void addBenchInstructionsCommand(CLI::App& bench, std::ostream& out) {
  auto options = std::make_shared<BenchInstructionsOptions>();
  CLI::App* command = bench.add_subcommand("instructions", "An instruction corpus on the built-in desks: per class, the share executed "
                                                           "and verified (first round, after repair) and refused cleanly");
  command->add_option("CORPUS", options->corpus, "Corpus file (class<TAB>expect<TAB>instruction; default: the built-in corpus)");
  command->add_option("--problems", options->problems, "Problems to run on (default: every built-in problem)")->delimiter(',');
  command->add_option("--class", options->group, "Only the instructions of this class");
  command->add_option("--spread", options->spread, "any_pose: largest shift of each movable object in x and y (m)")->capture_default_str();
  command->add_option("--turn", options->turn, "any_pose: largest turn of each movable object about z (rad)")->capture_default_str();
  command->add_option("--seed", options->seed, "Random seed")->capture_default_str();
  command->add_option("--failures", options->failuresShown, "Failures to list")->capture_default_str();
  command->add_flag("--json", options->json, "Print the figures and every failure as JSON");
  command->callback([options, &out] { runBench(*options, out); });
}

}  // namespace lang2manip
