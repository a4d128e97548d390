// The command line on hostile input: states outside the limits, nothing to check, names that
// two XML readers read differently, paths that are not files, MoveIt scenes solved end to end.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "lang2manip/cli/solve_scene.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

void writeFile(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

std::string builtinPandaUrdf() {
  return (testDataDirectory() / ".." / ".." / "data" / "models" / "robots" / "panda" / "panda.urdf")
      .lexically_normal()
      .string();
}

TEST(CheckCli, ValuesOutsideTheJointLimitsAreInvalidAndExitTwo) {
  // Joint 4's upper limit is -0.0698: 0.5 is outside although the arm collides with nothing.
  const RunResult text = run("check --config 0 -0.785 0 0.5 0 1.571 0.785 0.04");
  EXPECT_EQ(text.exitCode, 2) << text.output;
  EXPECT_THAT(text.output, HasSubstr("configuration of panda: INVALID"));
  EXPECT_THAT(text.output,
              HasSubstr("outside the joint limits: panda_joint4 = 0.5 is above its upper limit -0.0698"));
  const RunResult jsonRun = run("check --json --config 0 -0.785 0 -2.356 0 1.571 0.785 0.09", false);
  EXPECT_EQ(jsonRun.exitCode, 2);
  const nlohmann::json report = nlohmann::json::parse(jsonRun.output);
  EXPECT_FALSE(report["valid"].get<bool>());
  EXPECT_TRUE(report["checks"][0]["collision_free"].get<bool>());
  ASSERT_EQ(report["checks"][0]["limit_violations"].size(), 1U);
  EXPECT_THAT(report["checks"][0]["limit_violations"][0].get<std::string>(), HasSubstr("panda_finger_joint1 = 0.09"));
}

TEST(CheckCli, AValidConfigurationExitsZero) {
  const RunResult result = run("check --config 0 -0.785 0 -2.356 0 1.571 0.785 0.04");
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("configuration of panda: valid"));
}

TEST(CheckCli, SaysWhenNothingWasChecked) {
  const TempDirectory directory;
  const auto problem = directory.path() / "noquery.xml";
  writeFile(problem, "<?xml version=\"1.0\"?>\n<Problem name=\"noquery\">\n  <Robot robot=\"" +
                         builtinPandaUrdf() + "\"/>\n</Problem>\n");
  const RunResult result = run("check " + problem.string());
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("nothing was checked: problem noquery has no query; give a configuration with --config"));
}

TEST(CliRobotChoice, ARobotChosenForAProblemThatNamesItsOwnIsRefusedNotIgnored) {
  for (const char* command : {"describe panda_desk --robot ur5", "observe panda_desk --robot ur5", "show panda_desk --robot ur5"}) {
    SCOPED_TRACE(command);
    const RunResult result = run(command);
    EXPECT_EQ(result.exitCode, 1) << result.output;
    EXPECT_THAT(result.output, HasSubstr("robot \"ur5\" was chosen, but a robot is chosen only for a MoveIt scene"));
  }
  // check's --robot names the robot of --config; without one it would choose nothing.
  const RunResult check = run("check panda_desk --robot panda");
  EXPECT_EQ(check.exitCode, 1) << check.output;
  EXPECT_THAT(check.output, HasSubstr("--robot panda names the robot whose --config is given"));
}

/// panda_desk with the robot's base `z` (link0 reaches 0.5 mm below it; the desk top is at 0.75).
std::string pandaDeskWithBaseAt(const std::string& z) {
  const std::filesystem::path data = (testDataDirectory() / ".." / ".." / "data").lexically_normal();
  std::string text = readFileText(data / "problems" / "desk" / "panda_desk.xml");
  const auto replace = [&text](const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
      text.replace(at, from.size(), to);
    }
  };
  replace("\"robots/", "\"" + (data / "models" / "robots").string() + "/");
  replace("\"obstacles/", "\"" + (data / "models" / "obstacles").string() + "/");
  replace("\"controls/", "\"" + (data / "problems" / "desk" / "controls").string() + "/");
  replace("Z=\"0.7515\"", "Z=\"" + z + "\"");
  return text;
}

