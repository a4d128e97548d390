#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_run.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(SolveCli, SolvesThePaperSceneAndWritesJsonAndCsv) {
  const TempDirectory directory;
  const auto out = directory.path() / "result.json";
  const RunResult result = run("solve panda_desk --seed 3 --out " + out.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("query 1: solved by RRTConnect"));
  EXPECT_THAT(result.output, HasSubstr("verified"));
  const nlohmann::json report = nlohmann::json::parse(readFileText(out));
  EXPECT_TRUE(report["solved"].get<bool>());
  const nlohmann::json& trajectory = report["queries"][0]["trajectory"];
  EXPECT_EQ(trajectory["joint_names"][0], "panda_joint1") << "the URDF's name";
  EXPECT_FALSE(trajectory.contains("joint_robots")) << "ROS's message loaders refuse a key JointTrajectory has not";
  EXPECT_EQ(report["queries"][0]["trajectory_joint_robots"][0], "panda");
  ASSERT_GE(trajectory["points"].size(), 2u);
  EXPECT_TRUE(trajectory["points"][0].contains("time_from_start"));
  const std::string csv = readFileText(directory.path() / "result.csv");
  EXPECT_EQ(csv.rfind("time,panda_joint1,", 0), 0u) << csv.substr(0, 80);
}

TEST(SolveCli, JsonOutputAndPlannerOverride) {
  const RunResult result = run("solve panda_desk --planner omplKPIECE --param Range=0.3 --json", false);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const nlohmann::json report = nlohmann::json::parse(result.output);
  EXPECT_EQ(report["queries"][0]["planner"], "KPIECE1");
  EXPECT_EQ(report["queries"][0]["status"], "solved");
  EXPECT_GT(report["queries"][0]["statistics"]["vertices"].get<long>(), 0);
}

TEST(SolveCliBadInput, UnknownPlannerParameterAndMalformedArguments) {
  RunResult result = run("solve panda_desk --planner NotAPlanner");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("unknown planner \"NotAPlanner\"; valid planners: RRTConnect"));
  result = run("solve panda_desk --param Bogus=1");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("unknown parameter \"Bogus\" for planner RRTConnect"));
  result = run("solve panda_desk --param Range");
  EXPECT_THAT(result.output, HasSubstr("expected NAME=VALUE"));
  result = run("solve panda_desk --param Range=abc");
  EXPECT_THAT(result.output, HasSubstr("invalid value \"abc\""));
  result = run("solve panda_desk --query 5");
  EXPECT_THAT(result.output, HasSubstr("--query 5: the problem has 1 queries"));
  result = run("solve /nonexistent.xml");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("/nonexistent.xml"));
  result = run("solve panda_desk --time-limit -1");
  EXPECT_NE(result.exitCode, 0);
}

TEST(SolveCli, KauthamDemoWithItsOwnPlanner) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const auto problem = shared / "kautham/OMPL_geo_demos/Cube_Maze_R2/OMPL_RRTconnect_bigcube-maze2D_R2.xml";
  const RunResult result = run("solve " + problem.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("solved by RRTConnect"));
  const RunResult constrained =
      run("solve " + (shared / "kautham/OMPL_constr_demos/UR5/ur5_table_constr_box.xml").string());
  EXPECT_EQ(constrained.exitCode, 1);
  EXPECT_THAT(constrained.output, HasSubstr("planner \"omplconstr\" is not supported"));
}

TEST(SolveCli, KauthamPrmDemoSaysWhichOfItsParametersHaveNoEffect) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const auto problem = shared / "kautham/OMPL_geo_demos/Cube_Maze_R2/OMPL_PRM_bigcube-maze2D_R2_g.xml";
  const RunResult result = run("solve " + problem.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("solved by PRM"));
  EXPECT_THAT(result.output, HasSubstr("parameter \"DistanceThreshold\" = 0.20 has no effect: "));
  EXPECT_THAT(result.output, HasSubstr("valid state sampler: gaussian"));  // Kautham's Sampler 3
  EXPECT_THAT(result.output, Not(HasSubstr("Sampler 0(r)")));
  // stdout only: under LeakSanitizer, stderr ends with its suppression summary.
  const RunResult json = run("solve " + problem.string() + " --json", false);
  ASSERT_EQ(json.exitCode, 0) << json.output;
  const auto report = nlohmann::json::parse(json.output);
  ASSERT_EQ(report["ignored_parameters"].size(), 4u);
  EXPECT_EQ(report["valid_state_sampler"], "gaussian");
  EXPECT_EQ(report["ignored_parameters"][0]["name"], "MinGrowTime");
}

