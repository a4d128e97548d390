#pragma once
/// @file The kinds of `lang2manip bench`: each adds itself as a subcommand of the `bench` command
/// (addBenchCommand() in commands.hpp creates it and calls them).

#include <CLI/CLI.hpp>
#include <ostream>

namespace lang2manip {

/// `lang2manip bench ik --robot NAME [--samples N] [--seed N] [--timeout-ms T] [--json]`: the
/// TRAC-IK protocol (docs/benchmarks.md) for every registered IK solver in one run.
void addBenchIkCommand(CLI::App& bench, std::ostream& out);

/// `lang2manip bench mbm DIR [--family NAME] [--limit N] [--planner NAME] [--time-limit S]
/// [--json] [--log FILE]`: the MotionBenchMaker Panda problems (docs/benchmarks.md).
void addBenchMbmCommand(CLI::App& bench, std::ostream& out);

/// `lang2manip bench kautham FILE [--runs N] [--time-limit S] [--log FILE] [--seed N] [--json]`:
/// a Kautham <Benchmark> file, every problem it lists with its own planner, with OMPL's log.
void addBenchKauthamCommand(CLI::App& bench, std::ostream& out);

/// `lang2manip bench task [PROBLEM] [--task "..."] [--trials N] [--spread M] [--turn RAD] [--seed N]
/// [--baseline-ik NAME] [--json]`: randomized trials of a task (docs/benchmarks.md, task level).
void addBenchTaskCommand(CLI::App& bench, std::ostream& out);

/// `lang2manip bench instructions [CORPUS] [--problems A,B] [--class NAME] [--spread M] [--turn RAD]
/// [--seed N] [--failures N] [--json]`: an instruction corpus on the built-in desks, per class.
void addBenchInstructionsCommand(CLI::App& bench, std::ostream& out);
/// `bench families`: the published benchmarks' instruction families on generated tabletops.
void addBenchFamiliesCommand(CLI::App& bench, std::ostream& out);

}  // namespace lang2manip
