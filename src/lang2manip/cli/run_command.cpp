// `lang2manip run`: instruction -> plan -> grounded, executed and verified trajectories.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <ompl/util/RandomNumbers.h>

#include "lang2manip/cli/commands.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/cli/run_report.hpp"
#include "lang2manip/cli/task_planner_choice.hpp"
#include "lang2manip/cli/task_run.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/execution/task_executor.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/planning/planner_registry.hpp"
#include "lang2manip/symbolic/llm_task_planner.hpp"
#include "lang2manip/symbolic/observation.hpp"
#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/plan_prompt.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kPaperTask = "put the marker and eraser in the holder";

struct RunOptions {
  std::string problem;
  std::string robot = "panda";
  SceneOptions scene;
  std::string arm;
  std::string task = kPaperTask;
  TaskPlannerChoice planner;
  std::string motionPlanner;
  std::string ik;
  int rounds = RepairOptions{}.maxRounds;
  long seed = 1;
  double timeLimit = ExecutionSettings{}.planningTimeSeconds;
  double ikTimeout = ExecutionSettings{}.reach.ikTimeoutSeconds;
  std::string out = "lang2manip-run";
  bool json = false;
};

void checkOptions(const RunOptions& options) {
  if (options.task.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw InputError("run: --task must not be empty (e.g. --task \"" + std::string(kPaperTask) + "\")");
  }
  if (options.rounds < 1) throw InputError("run: --rounds " + std::to_string(options.rounds) + ": must be at least 1");
  if (options.seed < 0) throw InputError("run: --seed " + std::to_string(options.seed) + ": must be >= 0");
  if (!(options.timeLimit > 0.0)) throw InputError("run: --time-limit must be a positive number of seconds");
  if (!(options.ikTimeout > 0.0)) throw InputError("run: --ik-timeout must be a positive number of seconds");
  if (options.out.empty()) throw InputError("run: --out must name a directory");
  if (!options.motionPlanner.empty()) (void)canonicalPlannerName(options.motionPlanner);
}

ExecutionSettings executionSettings(const RunOptions& options) {
  ExecutionSettings settings;
  settings.manipulator = options.arm;
  if (!options.motionPlanner.empty()) settings.defaultPlanner = options.motionPlanner;
  if (!options.ik.empty()) settings.ikSolver = options.ik;
  settings.seed = static_cast<std::uint64_t>(options.seed);
  settings.planningTimeSeconds = options.timeLimit;
  settings.reach.ikTimeoutSeconds = options.ikTimeout;
  return settings;
}

/// The output directory, created; an existing file of that name is an error.
fs::path prepareOutput(const std::string& directory) {
  const fs::path path(directory);
  std::error_code error;
  if (fs::exists(path, error) && !fs::is_directory(path, error)) {
    throw InputError("run: --out " + directory + ": exists and is not a directory");
  }
  fs::create_directories(path, error);
  if (error) throw InputError("run: --out " + directory + ": cannot create the directory: " + error.message());
  return path;
}

void writeFile(const fs::path& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary);
  file << text;
  file.close();
  if (!file) throw InputError("run: cannot write " + path.string());
}

void writeInputs(const fs::path& out, const RunOptions& options, const Scene& scene, const std::string& robot,
                 double& observationSeconds) {
  const auto began = Clock::now();
  ObservationOptions observe;
  observe.robot = robot;
  const nlohmann::json observation = observeEnvironment(scene, observe);
  observationSeconds = secondsSince(began);
  writeFile(out / "observation.json", observation.dump(2) + "\n");
  writeFile(out / "observation.txt", observationText(observation));
  PlanningRequest request;
  request.task = options.task;
  request.scene = &scene;
  request.robot = robot;
  const LlmRequest llm = buildPlanRequest(request, defaultLlmTaskPlannerOptions());
  writeFile(out / "prompt.txt", renderPrompt(llm.system, llm.messages));
}

