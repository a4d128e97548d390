#include "lang2manip/cli/task_run.hpp"

#include <chrono>
#include <fstream>
#include <sstream>

#include <ompl/util/RandomNumbers.h>

#include "lang2manip/cli/run_page.hpp"
#include "lang2manip/cli/run_report.hpp"
#include "lang2manip/cli/run_scene.hpp"
#include "lang2manip/cli/trajectory_outputs.hpp"
#include "lang2manip/core/file_checks.hpp"
#include "lang2manip/core/json_limits.hpp"
#include "lang2manip/grounding/gripper_geometry.hpp"
#include "lang2manip/kinematics/ik_solver.hpp"
#include "lang2manip/planning/planner_catalog.hpp"
#include "lang2manip/language/instruction.hpp"
#include "lang2manip/symbolic/given_plan_planner.hpp"
#include "lang2manip/symbolic/plan_parser.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/symbolic/llm_task_planner.hpp"
#include "lang2manip/symbolic/observation.hpp"
#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/plan_validation.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"
#include "lang2manip/symbolic/plan_prompt.hpp"

namespace lang2manip {
namespace {

using Clock = std::chrono::steady_clock;

void chooseGoals(const std::string& task, const Scene& scene, const std::string& robot, const std::string& arm, TaskRun& run) {
  try {
    if (task.empty()) throw PlanningError("no instruction");
    run.goals = understandInstruction(task, describeObjects(scene, robot, arm)).goals;
    run.goalSource = "instruction";
    return;
  } catch (const PlanningError&) {
  }
  if (run.repair.plan && !run.repair.plan->goals.empty()) {
    run.goals = run.repair.plan->goals;
    run.goalSource = "plan_goal_statement";
    return;
  }
  run.goalSource = "plan";
  if (run.repair.plan) run.goals = goalsImpliedByPlan(*run.repair.plan);
}

ExecutionSettings executionSettings(const RunRequest& request, const RunScaling& scaling) {
  ExecutionSettings settings;
  settings.manipulator = request.arm;
  if (!request.motionPlanner.empty()) settings.defaultPlanner = request.motionPlanner;
  if (!request.ik.empty()) settings.ikSolver = request.ik;
  settings.seed = static_cast<std::uint64_t>(request.seed);
  settings.planningTimeSeconds = request.timeLimit;
  settings.reach.ikTimeoutSeconds = request.ikTimeout;
  if (request.recordTree) settings.recordTreeEdges = kRecordedTreeEdges;
  settings.timing = request.timing;
  settings.velocityScaling = scaling.velocity;
  settings.accelerationScaling = scaling.acceleration;
  settings.positionMargin = scaling.positionMargin;
  return settings;
}

void observe(const RunRequest& request, const Scene& scene, const std::string& robot, const std::string& arm,
             RunDocuments& documents, double& observationSeconds) {
  const auto began = Clock::now();
  ObservationOptions options;
  options.robot = robot;
  options.arm = arm;
  documents.observation = observeEnvironment(scene, options);
  observationSeconds = secondsSince(began);
  documents.observationText = observationText(documents.observation);
  PlanningRequest planning;
  planning.task = request.task;
  planning.scene = &scene;
  planning.robot = robot;
  planning.arm = arm;
  const LlmRequest llm = buildPlanRequest(planning, defaultLlmTaskPlannerOptions());
  documents.prompt = renderPrompt(llm.system, llm.messages);
}

/// The plan of `file` for `scene`: object and planner names checked. Throws InputError naming
/// the file and every problem.
/// Where `request`'s plan document comes from, for messages and the report: "plan file F" or
/// "plan on standard input".
std::string planSource(const RunRequest& request) {
  return (request.planText ? "plan on " : "plan file ") + request.planFile;
}

/// The plan of `request`'s plan document (the file, or the text it carries), its names checked
/// against `scene`. The document must be JSON, nothing around it (unlike an LLM's answer).
Plan readPlanDocument(const RunRequest& request, const Scene& scene, const std::string& robot, const std::string& arm) {
  const std::string name = planSource(request);
  std::string text;
  if (request.planText) {
    text = *request.planText;
  } else {
    requireRegularFile(request.planFile, "plan file");
    std::ifstream in(request.planFile, std::ios::binary);
    std::ostringstream content;
    content << in.rdbuf();
    text = content.str();
  }
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw InputError(name + " is empty; expected a JSON plan document");
  const nlohmann::json document = parseJsonWithinLimits(text, JsonLimits{}, name);
  PlanParseContext context;
  for (const SceneObject& object : scene.objects()) context.objects.push_back(object.name);
  context.planners = defaultLlmTaskPlannerOptions().plannerNames;
  Plan plan;
  try {
    plan = parsePlan(document, context);
  } catch (const PlanParseError& error) {
    throw InputError(name + " is not a plan for this scene:\n" + error.what());
  }
  const PlanValidation validation = validatePlan(plan, observeSymbolicState(scene, {}, robot, arm));
  if (!validation.valid()) throw InputError(name + " cannot be executed in this scene:\n" + validation.summary());
  return plan;
}

/// The task planner of `request`: the plan file's plan, or the chosen planner.
SelectedTaskPlanner taskPlannerFor(const RunRequest& request, const Scene& scene, const std::string& robot,
                                   const std::string& arm) {
  if (request.planFile.empty()) return makeTaskPlanner(request.planner);
  if (!request.planner.offline()) throw InputError("run: --plan executes the given plan; --llm chooses a task planner: give one of them");
  const std::string source = planSource(request);
  return SelectedTaskPlanner(nullptr, std::make_unique<GivenPlanTaskPlanner>(readPlanDocument(request, scene, robot, arm), source), source);
}

/// The accepted plan, else the last one that was parsed.
const Plan* planOf(const RepairResult& repair) {
  if (repair.plan) return &*repair.plan;
  if (!repair.rounds.empty() && repair.rounds.back().attempt.plan) return &*repair.rounds.back().attempt.plan;
  return nullptr;
}

}  // namespace

TaskRun planExecuteAndVerify(TaskPlanner& planner, TaskExecutor& executor, const std::string& task, int rounds,
                             const RunControl& control) {
  const Scene& scene = executor.initialScene();
  PlanningRequest request;
  request.task = task;
  request.scene = &scene;
  request.robot = executor.arm().robotName();
  request.arm = executor.arm().manipulator().name;
  RepairOptions options;
  options.maxRounds = rounds;
  options.progress = control.progress;
  executor.setProgressSink(control.progress);
  TaskRun run;
  run.repair = planWithRepair(planner, request, &executor, options, control.stop);
  executor.setProgressSink({});
  chooseGoals(task, scene, request.robot, request.arm, run);
  if (!executor.executions().empty()) {
    report(control.progress, {ProgressStage::kVerify, 0, -1, "", ""});
    run.verification = verifyExecution(executor.arm(), scene, executor.lastExecution(), run.goals);
  }
  return run;
}

void checkRunNames(const RunRequest& request, const Scene& scene) {
  const auto checked = [](const char* field, const auto& check) {
    try {
      check();
    } catch (const InputError& error) {
      throw RunNameError(field, error.what());
    }
  };
  checked("planner", [&] {
    if (!request.motionPlanner.empty()) (void)canonicalPlannerName(request.motionPlanner);
  });
  checked("ik", [&] { (void)makeIkSolver(request.ik.empty() ? defaultIkSolverName() : request.ik); });
  checked("arm", [&] {
    if (scene.robots().empty()) throw InputError("the scene has no robot");
    (void)findManipulator(*scene.robots().front().model, request.arm);
  });
}

std::string checkRunNames(const RunRequest& request) {
  const LoadedProblem loaded = loadProblem(request.problem, request.robot, request.scene);
  checkRunNames(request, loaded.problem.scene);
  return loaded.name;
}

RunDocuments runTask(const RunRequest& request, const RunControl& control) {
  const auto began = Clock::now();
  const LoadedProblem loaded = loadProblem(request.problem, request.robot, request.scene);
  const Scene& scene = loaded.problem.scene;
  checkRunNames(request, scene);
  const RunScaling scaling = chooseRunScaling(request, *scene.robots().front().model);
  TaskExecutor executor(scene, executionSettings(request, scaling));
  const SelectedTaskPlanner selected = taskPlannerFor(request, scene, executor.arm().robotName(), executor.arm().manipulator().name);
  if (control.seedOmpl) ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(request.seed));

