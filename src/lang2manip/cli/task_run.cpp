#include "lang2manip/cli/task_run.hpp"

#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"

namespace lang2manip {
namespace {

void chooseGoals(const std::string& task, const Scene& scene, const std::string& robot, TaskRun& run) {
  try {
    run.goals = understandInstruction(task, describeObjects(scene, robot)).goals;
    run.goalSource = "instruction";
    return;
  } catch (const PlanningError&) {
  }
  run.goalSource = "plan";
  if (run.repair.plan) run.goals = goalsImpliedByPlan(*run.repair.plan);
}

}  // namespace

TaskRun planExecuteAndVerify(TaskPlanner& planner, TaskExecutor& executor, const std::string& task, int rounds) {
  const Scene& scene = executor.initialScene();
  PlanningRequest request;
  request.task = task;
  request.scene = &scene;
  request.robot = executor.arm().robotName();
  RepairOptions options;
  options.maxRounds = rounds;
  TaskRun run;
  run.repair = planWithRepair(planner, request, &executor, options, StopCondition::never());
  chooseGoals(task, scene, request.robot, run);
  if (!executor.executions().empty()) {
    run.verification = verifyExecution(executor.arm(), scene, executor.lastExecution(), run.goals);
  }
  return run;
}

}  // namespace lang2manip
