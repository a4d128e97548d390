#include <cstdio>
#include <string>

#include "lang2manip/cli/commands.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/cli/task_planner_choice.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/plan_prompt.hpp"
#include "lang2manip/symbolic/repair_loop.hpp"

namespace lang2manip {
namespace {

struct PlanOptions {
  std::string problem;
  std::string robot;  ///< empty: the Panda for MoveIt scenes
  SceneOptions scene;
  std::string task;
  TaskPlannerChoice planner;
  int rounds = RepairOptions{}.maxRounds;
  bool json = false;
  bool printPrompt = false;
};

void checkOptions(const PlanOptions& options) {
  if (options.task.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw InputError("plan: --task is required and must not be empty (e.g. --task \"put the marker in the holder\")");
  }
  if (options.rounds < 1) {
    throw InputError("plan: --rounds " + std::to_string(options.rounds) + ": must be at least 1");
  }
}

void printPrompt(const PlanOptions& options, const Scene& scene, std::ostream& out) {
  PlanningRequest request;
  request.task = options.task;
  request.scene = &scene;
  const LlmRequest llm = buildPlanRequest(request, defaultLlmTaskPlannerOptions());
  out << renderPrompt(llm.system, llm.messages);
}

std::string roundsText(int used, int allowed) {
  return std::to_string(used) + (used == 1 ? " round" : " rounds") + " of " + std::to_string(allowed);
}

std::string statisticsText(const PlanningStatistics& statistics) {
  char times[128];
  std::snprintf(times, sizeof times, ", LLM time %.2f s, planning time %.1f ms", statistics.llmSeconds,
                statistics.planningSeconds * 1000.0);
  return "LLM calls: " + std::to_string(statistics.llmCalls) + ", tokens: " + tokenCountText(statistics.inputTokens) +
         " in / " + tokenCountText(statistics.outputTokens) + " out" + times;
}

/// The numbered actions, the repaired rounds (when any) and the counters.
void printPlanText(const std::string& task, const SelectedTaskPlanner& planner, const RepairResult& result,
                   int allowedRounds, std::ostream& out) {
  const Plan& plan = *result.plan;
  out << "plan for \"" << task << "\" by " << planner.label() << " (" << plan.actions.size()
      << (plan.actions.size() == 1 ? " action" : " actions") << "):\n";
  for (std::size_t index = 0; index < plan.actions.size(); ++index) {
    const SymbolicAction& action = plan.actions[index];
    out << "  " << index + 1 << ". " << describeAction(action);
    if (action.refinements.grasp != GraspDirection::kAuto) {
      out << " [" << graspDirectionName(action.refinements.grasp) << " grasp]";
    }
    if (!action.planner.empty()) out << " [planner " << action.planner << "]";
    out << '\n';
  }
  if (!plan.reasoning.empty()) out << "reasoning: " << plan.reasoning << '\n';
  for (const RepairRound& round : result.rounds) {
    if (round.outcome == RoundOutcome::kAccepted) continue;
    out << "round " << round.round << " rejected (" << roundOutcomeName(round.outcome) << "): " << round.attempt.failure
        << '\n';
  }
  out << "rounds: " << roundsText(static_cast<int>(result.rounds.size()), allowedRounds) << "; "
      << statisticsText(result.statistics) << '\n';
}

void runPlanner(const PlanOptions& options, const Scene& scene, std::ostream& out) {
  const SelectedTaskPlanner selected = makeTaskPlanner(options.planner);
  PlanningRequest request;
  request.task = options.task;
  request.scene = &scene;
  RepairOptions repair;
  repair.maxRounds = options.rounds;
  const RepairResult result = planWithRepair(selected.planner(), request, nullptr, repair, StopCondition::never());
  // As `run` does for the same failure: the command ran and its task could not be done (exit 2).
  if (!result.succeeded()) throw TaskFailedError("plan: " + result.failure);
  if (options.json) {
    out << toJson(*result.plan).dump(2) << '\n';
  } else {
    printPlanText(options.task, selected, result, options.rounds, out);
  }
}

}  // namespace

void addPlanCommand(CLI::App& app, std::ostream& out) {
  auto options = std::make_shared<PlanOptions>();
  CLI::App* command = app.add_subcommand(
      "plan", "Plan a task given in plain language as symbolic actions (offline planner or an LLM), "
              "checked against the scene and repaired when invalid");
  command->add_option("PROBLEM", options->problem,
                      "Built-in problem name, Kautham problem .xml, or MoveIt scene .yaml (default: " +
                          defaultProblemName() + ")");
  command->add_option("--robot", options->robot, "Robot of a MoveIt scene: a built-in name or a .urdf/.xacro file (default: panda)");
  addSceneOptions(*command, options->scene);
  addTaskOption(*command, options->task, "The instruction, e.g. \"put the marker and eraser in the holder\"");
  addTaskPlannerOptions(*command, options->planner);
  command->add_option("--rounds", options->rounds, "Planner rounds at most (repairs included)")->capture_default_str();
  command->add_flag("--json", options->json, "Print the plan as JSON ({\"actions\":[...]}), as later stages read it");
  command->add_flag("--print-prompt", options->printPrompt,
                    "Print the prompt a task planner receives (system prompt, task, observation) and exit");
  command->callback([options, &out] {
    checkOptions(*options);
    const LoadedProblem loaded = loadProblem(options->problem, options->robot, options->scene);
    if (options->printPrompt) {
      printPrompt(*options, loaded.problem.scene, out);
    } else {
      runPlanner(*options, loaded.problem.scene, out);
    }
  });
}

}  // namespace lang2manip