void writeOutputs(const fs::path& out, const RunOutcome& outcome) {
  const Plan* plan = outcome.repair.plan ? &*outcome.repair.plan : nullptr;
  if (plan == nullptr && !outcome.repair.rounds.empty() && outcome.repair.rounds.back().plan) {
    plan = &*outcome.repair.rounds.back().plan;
  }
  if (plan != nullptr) writeFile(out / "plan.json", toJson(*plan).dump(2) + "\n");
  if (outcome.execution != nullptr) {
    writeFile(out / "trajectory.json", runTrajectoryJson(*outcome.execution).dump(2) + "\n");
    writeFile(out / "trajectory.csv", runTrajectoryCsv(*outcome.execution));
  }
  writeFile(out / "report.json", runReportJson(outcome).dump(2) + "\n");
}

void runTask(const RunOptions& options, std::ostream& out) {
  const auto began = Clock::now();
  checkOptions(options);
  const LoadedProblem loaded = loadProblem(options.problem, options.robot, options.scene);
  const Scene& scene = loaded.problem.scene;
  TaskExecutor executor(scene, executionSettings(options));
  const SelectedTaskPlanner selected = makeTaskPlanner(options.planner);
  const fs::path directory = prepareOutput(options.out);
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(options.seed));

  RunOutcome outcome;
  outcome.problem = loaded.name;
  outcome.task = options.task;
  outcome.taskPlanner = selected.label();
  outcome.robot = executor.arm().robotName();
  outcome.manipulator = executor.arm().manipulator().name;
  outcome.seed = options.seed;
  writeInputs(directory, options, scene, outcome.robot, outcome.observationSeconds);

  TaskRun run = planExecuteAndVerify(selected.planner(), executor, options.task, options.rounds);
  outcome.repair = std::move(run.repair);
  outcome.goals = std::move(run.goals);
  outcome.goalSource = std::move(run.goalSource);
  outcome.verification = std::move(run.verification);
  outcome.executions = &executor.executions();
  if (!executor.executions().empty()) outcome.execution = &executor.lastExecution();
  outcome.totalSeconds = secondsSince(began);
  writeOutputs(directory, outcome);
  if (options.json) {
    out << runReportJson(outcome).dump(2) << '\n';
  } else {
    out << runSummary(outcome) << "  wrote " << directory.string() << "/ (plan.json, trajectory.json, trajectory.csv, report.json)\n";
  }
  if (!outcome.success()) throw TaskFailedError("run: the task did not succeed; see " + (directory / "report.json").string());
}

}  // namespace

void addRunCommand(CLI::App& app, std::ostream& out) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* command = app.add_subcommand(
      "run", "Plan a task given in plain language, ground every action into grasps, IK and motions, execute and "
             "verify it, and write the plan, trajectories and a report");
  command->add_option("PROBLEM", options->problem,
                      "Built-in problem name, Kautham problem .xml, or MoveIt scene .yaml (default: " + defaultProblemName() + ")");
  addTaskOption(*command, options->task, "The instruction")->capture_default_str();
  addTaskPlannerOptions(*command, options->planner);
  command->add_option("--planner", options->motionPlanner,
                      "Motion planner of the actions that name none (OMPL or Kautham name; default RRTConnect)");
  command->add_option("--ik", options->ik, "IK solver (dls, kdl, kdl_restarts; default dls)");
  command->add_option("--robot", options->robot, "Built-in robot for MoveIt scenes")->capture_default_str();
  addSceneOptions(*command, options->scene);
  command->add_option("--arm", options->arm, "The arm (manipulator) that executes the task (default: the robot's first)");
  command->add_option("--rounds", options->rounds, "Task planner rounds at most (repairs included)")->capture_default_str();
  command->add_option("--seed", options->seed, "Random seed of planners, IK restarts and placement samples")->capture_default_str();
  command->add_option("--time-limit", options->timeLimit, "Seconds one motion query may take")->capture_default_str();
  command->add_option("--ik-timeout", options->ikTimeout, "Seconds of IK search per pose")->capture_default_str();
  command->add_option("--out", options->out, "Output directory")->capture_default_str();
  command->add_flag("--json", options->json, "Print the report (report.json) to standard output instead of the summary");
  command->callback([options, &out] { runTask(*options, out); });
}

}  // namespace lang2manip
