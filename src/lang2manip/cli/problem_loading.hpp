#pragma once
/// @file How CLI commands turn a PROBLEM argument into a loaded problem: a built-in short name, a
/// Kautham problem .xml, a MotionBenchMaker/MoveIt scene .yaml (with its request file), or a
/// robot description (.urdf, .xacro).

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "lang2manip/grounding/object_semantics.hpp"
#include "lang2manip/model/kautham_problem.hpp"

namespace lang2manip {

struct LoadedProblem {
  std::string name;
  std::string file;
  /// "kautham" or "moveit".
  std::string format;
  /// The problem as a Kautham problem (for MoveIt input: built from the scene, with the request's
  /// start and goal as its query).
  KauthamProblem problem;
  /// Start and goal of each query: configurations and base poses per robot.
  std::vector<std::pair<RobotStates, RobotStates>> queries;
  /// Which objects move and what they are for, with the reason (inferObjectSemantics).
  std::vector<ObjectSemanticsDecision> objectSemantics;
};

/// What commands that load problems accept beside PROBLEM and --robot.
struct SceneOptions {
  /// "NAME:=VALUE" for every xacro robot read, over a problem's own <XacroArg>s.
  std::vector<std::string> xacroArguments;
  /// Objects to treat as movable / fixed whatever their models say or inference finds.
  std::vector<std::string> movable;
  std::vector<std::string> fixed;
  /// "[MANIPULATOR=]AXIS" approach axes for every robot read (see UrdfReadOptions::approachAxes).
  std::vector<std::string> approachAxes;
  /// Penetration (m) up to which a robot or what it holds rests on a fixed object.
  double contactTolerance = Scene::kDefaultContactTolerance;
};

/// Loads `nameOrPath` (empty: the default built-in problem): a built-in name, a Kautham problem
/// .xml, a MoveIt scene .yaml, or a robot description (.urdf or .xacro: a scene holding only that
/// robot, at the middle of its joint ranges, with no query). `robot` names the robot of MoveIt
/// scenes: a built-in robot or a .urdf/.xacro file (empty: the Panda); for other problems, which
/// name their own robots, it must be empty (a robot chosen there is refused, never ignored). Objects whose models do not say what they are
/// for are inferred (inferObjectSemantics), then `options.movable` / `options.fixed` apply.
/// Throws InputError on any problem with the input, an unknown object name in the overrides, an
/// object named both movable and fixed, or a contact tolerance out of range.
LoadedProblem loadProblem(const std::string& nameOrPath, const std::string& robot, const SceneOptions& options = {});

/// True when `nameOrPath` is a MoveIt scene (.yaml/.yml), the one kind of problem a robot is chosen for.
bool isMoveItSceneName(const std::string& nameOrPath);

/// Adds `--xacro-arg NAME:=VALUE` (repeatable), `--movable A,B`, `--fixed C`,
/// `--approach-axis [MANIPULATOR=]AXIS` (repeatable) and `--contact-tolerance M` to a command that
/// loads problems.
void addSceneOptions(CLI::App& command, SceneOptions& options);

}  // namespace lang2manip
