#pragma once
/// @file One task, as `run`, `bench task` and the server's /api/runs do it: planned through the
/// repair loop with the executor grounding every answer, then the last execution verified against
/// the goals; and a whole run from its request to the documents `run` writes.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/cli/run_report.hpp"
#include "lang2manip/cli/task_planner_choice.hpp"
#include "lang2manip/core/progress.hpp"
#include "lang2manip/core/stop_condition.hpp"
#include "lang2manip/execution/execution_verification.hpp"
#include "lang2manip/execution/task_executor.hpp"
#include "lang2manip/symbolic/repair_loop.hpp"

namespace lang2manip {

/// The paper's task, the default instruction of `run`.
inline constexpr const char* kPaperTask = "put the marker and eraser in the holder";

struct TaskRun {
  RepairResult repair;
  /// The goals the instruction states (offline understanding), else those the plan implies.
  std::vector<Goal> goals;
  /// "instruction" or "plan".
  std::string goalSource;
  /// Of the last execution; default (not successful) when no plan was executed.
  ExecutionVerification verification;

  [[nodiscard]] bool success() const { return repair.succeeded() && verification.success; }
};

/// How a run may be stopped and watched.
struct RunControl {
  /// Ends planning and execution early (deadline or cancellation); the run then fails.
  StopCondition stop = StopCondition::never();
  ProgressSink progress;
  /// Seed OMPL's process-wide random generator with the request's seed. Only the first seeding
  /// in a process takes effect (OMPL), so a process that runs many tasks (the server) leaves it.
  bool seedOmpl = true;
};

/// Plans `task` on `executor`'s initial scene with `planner` for at most `rounds` rounds, each
/// accepted answer executed by `executor`, and verifies the last execution.
TaskRun planExecuteAndVerify(TaskPlanner& planner, TaskExecutor& executor, const std::string& task, int rounds,
                             const RunControl& control = {});

/// Everything that defines a run (the options of `lang2manip run`).
struct RunRequest {
  /// Built-in name, Kautham problem, MoveIt scene or robot description (loadProblem()).
  std::string problem;
  std::string robot;  ///< the robot of a MoveIt scene (empty: the Panda); empty for other problems
  SceneOptions scene;
  /// The arm that executes the task; empty = the robot's first.
  std::string arm;
  /// The instruction; empty with a plan file (the goals are then those the plan implies).
  std::string task = kPaperTask;
  TaskPlannerChoice planner;
  /// A plan document (the plan.json format) executed instead of asking a task planner; one round.
  std::string planFile;
  /// The plan document's text when it was not read from planFile (`--plan -`: standard input);
  /// planFile then names where it came from.
  std::optional<std::string> planText;
  /// Motion planner of actions that name none; empty = the executor's default.
  std::string motionPlanner;
  /// IK solver; empty = the executor's default.
  std::string ik;
  int rounds = RepairOptions{}.maxRounds;
  long seed = 1;
  double timeLimit = ExecutionSettings{}.planningTimeSeconds;
  double ikTimeout = ExecutionSettings{}.reach.ikTimeoutSeconds;
  /// Keep the transit planners' exploration graphs (drawn green by the viewer).
  bool recordTree = false;
  /// How trajectories are timed, and the fractions of the joint limits they use: as given, else
  /// all of both with fullSpeed, else the robot's joint_limits.yaml defaults, else
  /// kDefaultRunVelocityScaling and kDefaultRunAccelerationScaling (chooseRunScaling()).
  TrajectoryTiming timing = ExecutionSettings{}.timing;
  std::optional<double> velocityScaling;
  std::optional<double> accelerationScaling;
  bool fullSpeed = false;
};

/// The scaling `request` runs with on `robot` (see RunRequest::velocityScaling).
RunScaling chooseRunScaling(const RunRequest& request, const RobotModel& robot);

/// What a run produced: the contents of the files `run` writes.
struct RunDocuments {
  /// observation.json and observation.txt: what the task planner was shown.
  nlohmann::json observation;
  std::string observationText;
  /// prompt.txt: the system prompt and first message an LLM planner is sent.
  std::string prompt;
  /// plan.json: the accepted plan, else the last plan tried; absent when no plan was parsed.
  std::optional<nlohmann::json> plan;
  /// trajectory.json, trajectory.csv and robot_trajectory.json (MoveIt's RobotTrajectory) of the
  /// last execution (trajectory_outputs.hpp); absent when nothing was executed.
  std::optional<nlohmann::json> trajectory;
  std::string trajectoryCsv;
  nlohmann::json robotTrajectory;
  /// gripper_trajectory.json and gripper_events.json; absent for a robot without a gripper.
  std::optional<nlohmann::json> gripperTrajectory;
  nlohmann::json gripperEvents;
  /// scene.glb and viewer.json: the scene with the executed motion animated and the tool paths,
  /// and what the viewer lists beside it (run_scene.hpp).
  std::string sceneGlb;
  nlohmann::json viewerDocument;
  /// report.json and the summary `run` prints.
  nlohmann::json report;
  std::string summary;
  bool success = false;
};

/// The names of the documents of the executed motion that `documents` has, in the order they are
/// written: trajectory.json, trajectory.csv, robot_trajectory.json, gripper_trajectory.json and
/// gripper_events.json (the last two for a robot with a gripper), each with its content.
std::vector<std::pair<std::string, std::string>> motionDocuments(const RunDocuments& documents);

/// The name a document of the executed motion (one of motionDocuments()) goes under: itself for a run that succeeded, "partial_" before it for
/// one that did not (written or served only when asked: a failed run's motion is not one to send
/// to an arm).
std::string trajectoryDocumentName(const std::string& name, bool success);

/// A name in a run request that nothing is registered under. field() is "planner", "ik" or "arm"
/// (`run`'s --planner, --ik, --arm and the run request's body fields); the message lists the
/// valid names.
class RunNameError : public InputError {
 public:
  RunNameError(std::string field, const std::string& message) : InputError(message), field_(std::move(field)) {}
  [[nodiscard]] const std::string& field() const noexcept { return field_; }

 private:
  std::string field_;
};

/// Checks the motion planner, IK solver and arm that `request` names against the registries and
/// the robot of `scene`, as runTask() does before any planning. Throws RunNameError, or
/// NotSupportedError for a Kautham planner lang2manip does not run.
void checkRunNames(const RunRequest& request, const Scene& scene);
/// Loads the request's problem and checks its names (checkRunNames()): for a run queued to start
/// later. Returns the problem's name; throws InputError for a problem that cannot be loaded too.
std::string checkRunNames(const RunRequest& request);

/// Loads the problem, plans, executes and verifies the task of `request`. A task that fails is a
/// result (success false, the report says why). Throws InputError for a bad problem, arm, planner
/// or solver name, a plan file that cannot be read or is not a plan for this scene (every problem
/// with its JSON path), and LlmError for an LLM planner that cannot be set up (no key, bad URL).
RunDocuments runTask(const RunRequest& request, const RunControl& control = {});

}  // namespace lang2manip
