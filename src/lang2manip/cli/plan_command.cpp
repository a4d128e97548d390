#include "lang2manip/cli/commands.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/symbolic/llm_task_planner.hpp"
#include "lang2manip/symbolic/plan_prompt.hpp"

namespace lang2manip {
namespace {

struct PlanOptions {
  std::string problem;
  std::string robot = "panda";
  std::string task;
  bool printPrompt = false;
};

void printPrompt(const PlanOptions& options, std::ostream& out) {
  if (options.task.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw InputError("plan: --task is required and must not be empty (e.g. --task \"put the marker in the holder\")");
  }
  const LoadedProblem loaded = loadProblem(options.problem, options.robot);
  PlanningRequest request;
  request.task = options.task;
  request.scene = &loaded.problem.scene;
  const LlmRequest llm = buildPlanRequest(request, LlmTaskPlannerOptions{});
  out << renderPrompt(llm.system, llm.messages);
}

}  // namespace

void addPlanCommand(CLI::App& app, std::ostream& out) {
  auto options = std::make_shared<PlanOptions>();
  CLI::App* command = app.add_subcommand("plan", "Plan a task given in plain language (now: --print-prompt)");
  command->add_option("PROBLEM", options->problem,
                      "Built-in problem name, Kautham problem .xml, or MoveIt scene .yaml (default: " +
                          defaultProblemName() + ")");
  command->add_option("--robot", options->robot, "Built-in robot for MoveIt scenes")->capture_default_str();
  command->add_option("--task", options->task, "The instruction, e.g. \"put the marker and eraser in the holder\"");
  command->add_flag("--print-prompt", options->printPrompt,
                    "Print the prompt a task planner receives (system prompt, task, observation) and exit");
  command->callback([options, &out] {
    if (!options->printPrompt) {
      throw NotSupportedError(
          "plan: running a task planner from this command is not available yet; use --print-prompt to "
          "see the prompt planners receive");
    }
    printPrompt(*options, out);
  });
}

}  // namespace lang2manip
