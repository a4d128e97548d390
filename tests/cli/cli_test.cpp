#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_run.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;

using test::run;
using test::RunResult;

TEST(Cli, ProblemsListsTheBuiltInProblemsWithTheDefaultFirst) {
  const RunResult result = run("problems");
  EXPECT_EQ(result.exitCode, 0);
  EXPECT_THAT(result.output, ::testing::StartsWith("panda_desk (default)"));
  for (const char* name : {"ur5_desk", "iiwa14_desk", "yumi_desk", "tx90_desk"}) {
    EXPECT_THAT(result.output, HasSubstr(name));
  }
  const nlohmann::json list = nlohmann::json::parse(run("problems --json", false).output);
  EXPECT_EQ(list[0]["name"], "panda_desk");
  EXPECT_TRUE(list[0]["default"].get<bool>());
}

TEST(Cli, UsageErrorsExitOneAndHelpExitsZero) {
  RunResult result = run("run --rounds x");
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("Could not convert: --rounds = x"));
  result = run("frobnicate");
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("unknown command \"frobnicate\" (commands: problems, problem, show,"));
  result = run("gltf panda_desk");
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_EQ(run("--help").exitCode, 0);
  EXPECT_EQ(run("run --help").exitCode, 0);
  EXPECT_EQ(run("--version").exitCode, 0);
}

TEST(Cli, ADashTaskIsReadFromStandardInput) {
  RunResult result = run("plan --task -", true, "printf '  put the marker in the holder\\n' |");
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("plan for \"put the marker in the holder\" by offline"));
  result = run("plan --task -", true, "true |");
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("must not be empty"));
  result = run("plan --task -", true, "head -c 70000 /dev/zero | tr '\\0' x |");
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("longer than 64 KiB"));
  const test::TempDirectory directory;
  result = run("run --json --task - --out " + directory.path().string(), false, "printf 'pick up the eraser' |");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_EQ(nlohmann::json::parse(result.output)["task"], "pick up the eraser");
}

TEST(Cli, RunJsonPrintsTheReport) {
  const test::TempDirectory directory;
  RunResult result = run("run --json --task \"pick up the marker\" --out " + directory.path().string(), false);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const nlohmann::json report = nlohmann::json::parse(result.output);
  EXPECT_TRUE(report["success"].get<bool>());
  EXPECT_EQ(report, nlohmann::json::parse(test::readFileText(directory.path() / "report.json")));
  result = run("run --json --rounds 1 --task \"put the holder in the marker\" --out " + directory.path().string(), false);
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_FALSE(nlohmann::json::parse(result.output)["success"].get<bool>());
}

TEST(Cli, ShowDefaultsToThePaperScene) {
  const RunResult result = run("show");
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("robot panda"));
  EXPECT_THAT(result.output, HasSubstr("panda_joint1 revolute [-2.8973, 2.8973]"));
  EXPECT_THAT(result.output, HasSubstr("marker"));
  EXPECT_THAT(result.output, HasSubstr("holder"));
  EXPECT_THAT(result.output, HasSubstr("query 1"));
}

TEST(Cli, ShowJsonHasRobotsObjectsAndQueries) {
  const RunResult result = run("show panda_desk --json", false);
  ASSERT_EQ(result.exitCode, 0);
  const nlohmann::json report = nlohmann::json::parse(result.output);
  EXPECT_EQ(report["robots"][0]["dofs"].get<int>(), 8);
  EXPECT_EQ(report["robots"][0]["joints"][0]["name"], "panda_joint1");
  // Accelerations from panda.joint_limits.yaml; the finger has none (null).
  EXPECT_EQ(report["robots"][0]["joints"][0]["acceleration"], 15.0);
  EXPECT_TRUE(report["robots"][0]["joints"][7]["acceleration"].is_null());
  EXPECT_FALSE(report["objects"].empty());
  ASSERT_FALSE(report["queries"].empty());
  EXPECT_EQ(report["queries"][0]["robots"][0]["start"].size(), 8U);
  // The paper's query: the start (home) and the goal (above the marker) are collision-free.
  EXPECT_TRUE(report["queries"][0]["collision_free"].get<bool>()) << report["queries"][0].dump(2);
  EXPECT_TRUE(report["queries"][0]["start_collision"]["valid"].get<bool>());
  EXPECT_TRUE(report["queries"][0]["goal_collision"]["contacts"].empty());
}

TEST(Cli, CheckReportsEachQueryStateOfTheDefaultProblem) {
  const RunResult result = run("check");
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("problem panda_desk: all states valid (collision-free, within the joint limits)"));
  EXPECT_THAT(result.output, HasSubstr("query 1 start: valid"));
  EXPECT_THAT(result.output, HasSubstr("query 1 goal: valid"));
}

TEST(Cli, CheckNamesTheCollidingPairsOfAConfiguration) {
  // Home with joint 6 at its lower limit folds the wrist into link 5.
  const RunResult text = run("check panda_desk --robot panda --config 0 -0.785 0 -2.356 0 -0.0175 0.785 0.04");
  EXPECT_EQ(text.exitCode, 2) << text.output;
  EXPECT_THAT(text.output, HasSubstr("check: 1 of 1 checked states are invalid"));
  EXPECT_THAT(text.output, HasSubstr("configuration of panda: INVALID"));
  EXPECT_THAT(text.output, HasSubstr("panda/panda_link5 - panda/panda_link7: penetration"));
  const RunResult json = run("check --json --config 0 1.7628 0 -2.356 0 1.571 0.785 0.04", false);
  const nlohmann::json report = nlohmann::json::parse(json.output);
  EXPECT_FALSE(report["valid"].get<bool>());
  bool desk = false;
  for (const auto& contact : report["checks"][0]["contacts"]) {
    desk = desk || (contact["first"] == "panda/panda_link5" && contact["second"] == "desk" &&
                    contact["penetration_depth"].get<double>() > 0.0);
  }
  EXPECT_TRUE(desk) << json.output;
}