TEST(CheckCli, ARobotBaseRestingOnTheDeskIsInContactNotInCollision) {
  const TempDirectory directory;
  const auto problem = directory.path() / "resting.xml";
  writeFile(problem, pandaDeskWithBaseAt("0.7502"));  // 0.3 mm into the desk
  RunResult result = run("check " + problem.string());
  EXPECT_EQ(result.exitCode, 0) << result.output;
  result = run("check " + problem.string() + " --contact-tolerance 0");
  EXPECT_EQ(result.exitCode, 2) << result.output;
  EXPECT_THAT(result.output, HasSubstr("panda/panda_link0 - desk: penetration 0.0003 m"));
  writeFile(problem, pandaDeskWithBaseAt("0.7480"));  // 2.5 mm into the desk
  result = run("check " + problem.string());
  EXPECT_EQ(result.exitCode, 2) << result.output;
  EXPECT_THAT(result.output, HasSubstr("panda/panda_link0 - desk: penetration 0.0025 m"));
  EXPECT_EQ(run("check " + problem.string() + " --contact-tolerance 0.003").exitCode, 0);
  result = run("check " + problem.string() + " --contact-tolerance 0.05");
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("contact tolerance 0.05 m is not in [0, 0.01] m"));
}

TEST(TerminalOutput, EscapeSequencesInNamesFromFilesAreShownNotSentToTheTerminal) {
  const TempDirectory directory;
  const auto plan = directory.path() / "plan.json";
  std::ofstream(plan) << R"({"actions": [{"action": "pick", "object": "\u001b]0;owned\u0007\u001b[2Jmarker"}]})";
  const RunResult result = run("run --plan " + plan.string() + " --out " + (directory.path() / "out").string());
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("\\x1b]0;owned\\x07\\x1b[2Jmarker"));
  EXPECT_EQ(result.output.find('\x1b'), std::string::npos) << "a raw escape reached the terminal";
  EXPECT_EQ(result.output.find('\x07'), std::string::npos);
}

TEST(GltfCli, WritesTheSceneAsGlbAndSaysWhenItCannot) {
  const TempDirectory directory;
  const auto glb = directory.path() / "desk.glb";
  RunResult result = run("gltf panda_desk --goal -o " + glb.string());
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("wrote " + glb.string() + ": "));
  const std::string bytes = readFileText(glb);
  ASSERT_GE(bytes.size(), 12U);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  result = run("gltf panda_desk -o " + (directory.path() / "missing" / "desk.glb").string());
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("gltf: --out " + (directory.path() / "missing" / "desk.glb").string() + ": its directory"));
  result = run("gltf panda_desk");
  EXPECT_NE(result.exitCode, 0);
  EXPECT_THAT(result.output, HasSubstr("--out is required"));
}

TEST(CliPaths, ADirectoryOrADeviceGivenAsAFileSaysWhatItIs) {
  const TempDirectory directory;
  RunResult result = run("show " + directory.path().string());
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr(directory.path().string() + ": problem file is a directory, not a file"));
  EXPECT_THAT(result.output, Not(HasSubstr("does not exist")));
  result = run("show /dev/zero");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("/dev/zero: problem file is a character device, not a regular file"));
}

TEST(CliUrdfNames, WhitespaceInANameIsAnErrorWithFileAndLineNeverACrash) {
  const TempDirectory directory;
  const std::string links[] = {"a\tb", "a\rb", "a&#9;b", "a&#13;", " a"};
  for (const std::string& name : links) {
    const auto urdf = directory.path() / "robot.urdf";
    writeFile(urdf, "<robot name=\"r\">\n<link name=\"" + name + "\"/>\n</robot>\n");
    const auto problem = directory.path() / "problem.xml";
    writeFile(problem, "<?xml version=\"1.0\"?>\n<Problem name=\"p\">\n  <Robot robot=\"" + urdf.string() +
                           "\"/>\n</Problem>\n");
    for (const char* command : {"show", "check", "run"}) {
      const RunResult result = run(std::string(command) + " " + problem.string());
      EXPECT_EQ(result.exitCode, 1) << command << " " << name << ": " << result.output;
      EXPECT_THAT(result.output, HasSubstr(urdf.string() + ":2: link name"));
      EXPECT_THAT(result.output, HasSubstr("contains whitespace or a control character"));
    }
  }
}

