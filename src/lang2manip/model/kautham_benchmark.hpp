#pragma once
/// @file Kautham's <Benchmark> files: the problems to run (each under the planner alias its
/// results are logged as) and the parameters of OMPL's benchmark request.
/// @code
/// <Benchmark Name="experiment">
///   <Problem File="OMPL_RRT_bigcube-s-passage_R2.xml" PlannerAlias="RRT"/>
///   <Parameter Name="maxTime" Value="3.0"/>
///   <Parameter Name="runCount" Value="10"/>
///   <Parameter Name="filename" Value="result.log"/>
/// </Benchmark>
/// @endcode

#include <filesystem>
#include <string>
#include <vector>

#include "lang2manip/core/error.hpp"

namespace lang2manip {

struct KauthamBenchmark {
  struct Entry {
    /// The problem file, resolved against the benchmark file's directory.
    std::filesystem::path problem;
    /// The name its runs are logged under (the problem's planner name when the file gives none).
    std::string alias;
    SourceLocation where;
  };
  std::string name;
  std::vector<Entry> problems;
  /// OMPL's Benchmark::Request: seconds per run, megabytes, runs per planner (its defaults).
  double maxTime = 5.0;
  double maxMemoryMb = 4096.0;
  int runCount = 100;
  /// The log file the benchmark names (empty when it names none).
  std::string logFile;
  /// Parameters accepted that change nothing here (displayProgress, timeBetweenUpdates).
  std::vector<std::string> ignoredParameters;
};

/// Reads a benchmark file. Throws InputError naming the file and line for malformed XML, a root
/// other than <Benchmark>, a <Problem> without File, an unknown <Parameter> (listing the known
/// ones), a value that is not a number where one is needed, maxTime or maxMem <= 0, runCount < 1,
/// and a benchmark without problems. The problem files are not read here.
KauthamBenchmark readKauthamBenchmarkFile(const std::filesystem::path& path);

/// Reads benchmark text; problem files resolve against `directory`.
KauthamBenchmark readKauthamBenchmarkString(const std::string& xml, const std::string& sourceName,
                                            const std::filesystem::path& directory);

}  // namespace lang2manip