TEST(Cli, CheckRejectsBadConfigurations) {
  RunResult result = run("check --robot pr2 --config 0 0");
  EXPECT_NE(result.exitCode, 0);
  EXPECT_THAT(result.output, HasSubstr("unknown robot 'pr2'; valid robots: panda"));
  result = run("check --config 0 0");
  EXPECT_NE(result.exitCode, 0);
  EXPECT_THAT(result.output, HasSubstr("has 2 values; the robot has 8 joint variables"));
}

TEST(Cli, ShowEveryBuiltInProblem) {
  for (const char* name : {"ur5_desk", "iiwa14_desk", "yumi_desk", "tx90_desk"}) {
    const RunResult result = run(std::string("show ") + name);
    EXPECT_EQ(result.exitCode, 0) << name << ": " << result.output;
  }
}

TEST(Cli, ShowsAMotionBenchMakerScene) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const RunResult result = run("show " + (shared / "mbm/panda/box_panda/scene0001.yaml").string());
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("moveit"));
  EXPECT_THAT(result.output, HasSubstr("side_back"));
}

TEST(Cli, ErrorsExitNonZeroWithAMessage) {
  RunResult result = run("show no_such_problem");
  EXPECT_NE(result.exitCode, 0);
  EXPECT_THAT(result.output, HasSubstr("lang2manip: error: \"no_such_problem\" is neither a problem file, a built-in problem nor a built-in robot"));
  result = run("show /tmp/nope.xml");
  EXPECT_NE(result.exitCode, 0);
  EXPECT_THAT(result.output, HasSubstr("/tmp/nope.xml: problem file does not exist"));
  result = run("frobnicate");
  EXPECT_NE(result.exitCode, 0);
  result = run("");
  EXPECT_NE(result.exitCode, 0);
  EXPECT_THAT(result.output, HasSubstr("subcommand"));
  result = run("show --robot");
  EXPECT_NE(result.exitCode, 0);
}

TEST(Cli, RejectsAFileThatIsNotAProblem) {
  const test::TempDirectory directory;
  const std::string file = (directory.path() / "notes.txt").string();
  std::FILE* handle = std::fopen(file.c_str(), "w");
  std::fputs("hello", handle);
  std::fclose(handle);
  const RunResult result = run("show " + file);
  EXPECT_NE(result.exitCode, 0);
  EXPECT_THAT(result.output, HasSubstr("not a problem file"));
}

TEST(Cli, HelpAndVersionSucceed) {
  EXPECT_EQ(run("--help").exitCode, 0);
  EXPECT_THAT(run("--version").output, HasSubstr("lang2manip 0.1.0"));
}

TEST(Cli, ObserveDefaultsToThePaperSceneAndPrintsThePromptText) {
  const RunResult result = run("observe");
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("Robot panda (model panda, 8 DOFs)"));
  EXPECT_THAT(result.output, HasSubstr("panda_joint1 revolute 0.000 [-2.897, 2.897]"));
  EXPECT_THAT(result.output, HasSubstr("tool frame panda_hand_tcp"));
  EXPECT_THAT(result.output, HasSubstr("configuration: home"));
  EXPECT_THAT(result.output, HasSubstr("holder: kind pen_holder"));
  EXPECT_THAT(result.output, HasSubstr("  marker on desk\n"));
  EXPECT_THAT(result.output, HasSubstr("  marker right_of eraser\n"));
}

TEST(Cli, ObserveJsonHasRobotsObjectsAndRelations) {
  const RunResult result = run("observe ur5_desk --json", false);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const nlohmann::json observation = nlohmann::json::parse(result.output);
  EXPECT_EQ(observation["robots"].size(), 1U);
  EXPECT_FALSE(observation["robots"][0]["end_effectors"].empty());
  EXPECT_EQ(observation["objects"].size(), 4U);
  bool holderOnDesk = false;
  for (const auto& fact : observation["relations"]) {
    holderOnDesk = holderOnDesk || (fact["subject"] == "holder" && fact["relation"] == "on" && fact["object"] == "desk");
  }
  EXPECT_TRUE(holderOnDesk);
}

TEST(Cli, ObserveUnknownProblemIsAClearError) {
  const RunResult result = run("observe no_such_problem");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("no_such_problem"));
  EXPECT_THAT(result.output, HasSubstr("panda_desk"));
}

TEST(Cli, PlanPrintPromptShowsSystemPromptTaskAndObservation) {
  const RunResult result = run("plan --task \"put the marker and eraser in the holder\" --print-prompt", false);
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("=== system ==="));
  EXPECT_THAT(result.output, HasSubstr("ACTION GRAMMAR"));
  EXPECT_THAT(result.output, HasSubstr("\"additionalProperties\":false"));
  EXPECT_THAT(result.output, HasSubstr("prompt version lang2manip-plan-prompt-4"));
  EXPECT_THAT(result.output, HasSubstr("=== user ===\nTASK: put the marker and eraser in the holder"));
  EXPECT_THAT(result.output, HasSubstr("marker: kind marker (a cylinder), blue, movable"));
}

TEST(Cli, PlanPrintPromptNeedsATask) {
  for (const char* arguments : {"plan --print-prompt", "plan --print-prompt --task \"  \""}) {
    const RunResult result = run(arguments);
    EXPECT_EQ(result.exitCode, 1) << arguments;
    EXPECT_THAT(result.output, HasSubstr("--task is required")) << arguments;
  }
}

}  // namespace
}  // namespace lang2manip
