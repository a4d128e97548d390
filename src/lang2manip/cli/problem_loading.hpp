#pragma once
/// @file How CLI commands turn a PROBLEM argument into a loaded problem: a built-in short name, a
/// Kautham problem .xml, or a MotionBenchMaker/MoveIt scene .yaml (with its request file).

#include <string>

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

/// Loads `nameOrPath` (empty: the default built-in problem). `robot` names the built-in robot for
/// MoveIt scenes. Throws InputError on any problem with the input.
LoadedProblem loadProblem(const std::string& nameOrPath, const std::string& robot);

}  // namespace lang2manip