TEST(SolveCli, SolvesAMotionBenchMakerSceneEndToEnd) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const auto scene = shared / "mbm/panda/table_pick_panda/scene0001.yaml";
  const RunResult result = run("solve " + scene.string() + " --seed 2 --json", false);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const nlohmann::json report = nlohmann::json::parse(result.output);
  ASSERT_EQ(report["queries"].size(), 1U);
  const nlohmann::json& query = report["queries"][0];
  EXPECT_EQ(query["status"], "solved") << query["message"];
  EXPECT_EQ(query["path_dof_names"].size(), 8U);
  ASSERT_GE(query["path"].size(), 2U);
  EXPECT_TRUE(report["solved"].get<bool>());
}

TEST(ProblemWriteCli, AnyProblemIsWrittenAsAKauthamProblemThatReadsBackAndIsReplacedWhole) {
  const TempDirectory directory;
  const std::filesystem::path out = directory.path() / "desk";
  RunResult result = run("problem write panda_desk --out " + out.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("Kautham problem \"panda_desk\" of panda_desk (1 robot(s), 4 object(s), 1 query(ies))"));
  EXPECT_TRUE(std::filesystem::is_regular_file(out / "controls" / "panda_desk.cntr"));
  result = run("check " + (out / "panda_desk.xml").string());
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("query 1 goal: valid"));
  result = run("problem write panda_desk --name again --out " + out.string());
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_TRUE(std::filesystem::exists(out / "again.xml"));
  EXPECT_FALSE(std::filesystem::exists(out / "panda_desk.xml")) << "one set, replaced whole";
  writeFile(directory.path() / "mine" / "notes.txt", "mine");
  result = run("problem write panda_desk --out " + (directory.path() / "mine").string());
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("--force"));
  result = run("problem write panda_desk --name ../up --out " + out.string());
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("--name \"../up\" must be letters, digits"));
}

TEST(SolveCli, APathThatGotLongerSaysItWasRepaired) {
  const RunResult result = run("solve panda_desk --seed 3 --json", false);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  nlohmann::json query = nlohmann::json::parse(result.output)["queries"][0];
  EXPECT_THAT(solveQueryText(query), Not(HasSubstr("longer")));
  nlohmann::json& statistics = query["statistics"];
  statistics["length_after_simplification"] = statistics["length_before_simplification"].get<double>() + 0.5;
  statistics["repaired_segments"] = 2;
  EXPECT_THAT(solveQueryText(query), HasSubstr("longer: 2 segment(s) that touched an obstacle at the verification resolution planned again around it"));
}

TEST(SolveCli, AQueryThatCannotBePlannedIsReportedAndExitsTwo) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  // The goal collides with the built-in Panda's enclosing capsules.
  const auto colliding = shared / "mbm/panda/bookshelf_small_panda/scene0009.yaml";
  RunResult result = run("solve " + colliding.string());
  EXPECT_EQ(result.exitCode, 2) << result.output;
  EXPECT_THAT(result.output, HasSubstr("query 1: not planned: goal is in collision: panda/panda_link5 touches panda/panda_link7"));
  EXPECT_THAT(result.output, Not(HasSubstr("previous query")));
  EXPECT_EQ(run("check " + colliding.string()).exitCode, 2);
  // The goal lies just outside the built-in Panda's joint limits.
  const auto outside = shared / "mbm/panda/table_pick_panda/scene0031.yaml";
  result = run("solve " + outside.string() + " --json", false);
  EXPECT_EQ(result.exitCode, 2) << result.output;
  const nlohmann::json report = nlohmann::json::parse(result.output);
  EXPECT_EQ(report["queries"][0]["status"], "invalid_query");
  EXPECT_THAT(report["queries"][0]["message"].get<std::string>(), HasSubstr("outside the joint limits of \"panda\""));
  result = run("check " + outside.string());
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_THAT(result.output, HasSubstr("outside the joint limits: panda_joint"));
}

}  // namespace
}  // namespace lang2manip::test
