#pragma once
/// @file The built-in robots and problems shipped with lang2manip (Kautham layout: models/ and
/// problems/), found at run time.

#include <filesystem>
#include <string>
#include <vector>

namespace lang2manip {

/// The data directory: $LANG2MANIP_DATA if set, else the source tree's data/ (when run from a
/// build tree), else the installed share/lang2manip. Throws InputError when none exists.
std::filesystem::path builtinDataDirectory();

struct BuiltinProblem {
  std::string shortName;
  std::string description;
  std::filesystem::path file;
};

/// Every built-in problem, the default (the paper's scene) first.
std::vector<BuiltinProblem> builtinProblems();

/// Short name of the default problem (the paper's Panda desk scene).
std::string defaultProblemName();

/// A problem given by short name or by path. A path that exists is returned as is; a short name
/// resolves to its file, a built-in robot's name to that robot's desk problem ("ur5" ->
/// ur5_desk); anything else throws InputError listing the short names and robots.
std::filesystem::path resolveProblem(const std::string& nameOrPath);

/// The URDF of a built-in robot by short name (panda, ur5, iiwa14, yumi, tx90); throws
/// InputError listing the names when unknown.
std::filesystem::path builtinRobotUrdf(const std::string& name);

/// Short names of the built-in robots.
std::vector<std::string> builtinRobotNames();

}  // namespace lang2manip
