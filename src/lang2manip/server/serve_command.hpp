#pragma once
/// @file `lang2manip serve`, `bench api` and `bench api-attacks` (the server module's commands).

#include <CLI/CLI.hpp>
#include <ostream>

namespace lang2manip {

/// `lang2manip serve [PROBLEM] [--host H] [--port P] [--token T] [--data-root DIR] [--viewer DIR]
/// [--max-sessions N] [--max-connections N] [--max-request-seconds S]`: serves the HTTP API until SIGINT or SIGTERM.
void addServeCommand(CLI::App& app, std::ostream& out);

/// `lang2manip bench api [PROBLEM] [--clients N] [--solves N]`: N concurrent clients on loopback,
/// each its own session (open, solve, get path), against the same solves in process.
void addBenchApiCommand(CLI::App& bench, std::ostream& out);

/// `lang2manip bench api-attacks [--probes N] [--attackers N]`: a legitimate client's round trips
/// (health, a solve) while other clients misuse the server, against no attack in the same process.
void addBenchAttacksCommand(CLI::App& bench, std::ostream& out);

}  // namespace lang2manip
