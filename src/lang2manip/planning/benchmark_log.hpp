#pragma once
/// @file Benchmark results in OMPL's benchmark log format (ompl::tools::Benchmark), readable by
/// ompl_benchmark_statistics.py and Planner Arena.

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace lang2manip {

struct MotionPlan;

/// One planning run: property values by OMPL property name ("time REAL", "solved BOOLEAN", ...).
using BenchmarkRun = std::map<std::string, std::string>;

struct BenchmarkPlannerRuns {
  /// e.g. "geometric_RRTConnect".
  std::string name;
  /// Planner parameters ("range = 0.2").
  std::map<std::string, std::string> common;
  std::vector<BenchmarkRun> runs;
};

struct BenchmarkExperiment {
  std::string name;
  std::string host;
  /// "YYYY-Mon-DD HH:MM:SS" as OMPL writes it.
  std::string startTime;
  std::string setupInfo;
  std::string cpuInfo;
  unsigned long seed = 0;
  double maxTime = 0.0;
  double maxMemoryMb = 0.0;
  unsigned int runCount = 1;
  double totalDuration = 0.0;
  /// Enum types besides OMPL's "status" (written after it): name -> value names, a run's
  /// "NAME ENUM" property being an index into them (e.g. "family" -> the benchmark's families).
  std::vector<std::pair<std::string, std::vector<std::string>>> enumTypes;
  std::vector<BenchmarkPlannerRuns> planners;
};

/// Writes `experiment` as OMPL 1.5's Benchmark::saveResultsToStream does.
void writeOmplBenchmarkLog(const BenchmarkExperiment& experiment, std::ostream& out);

/// An experiment named `name` on this host, starting now (OMPL's time format).
BenchmarkExperiment startBenchmarkExperiment(std::string name);

/// The properties OMPL logs for one run (time, solved, status, lengths, graph size, checks) of
/// `plan`.
BenchmarkRun benchmarkRunOf(const MotionPlan& plan);

/// The run OMPL logs for a problem whose start (or goal) is invalid: not solved, no time, status
/// "Invalid start" ("Invalid goal"), the other properties left empty as OMPL leaves them.
BenchmarkRun invalidBenchmarkRun(bool invalidStart);

/// OMPL's name for a planner status in logs ("Exact solution", "Timeout", ...): the `status ENUM`
/// value is its index in this list.
const std::vector<std::string>& omplStatusNames();

}  // namespace lang2manip
