#pragma once
/// @file The subcommands of `lang2manip`. Each adds itself to the application with its options and
/// a callback that runs when it is parsed; callbacks throw on errors (runCli reports them).

#include <CLI/CLI.hpp>
#include <ostream>
#include <stdexcept>

namespace lang2manip {

/// `lang2manip problems [--json]`: the built-in problems.
void addProblemsCommand(CLI::App& app, std::ostream& out);

/// `lang2manip problem write [PROBLEM] --out DIR [--name STEM]`: any problem written as a Kautham
/// problem (XML, controls, models), replaced whole as run's outputs are.
void addProblemCommand(CLI::App& app, std::ostream& out);

/// `lang2manip show [PROBLEM] [--robot NAME] [--json]`: robots, controls, objects and queries.
void addShowCommand(CLI::App& app, std::ostream& out);

/// `lang2manip check [PROBLEM] [--robot NAME --config q1 q2 ...] [--json]`: whether each query's
/// start and goal (or the given configuration) is valid: collision-free (naming the colliding
/// pairs) and within the joint limits (naming the joints outside). Ends with TaskFailedError
/// (exit status 2) when any checked state is invalid, InputError when nothing can be checked.
void addCheckCommand(CLI::App& app, std::ostream& out);

/// `lang2manip solve [PROBLEM] [--planner NAME] [--param NAME=VALUE ...] [--json] [--out FILE]`:
/// solves the problem's motion queries and writes the paths and trajectories.
void addSolveCommand(CLI::App& app, std::ostream& out);

/// `lang2manip observe [PROBLEM] [--robot NAME] [--json]`: the environment-state observation
/// given to task planners (text), or the same as JSON.
void addObserveCommand(CLI::App& app, std::ostream& out);

/// `lang2manip plan [PROBLEM] --task "..." [--llm offline|PROVIDER:MODEL] [--llm-base-url URL]
/// [--llm-timeout S] [--llm-record FILE | --llm-replay FILE] [--rounds N] [--json]
/// [--print-prompt]`: runs the task planner through the repair loop (the plan is checked against
/// the scene's symbolic state; nothing is executed) and prints the plan, or its JSON, or the
/// prompt. A planner that fails every round is an error listing the attempts.
void addPlanCommand(CLI::App& app, std::ostream& out);

/// `lang2manip run [PROBLEM] [--task "..."] [--llm SPEC] [--planner NAME] [--ik NAME] [--arm NAME]
/// [--seed N] [--time-limit S] [--ik-timeout S] [--rounds N] [--out DIR]`: plans the task (default: the paper's task
/// on the paper's scene, offline), grounds and executes every action, verifies the result and
/// writes plan.json, observation.{txt,json}, prompt.txt, trajectory.{json,csv} and report.json.
/// A task that does not succeed still writes everything and ends with TaskFailedError.
void addRunCommand(CLI::App& app, std::ostream& out);

/// `lang2manip xacro FILE [NAME:=VALUE ...] [--package-path DIR]`: prints the URDF a xacro file
/// expands to.
void addXacroCommand(CLI::App& app, std::ostream& out);

/// `lang2manip gltf [PROBLEM] -o FILE [--collision] [--goal]`: the scene, robots at the first
/// query's start (or goal), as a glTF binary file.
void addGltfCommand(CLI::App& app, std::ostream& out);

/// `lang2manip render RUN_DIR [--size WxH] [--camera AZ,EL[,DIST]] [--columns N] [--out DIR]
/// [--chromium PATH]`: PNG snapshots of a run's key moments and a contact sheet (headless Chromium).
void addRenderCommand(CLI::App& app, std::ostream& out);

/// `lang2manip describe [PROBLEM] [--write-srdf FILE] [--json]`: the arms, tool frames, grippers
/// (measured by forward kinematics), named states and object semantics lang2manip understood.
void addDescribeCommand(CLI::App& app, std::ostream& out);
/// A command ran to its end but the task failed (its results were written); exit status 2.
class TaskFailedError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// `lang2manip bench KIND ...`: benchmarks that print figures (kinds: ik; see bench_commands.hpp).
void addBenchCommand(CLI::App& app, std::ostream& out);

}  // namespace lang2manip
