// `lang2manip run`: instruction -> plan -> grounded, executed and verified trajectories.

#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "lang2manip/cli/commands.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/cli/progress_display.hpp"
#include "lang2manip/cli/run_page.hpp"
#include "lang2manip/cli/task_planner_choice.hpp"
#include "lang2manip/cli/task_run.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/output_files.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/planning/planner_registry.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;

struct RunOptions {
  RunRequest request;
  std::string out = "lang2manip-out/run";
  bool force = false;
  bool keepPartial = false;
  double velocityScaling = 0.0;
  double accelerationScaling = 0.0;
  bool json = false;
  bool html = false;
  std::string timing = trajectoryTimingName(ExecutionSettings{}.timing);
};

/// The options' request, checked, with the timing named by --timing.
RunRequest checkedRequest(const RunOptions& options) {
  RunRequest request = options.request;
  try {
    request.timing = trajectoryTimingNamed(options.timing);
  } catch (const InputError& error) {
    throw InputError(std::string("run: --timing: ") + error.what());
  }
  if (request.planFile.empty() && request.task.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw InputError("run: --task must not be empty (e.g. --task \"" + std::string(kPaperTask) + "\")");
  }
  if (request.rounds < 1) throw InputError("run: --rounds " + std::to_string(request.rounds) + ": must be at least 1");
  if (request.seed < 0) throw InputError("run: --seed " + std::to_string(request.seed) + ": must be >= 0");
  if (!(request.timeLimit > 0.0)) throw InputError("run: --time-limit must be a positive number of seconds");
  if (!(request.ikTimeout > 0.0)) throw InputError("run: --ik-timeout must be a positive number of seconds");
  for (const auto& [value, flag] : {std::pair{request.velocityScaling, "--velocity-scaling"},
                                    std::pair{request.accelerationScaling, "--acceleration-scaling"}}) {
    if (!value) continue;
    if (const std::string problem = scalingProblem(*value); !problem.empty()) {
      throw InputError(std::string("run: ") + flag + " " + problem);
    }
  }
  if (!request.motionPlanner.empty()) (void)canonicalPlannerName(request.motionPlanner);
  return request;
}

/// Writes the run's documents into `set`; the names of the files written, in order. The motion
/// of a run that did not succeed is written only with `keepPartial`, under "partial_" names.
std::vector<std::string> writeDocuments(OutputDirectory& set, const RunDocuments& documents, bool keepPartial) {
  std::vector<std::string> written;
  const auto write = [&](const std::string& name, const std::string& text) {
    set.write(name, text);
    written.push_back(name);
  };
  write("observation.json", documents.observation.dump(2) + "\n");
  write("observation.txt", documents.observationText);
  write("prompt.txt", documents.prompt);
  if (documents.plan) write("plan.json", documents.plan->dump(2) + "\n");
  if (documents.success || keepPartial) {
    for (const auto& [name, text] : motionDocuments(documents)) write(trajectoryDocumentName(name, documents.success), text);
  }
  write("report.json", documents.report.dump(2) + "\n");
  write("scene.glb", documents.sceneGlb);
  write("viewer.json", documents.viewerDocument.dump(1) + "\n");
  return written;
}

/// runTask(), a bad name reported with its flag.
RunDocuments runTaskNamingFlags(const RunRequest& request) {
  RunControl control;
  control.progress = [](const ProgressEvent& event) { std::cerr << "run: " << runPhaseText(event) << '\n'; };
  try {
    return runTask(request, control);
  } catch (const RunNameError& error) {
    throw InputError("run: --" + error.field() + ": " + error.what());
  }
}

void runCommand(const RunOptions& options, std::ostream& out) {
  const RunRequest request = checkedRequest(options);
  // Before the long work: a missing viewer or an output directory that may not be replaced is an
  // error now, not after the run.
  const std::string viewer = options.html ? viewerScript() : "";
  OutputDirectory set(options.out, "run: --out", options.force);
  const RunDocuments documents = runTaskNamingFlags(request);
  std::vector<std::string> written = writeDocuments(set, documents, options.keepPartial);
  if (options.html) {
    set.write("run.html", runPageHtml(documents.viewerDocument, documents.sceneGlb, viewer));
    written.push_back("run.html");
  }
  set.commit();
  if (options.json) {
    out << documents.report.dump(2) << '\n';
  } else {
    std::string list;
    for (const std::string& name : written) list += (list.empty() ? "" : ", ") + name;
    out << documents.summary << "  wrote " << options.out << "/ (" << list << ")\n";
    if (!documents.success && documents.trajectory && !options.keepPartial) {
      out << "  no trajectory written: the task did not succeed (--keep-partial writes what was executed as "
             "partial_trajectory.json)\n";
    }
  }
  if (!documents.success) throw TaskFailedError("run: the task did not succeed; see " + (fs::path(options.out) / "report.json").string());
}

}  // namespace