  RunOutcome outcome;
  outcome.problem = loaded.name;
  outcome.task = request.task.empty() ? "plan file " + request.planFile : request.task;
  outcome.taskPlanner = selected.label();
  outcome.robot = executor.arm().robotName();
  outcome.manipulator = executor.arm().manipulator().name;
  outcome.seed = request.seed;
  outcome.timing = trajectoryTimingName(request.timing);
  outcome.scaling = scaling;
  RunDocuments documents;
  report(control.progress, {ProgressStage::kObserve, 0, -1, "", outcome.robot});
  observe(request, scene, outcome.robot, outcome.manipulator, documents, outcome.observationSeconds);

  TaskRun run = planExecuteAndVerify(selected.planner(), executor, request.task, request.planFile.empty() ? request.rounds : 1, control);
  outcome.repair = std::move(run.repair);
  outcome.goals = std::move(run.goals);
  outcome.goalSource = std::move(run.goalSource);
  outcome.verification = std::move(run.verification);
  outcome.executions = &executor.executions();
  if (!executor.executions().empty()) outcome.execution = &executor.lastExecution();
  outcome.totalSeconds = secondsSince(began);

  if (const Plan* plan = planOf(outcome.repair)) documents.plan = toJson(*plan);
  if (outcome.execution != nullptr) {
    const TrajectoryJoints joints = trajectoryJoints(executor.arm());
    documents.trajectory = runTrajectoryJson(*outcome.execution, joints);
    documents.trajectoryCsv = runTrajectoryCsv(*outcome.execution, joints);
    documents.robotTrajectory = moveItRobotTrajectory(*outcome.execution, joints);
    if (!joints.gripper.empty()) {
      documents.gripperTrajectory = gripperJointTrajectory(*outcome.execution, joints);
      documents.gripperEvents = gripperEvents(*outcome.execution, joints);
    }
  }
  documents.report = runReportJson(outcome);
  documents.summary = runSummary(outcome);
  documents.success = outcome.success();
  documents.sceneGlb = runSceneGlb(scene, executor.arm(), outcome.execution);
  documents.viewerDocument = viewerRunDocument(request.task, documents.report, outcome.execution, outcome.robot,
                                               documents.observationText, documents.prompt);
  return documents;
}

