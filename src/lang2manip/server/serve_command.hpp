#pragma once
/// @file `lang2manip serve` and `lang2manip bench api` (the server module's commands).

#include <CLI/CLI.hpp>
#include <ostream>

namespace lang2manip {

/// `lang2manip serve [PROBLEM] [--host H] [--port P] [--token T] [--data-root DIR] [--viewer DIR]
/// [--max-sessions N] [--threads N]`: serves the HTTP API until SIGINT or SIGTERM.
void addServeCommand(CLI::App& app, std::ostream& out);

/// `lang2manip bench api [PROBLEM] [--clients N] [--solves N]`: N concurrent clients on loopback,
/// each its own session (open, solve, get path), against the same solves in process.
void addBenchApiCommand(CLI::App& bench, std::ostream& out);

}  // namespace lang2manip
