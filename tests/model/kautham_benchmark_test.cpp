// Kautham <Benchmark> files: what they list and every malformed case, with file and line.

#include "lang2manip/model/kautham_benchmark.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "model_test_support.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;
using test::errorMessage;

TEST(KauthamBenchmark, ReadsProblemsAliasesAndParameters) {
  const KauthamBenchmark benchmark = readKauthamBenchmarkString(R"(<Benchmark Name="experiment">
  <Problem File="rrt.xml" PlannerAlias="RRT"/>
  <Problem File="sub/prm.xml"/>
  <Parameter Name="maxTime" Value="3.0"/>
  <Parameter Name="maxMem" Value="512"/>
  <Parameter Name="runCount" Value="10"/>
  <Parameter Name="filename" Value="result.log"/>
  <Parameter Name="displayProgress" Value="true"/>
</Benchmark>)", "b.xml", "/data/bench");
  EXPECT_EQ(benchmark.name, "experiment");
  ASSERT_EQ(benchmark.problems.size(), 2U);
  EXPECT_EQ(benchmark.problems[0].problem, std::filesystem::path("/data/bench/rrt.xml"));
  EXPECT_EQ(benchmark.problems[0].alias, "RRT");
  EXPECT_EQ(benchmark.problems[1].problem, std::filesystem::path("/data/bench/sub/prm.xml"));
  EXPECT_EQ(benchmark.problems[1].alias, "");
  EXPECT_DOUBLE_EQ(benchmark.maxTime, 3.0);
  EXPECT_DOUBLE_EQ(benchmark.maxMemoryMb, 512.0);
  EXPECT_EQ(benchmark.runCount, 10);
  EXPECT_EQ(benchmark.logFile, "result.log");
  EXPECT_EQ(benchmark.ignoredParameters, std::vector<std::string>{"displayProgress"});
}

TEST(KauthamBenchmark, ReadsEveryBenchmarkOfKauthamsDemos) {
  const auto shared = test::sharedDataDirectory();
  if (!shared) GTEST_SKIP() << "../shared/data is absent";
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(*shared / "kautham")) {
    if (entry.path().filename().string().rfind("benchmark", 0) != 0 || entry.path().extension() != ".xml") continue;
    const KauthamBenchmark benchmark = readKauthamBenchmarkFile(entry.path());
    ++files;
    for (const auto& problem : benchmark.problems) EXPECT_TRUE(std::filesystem::is_regular_file(problem.problem)) << problem.problem;
  }
  EXPECT_GE(files, 4);
}

struct BadBenchmark {
  const char* name;
  const char* xml;
  const char* expected;
};

class KauthamBenchmarkBadInput : public ::testing::TestWithParam<BadBenchmark> {};

TEST_P(KauthamBenchmarkBadInput, ReportsFileLineAndProblem) {
  const std::string message = errorMessage([] { (void)readKauthamBenchmarkString(GetParam().xml, "bad.xml", "/d"); });
  EXPECT_THAT(message, HasSubstr("bad.xml:"));
  EXPECT_THAT(message, HasSubstr(GetParam().expected));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, KauthamBenchmarkBadInput,
    ::testing::Values(
        BadBenchmark{"NotABenchmark", "<Problem/>", "not a Kautham benchmark file"},
        BadBenchmark{"NoProblems", "<Benchmark><Parameter Name=\"maxTime\" Value=\"1\"/></Benchmark>", "names no <Problem>"},
        BadBenchmark{"ProblemWithoutFile", "<Benchmark><Problem PlannerAlias=\"x\"/></Benchmark>", "<Problem> needs attribute \"File\""},
        BadBenchmark{"UnknownParameter", "<Benchmark><Problem File=\"a\"/><Parameter Name=\"maxtime\" Value=\"1\"/></Benchmark>",
                     "unknown benchmark parameter \"maxtime\" (parameters: maxTime, maxMem"},
        BadBenchmark{"TimeNotANumber", "<Benchmark><Problem File=\"a\"/><Parameter Name=\"maxTime\" Value=\"soon\"/></Benchmark>",
                     "\"soon\" is not a number"},
        BadBenchmark{"NegativeTime", "<Benchmark><Problem File=\"a\"/><Parameter Name=\"maxTime\" Value=\"-1\"/></Benchmark>",
                     "must be positive"},
        BadBenchmark{"ZeroRuns", "<Benchmark><Problem File=\"a\"/><Parameter Name=\"runCount\" Value=\"0\"/></Benchmark>",
                     "whole number from 1 to 1000000"},
        BadBenchmark{"FractionalRuns", "<Benchmark><Problem File=\"a\"/><Parameter Name=\"runCount\" Value=\"2.5\"/></Benchmark>",
                     "whole number"},
        BadBenchmark{"ParameterWithoutValue", "<Benchmark><Problem File=\"a\"/><Parameter Name=\"maxTime\"/></Benchmark>",
                     "needs attribute \"Value\""},
        BadBenchmark{"UnknownElement", "<Benchmark><Problem File=\"a\"/><Planner/></Benchmark>", "unknown element <Planner>"},
        BadBenchmark{"MalformedXml", "<Benchmark><Problem File=\"a\"></Benchmark>", "bad.xml"}),
    [](const ::testing::TestParamInfo<BadBenchmark>& parameter) { return std::string(parameter.param.name); });

}  // namespace
}  // namespace lang2manip
