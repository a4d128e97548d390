#pragma once
/// @file How CLI commands turn a PROBLEM argument into a loaded problem: a built-in short name, a
/// Kautham problem .xml, a MotionBenchMaker/MoveIt scene .yaml (with its request file), or a
/// robot description (.urdf, .xacro).

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

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
};

/// Loads `nameOrPath` (empty: the default built-in problem): a built-in name, a Kautham problem
/// .xml, a MoveIt scene .yaml, or a robot description (.urdf or .xacro: a scene holding only that
/// robot, at the middle of its joint ranges, with no query). `robot` names the robot of MoveIt
/// scenes: a built-in robot or a .urdf/.xacro file. `xacroArguments` ("name:=value") go to every
/// xacro robot read, over a problem's own <XacroArg>s. Throws InputError on any problem with the
/// input.
LoadedProblem loadProblem(const std::string& nameOrPath, const std::string& robot,
                          const std::vector<std::string>& xacroArguments = {});

/// Adds `--xacro-arg NAME:=VALUE` (repeatable) to a command that loads problems.
void addXacroArgumentOption(CLI::App& command, std::vector<std::string>& arguments);

}  // namespace lang2manip