TEST(XacroCli, ExpandsShowsAndPassesArguments) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const auto panda = shared / "robots/franka_description/robots/panda/panda.urdf.xacro";
  const RunResult expanded = run("xacro " + panda.string() + " hand:=true");
  ASSERT_EQ(expanded.exitCode, 0) << expanded.output;
  EXPECT_THAT(expanded.output, HasSubstr("<link name=\"panda_hand_tcp\""));
  EXPECT_THAT(expanded.output, Not(HasSubstr("xacro:")));
  const RunResult shown = run("show " + panda.string() + " --xacro-arg hand:=true");
  ASSERT_EQ(shown.exitCode, 0) << shown.output;
  EXPECT_THAT(shown.output, HasSubstr("8 DOFs"));
  EXPECT_THAT(shown.output, HasSubstr("tool frame panda_hand_tcp"));
  EXPECT_THAT(run("show " + panda.string()).output, HasSubstr("7 DOFs"));
  const RunResult bad = run("show " + panda.string() + " --xacro-arg hand");
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_THAT(bad.output, HasSubstr("xacro argument \"hand\" is not NAME:=VALUE"));
  const RunResult missing = run("xacro /nonexistent/robot.xacro");
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_THAT(missing.output, HasSubstr("/nonexistent/robot.xacro"));
}

TEST(BenchMbmCli, OneProblemPerFamilyWithJsonAndOmplLog) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const TempDirectory directory;
  const auto log = directory.path() / "mbm.log";
  const RunResult result = run("bench mbm " + (shared / "mbm/panda").string() +
                                      " --family box_panda --limit 2 --time-limit 5 --json --log " + log.string(),
                                  false);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const nlohmann::json report = nlohmann::json::parse(result.output);
  ASSERT_EQ(report["families"].size(), 1u);
  EXPECT_EQ(report["families"][0]["name"], "box_panda");
  EXPECT_EQ(report["overall"]["problems"], 2);
  for (const char* key : {"valid", "solved", "median_ms", "mean_ms", "p95_ms", "max_ms", "simplify_median_ms"}) {
    EXPECT_TRUE(report["overall"].contains(key)) << key;
  }
  const std::string text = readFileText(log);
  EXPECT_EQ(text.rfind("OMPL version 1.5.2\nExperiment ", 0), 0u);
  EXPECT_THAT(text, HasSubstr("Experiment lang2manip bench mbm: MotionBenchMaker panda, family box_panda, RRTConnect, 5 s per problem\n"));
  EXPECT_THAT(text, HasSubstr("\nfamily|box_panda\n1 planners\ngeometric_RRTConnect\n"));
  EXPECT_THAT(text, HasSubstr("\nfamily ENUM\ngraph motions INTEGER\n"));
  EXPECT_THAT(text, HasSubstr("\nproblem INTEGER\n"));
  EXPECT_THAT(text, HasSubstr("\n2 runs\n")) << "every problem, valid or not, is a run";
  EXPECT_THAT(text, HasSubstr("time REAL"));
  EXPECT_THAT(text, HasSubstr("\n.\n"));
}

TEST(BenchKauthamCli, RunsEveryProblemOfABenchmarkFileAndWritesOmplsLog) {
  const auto shared = sharedDataDirectory();
  if (!shared) GTEST_SKIP() << "../shared/data is absent";
  const TempDirectory directory;
  const std::filesystem::path log = directory.path() / "result.log";
  const RunResult result = run("bench kautham " + (*shared / "kautham/OMPL_geo_demos/Cube-sPassage_R2/benchmarking_RRT-RRTstar.xml").string() +
                                   " --runs 2 --time-limit 1 --json --log " + log.string(),
                               false);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const nlohmann::json report = nlohmann::json::parse(result.output);
  ASSERT_EQ(report["problems"].size(), 2U);
  EXPECT_EQ(report["problems"][0]["alias"], "RRT");
  EXPECT_EQ(report["problems"][1]["alias"], "RRTstar");
  EXPECT_EQ(report["problems"][0]["runs"], 2);
  EXPECT_EQ(report["ignored_parameters"], nlohmann::json({"displayProgress", "timeBetweenUpdates"}));
  const std::string text = readFileText(log);
  EXPECT_THAT(text, HasSubstr("geometric_RRT\n"));
  EXPECT_THAT(text, HasSubstr("geometric_RRTstar\n"));
  EXPECT_THAT(text, HasSubstr("2 runs"));
}

TEST(BenchKauthamCli, ABadBenchmarkFileIsAClearError) {
  const TempDirectory directory;
  const std::filesystem::path file = directory.path() / "bench.xml";
  std::ofstream(file) << "<Benchmark>\n  <Problem File=\"missing.xml\"/>\n</Benchmark>\n";
  const RunResult result = run("bench kautham " + file.string() + " --runs 1");
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr(file.string() + ":2"));
  EXPECT_THAT(result.output, HasSubstr("missing.xml"));
}

TEST(BenchMbmCli, BadDirectoryAndFamily) {
  RunResult result = run("bench mbm /nonexistent");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("/nonexistent: not a directory"));
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  result = run("bench mbm " + (shared / "mbm/panda").string() + " --family nope");
  EXPECT_THAT(result.output, HasSubstr("--family nope: unknown family; families: bookshelf_small_panda"));
}

}  // namespace
}  // namespace lang2manip::test
