#pragma once
/// @file The `lang2manip` command: subcommands, argument parsing, error reporting and exit codes.

#include <ostream>

namespace lang2manip {

/// Runs the command line `argv`. Writes results to `out` and errors to `err`. Returns 0 on
/// success and non-zero on any error (bad arguments, bad input files, failures).
int runCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace lang2manip
