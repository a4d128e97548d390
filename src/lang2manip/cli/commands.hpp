#pragma once
/// @file The subcommands of `lang2manip`. Each adds itself to the application with its options and
/// a callback that runs when it is parsed; callbacks throw on errors (runCli reports them).

#include <CLI/CLI.hpp>
#include <ostream>

namespace lang2manip {

/// `lang2manip problems [--json]`: the built-in problems.
void addProblemsCommand(CLI::App& app, std::ostream& out);

/// `lang2manip show [PROBLEM] [--robot NAME] [--json]`: robots, controls, objects and queries.
void addShowCommand(CLI::App& app, std::ostream& out);

}  // namespace lang2manip