std::vector<std::pair<std::string, std::string>> motionDocuments(const RunDocuments& documents) {
  std::vector<std::pair<std::string, std::string>> files;
  if (!documents.trajectory) return files;
  files.emplace_back("trajectory.json", documents.trajectory->dump(2) + "\n");
  files.emplace_back("trajectory.csv", documents.trajectoryCsv);
  files.emplace_back("robot_trajectory.json", documents.robotTrajectory.dump(1) + "\n");
  if (documents.gripperTrajectory) {
    files.emplace_back("gripper_trajectory.json", documents.gripperTrajectory->dump(1) + "\n");
    files.emplace_back("gripper_events.json", documents.gripperEvents.dump(2) + "\n");
  }
  return files;
}

std::string trajectoryDocumentName(const std::string& name, bool success) { return success ? name : "partial_" + name; }

RunScaling chooseRunScaling(const RunRequest& request, const RobotModel& robot) {
  RunScaling scaling;
  const auto choose = [&](const std::optional<double>& requested, const std::optional<double>& robotDefault, double& value,
                          std::string& source) {
    if (requested) {
      value = *requested;
      source = "request";
    } else if (request.fullSpeed) {
      value = 1.0;
      source = "full speed";
    } else if (robotDefault) {
      value = *robotDefault;
      source = "joint_limits.yaml";
    }
  };
  choose(request.velocityScaling, robot.scalingDefaults().velocity, scaling.velocity, scaling.velocitySource);
  choose(request.accelerationScaling, robot.scalingDefaults().acceleration, scaling.acceleration, scaling.accelerationSource);
  if (request.fullSpeed) scaling.positionMargin = PositionMargin{0.0, 0.0};
  return scaling;
}

}  // namespace lang2manip