void addRunCommand(CLI::App& app, std::ostream& out) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* command = app.add_subcommand(
      "run", "Plan a task given in plain language, ground every action into grasps, IK and motions, execute and "
             "verify it, and write the plan, trajectories and a report");
  command->add_option("PROBLEM", options->request.problem,
                      "Built-in problem name, Kautham problem .xml, or MoveIt scene .yaml (default: " + defaultProblemName() + ")");
  CLI::Option* task = addTaskOption(*command, options->request.task, "The instruction")->capture_default_str();
  command->add_option("--plan", options->request.planFile,
                      "Execute this plan document (the plan.json format; \"-\": read it from standard input) instead of "
                      "planning the task; the goals checked are the --task's when given, else those the plan implies");
  addTaskPlannerOptions(*command, options->request.planner);
  command->add_option("--planner", options->request.motionPlanner,
                      "Motion planner of the actions that name none (OMPL or Kautham name; default RRTConnect)");
  command->add_option("--ik", options->request.ik, "IK solver (dls, kdl, kdl_restarts; default dls)");
  command->add_option("--robot", options->request.robot, "Robot of a MoveIt scene: a built-in name or a .urdf/.xacro file (default: panda)");
  addSceneOptions(*command, options->request.scene);
  command->add_option("--arm", options->request.arm, "The arm (manipulator) that executes the task (default: the robot's first)");
  command->add_option("--rounds", options->request.rounds, "Task planner rounds at most (repairs included)")->capture_default_str();
  command->add_option("--seed", options->request.seed, "Random seed of planners, IK restarts and placement samples")->capture_default_str();
  command->add_option("--time-limit", options->request.timeLimit, "Seconds one motion query may take")->capture_default_str();
  command->add_option("--ik-timeout", options->request.ikTimeout, "Seconds of IK search per pose")->capture_default_str();
  command->add_option("--out", options->out,
                      "Output directory; replaced whole by each run (the earlier outputs kept in DIR.previous)")
      ->capture_default_str();
  command->add_flag("--force", options->force,
                    "Use --out even when it holds files lang2manip did not write (they are kept in DIR.previous)");
  command->add_flag("--keep-partial", options->keepPartial,
                    "When the task does not succeed, still write what was executed, as partial_trajectory.json, "
                    "partial_trajectory.csv, partial_robot_trajectory.json, ...");
  command->add_option("--velocity-scaling", options->velocityScaling,
                      "Fraction of every joint's velocity limit the trajectories use, in [0.01, 1] (default: the robot's "
                      "joint_limits.yaml default_velocity_scaling_factor, else 0.5)");
  command->add_option("--acceleration-scaling", options->accelerationScaling,
                      "Fraction of every joint's acceleration limit the trajectories use, in [0.01, 1] (default: the robot's "
                      "joint_limits.yaml default_acceleration_scaling_factor, else 0.25)");
  command->add_flag("--full-speed", options->request.fullSpeed,
                    "Use all of every joint's velocity and acceleration limits and plan up to its position limits "
                    "(transits otherwise keep 0.05 rad, 5 mm from them; what --velocity-scaling or "
                    "--acceleration-scaling name still holds)");
  command->add_option("--timing", options->timing,
                      "How motions are timed: time-optimal (motions joined and blended, stops only where the gripper "
                      "acts) or rest-to-rest (a stop at every waypoint)")
      ->capture_default_str();
  command->add_flag("--record-tree", options->request.recordTree,
                    "Keep each transit planner's exploration graph (scene.glb draws it green at the tool frame)");
  command->add_flag("--html", options->html, "Also write run.html: the scene, the motion and the plan in one page that opens offline");
  command->add_flag("--json", options->json, "Print the report (report.json) to standard output instead of the summary");
  command->callback([options, task, command, &out] {
    if (command->count("--velocity-scaling") > 0) options->request.velocityScaling = options->velocityScaling;
    if (command->count("--acceleration-scaling") > 0) options->request.accelerationScaling = options->accelerationScaling;
    if (!options->request.planFile.empty() && task->count() == 0) options->request.task.clear();
    if (options->request.planFile == "-") {
      options->request.planFile = "standard input";
      options->request.planText = planFromStandardInput();
    }
    runCommand(*options, out);
  });
}

}  // namespace lang2manip
