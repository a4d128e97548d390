// What `run` writes and at what speed: one set of outputs replaced whole (failed and interrupted
// runs included), directories it may not replace, and the scaling of the joint limits it uses.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_run.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ::testing::HasSubstr;

json readOutputJson(const fs::path& file) { return json::parse(readFileText(file), nullptr, false); }

/// Budgets of an optimized build; the sanitized binary runs about ten times slower.
#if defined(__SANITIZE_ADDRESS__)
const std::string kRunBudgets = " --time-limit 50 --ik-timeout 0.1";
#else
const std::string kRunBudgets;
#endif

TEST(RunCli, AFailedTaskReplacesTheEarlierOutputsWithoutATrajectoryUnlessAskedAndExitsWithTwo) {
  const TempDirectory directory;
  const fs::path out = directory.path() / "out";
  const RunResult succeeded = run("run --task \"put the marker in the holder\"" + kRunBudgets + " --out " + out.string());
  ASSERT_EQ(succeeded.exitCode, 0) << succeeded.output;
  const std::string failing = "run --task \"put the eraser 300 cm to the left of the holder\" --rounds 1" + kRunBudgets + " --out " + out.string();
  const RunResult result = run(failing);
  EXPECT_EQ(result.exitCode, 2) << result.output;
  EXPECT_THAT(result.output, HasSubstr("FAILED"));
  EXPECT_THAT(result.output, HasSubstr("the task did not succeed"));
  EXPECT_THAT(result.output, HasSubstr("no trajectory written"));
  const json report = readOutputJson(out / "report.json");
  ASSERT_TRUE(report.is_object());
  EXPECT_FALSE(report["success"].get<bool>());
  ASSERT_EQ(report["actions"].size(), 2u);
  EXPECT_EQ(report["actions"][0]["status"], "succeeded");
  EXPECT_EQ(report["actions"][1]["status"], "failed");
  EXPECT_EQ(report["actions"][1]["stage"], "placement");
  EXPECT_THAT(report["actions"][1]["reason"].get<std::string>(), HasSubstr("eraser"));
  EXPECT_TRUE(fs::exists(out / "plan.json"));
  for (const char* name : {"trajectory.json", "trajectory.csv", "robot_trajectory.json", "gripper_trajectory.json", "gripper_events.json",
                           "partial_trajectory.json"}) {
    EXPECT_FALSE(fs::exists(out / name)) << name << ": the earlier run's motion or a failed run's must not be there";
  }
  EXPECT_TRUE(readOutputJson(fs::path(out.string() + ".previous") / "report.json")["success"].get<bool>()) << "the earlier set is kept";
  EXPECT_TRUE(fs::exists(fs::path(out.string() + ".previous") / "trajectory.json"));

  const RunResult partial = run(failing + " --keep-partial");
  EXPECT_EQ(partial.exitCode, 2) << partial.output;
  EXPECT_EQ(readOutputJson(out / "partial_trajectory.json")["segments"].size(), 1u);
  EXPECT_TRUE(fs::exists(out / "partial_trajectory.csv"));
  EXPECT_TRUE(fs::exists(out / "partial_robot_trajectory.json"));
  EXPECT_TRUE(fs::exists(out / "partial_gripper_events.json"));
  EXPECT_FALSE(fs::exists(out / "trajectory.json"));
}

TEST(RunCli, OutputDirectoriesThatMayNotBeReplacedAreRefusedBeforeTheRun) {
  const TempDirectory directory;
  const fs::path foreign = directory.path() / "notes";
  fs::create_directories(foreign);
  std::ofstream(foreign / "thesis.tex") << "years of work";
  RunResult result = run("run --out " + foreign.string());
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("run: --out " + foreign.string() + ": holds files lang2manip did not write"));
  EXPECT_THAT(result.output, ::testing::Not(HasSubstr("SUCCESS")));
  result = run("run --out " + (directory.path() / "file").string() + " --task \"put the marker in the holder\"" + kRunBudgets);
  EXPECT_EQ(result.exitCode, 0) << result.output;
  std::ofstream(directory.path() / "plain") << "x";
  EXPECT_THAT(run("run --out " + (directory.path() / "plain").string()).output, HasSubstr("exists and is not a directory"));
  EXPECT_THAT(run("run --out .").output, HasSubstr("is the current directory"));
  EXPECT_THAT(run("run --out ''").output, HasSubstr("--out: must name a directory"));
  result = run("run --force --out " + foreign.string() + " --task \"put the marker in the holder\"" + kRunBudgets);
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_TRUE(fs::exists(fs::path(foreign.string() + ".previous") / "thesis.tex"));
}

TEST(RunCli, AnInterruptedRunLeavesTheEarlierSetOrAWholeNewOne) {
  const TempDirectory directory;
  const fs::path out = directory.path() / "out";
  ASSERT_EQ(run("run --task \"put the marker in the holder\"" + kRunBudgets + " --out " + out.string()).exitCode, 0);
  for (const char* delay : {"0.05", "0.3", "0.8", "2"}) {
    const std::string command = std::string("timeout -s INT ") + delay + " " + LANG2MANIP_CLI_PATH + " run --out " + out.string() + kRunBudgets;
    const int status = std::system((command + " > /dev/null 2>&1").c_str());
    (void)status;
    const json report = readOutputJson(out / "report.json");
    ASSERT_TRUE(report.is_object()) << "after SIGINT at " << delay << " s no whole report";
    const std::string task = report["task"].get<std::string>();
    const bool earlier = task == "put the marker in the holder";
    EXPECT_TRUE(earlier || task == "put the marker and eraser in the holder") << task;
    EXPECT_EQ(readOutputJson(out / "viewer.json")["task"].get<std::string>(), task) << "files of two runs mixed after SIGINT at " << delay << " s";
    ASSERT_EQ(run("run --task \"put the marker in the holder\"" + kRunBudgets + " --out " + out.string()).exitCode, 0);
    std::size_t entries = 0;
    for (const auto& entry : fs::directory_iterator(directory.path())) {
      EXPECT_EQ(entry.path().filename().string().find(".partial-"), std::string::npos) << "left over: " << entry.path();
      ++entries;
    }
    EXPECT_EQ(entries, 2u) << "out and out.previous";
  }
}

/// report.json's "trajectory" of `run ARGUMENTS --out DIRECTORY`.
json trajectoryReport(const std::string& arguments, const fs::path& directory) {
  const RunResult result = run("run " + arguments + " --task \"put the marker in the holder\"" + kRunBudgets + " --out " + directory.string());
  EXPECT_EQ(result.exitCode, 0) << result.output;
  return readOutputJson(directory / "report.json")["trajectory"];
}

/// A file `victim` holding "victim", and `link` a symbolic link to it.
void plantLink(const fs::path& link, const fs::path& victim) {
  std::ofstream(victim) << "victim";
  fs::create_symlink(victim, link);
}

/// The victim was not written through the link, and the output is a regular file of its own.
void expectWrittenBesideTheLink(const fs::path& output, const fs::path& victim) {
  EXPECT_EQ(readFileText(victim), "victim") << output << " was written through a symbolic link";
  EXPECT_FALSE(fs::is_symlink(output)) << output;
  EXPECT_TRUE(fs::is_regular_file(output)) << output;
}

TEST(OutputWriters, NoWriterFollowsASymbolicLinkPlantedWhereItsOutputGoes) {
  const TempDirectory directory;
  const fs::path victim = directory.path() / "victim.txt";
  const auto writes = [&](const std::string& name, const std::string& command, int exitCode = 0) {
    SCOPED_TRACE(command);
    const fs::path output = directory.path() / name;
    fs::remove(output);
    plantLink(output, victim);
    const RunResult result = run(command + " " + output.string());
    EXPECT_EQ(result.exitCode, exitCode) << result.output;
    expectWrittenBesideTheLink(output, victim);
  };
  writes("result.json", "solve panda_desk --seed 3 --out");
  writes("scene.glb", "gltf panda_desk -o");
  writes("panda.srdf", "describe panda --write-srdf");
  writes("solve.html", "solve panda_desk --seed 3 --html");
  // run: a link inside the earlier set goes with that set; the new set is the run's own.
  const fs::path out = directory.path() / "run";
  ASSERT_EQ(run("run --task \"put the marker in the holder\"" + kRunBudgets + " --out " + out.string()).exitCode, 0);
  fs::remove(out / "report.json");
  plantLink(out / "report.json", victim);
  const RunResult again = run("run --task \"put the marker in the holder\"" + kRunBudgets + " --out " + out.string());
  EXPECT_EQ(again.exitCode, 0) << again.output;
  expectWrittenBesideTheLink(out / "report.json", victim);
}

TEST(RunCli, RunsUseSafeScalingByDefaultTheRobotsMoveItDefaultsAndFullSpeedOnlyWhenAsked) {
  const TempDirectory directory;
  const json defaults = trajectoryReport("", directory.path() / "defaults");
  EXPECT_EQ(defaults["velocity_scaling"], 0.5);
  EXPECT_EQ(defaults["acceleration_scaling"], 0.25);
  EXPECT_EQ(defaults["scaling_from"], (json{{"velocity", "default"}, {"acceleration", "default"}}));
  EXPECT_EQ(defaults["position_margin"], (json{{"angular", 0.05}, {"linear", 0.005}}));
  const json full = trajectoryReport("--full-speed", directory.path() / "full");
  EXPECT_EQ(full["position_margin"], (json{{"angular", 0.0}, {"linear", 0.0}}));
  EXPECT_EQ(full["velocity_scaling"], 1.0);
  EXPECT_EQ(full["acceleration_scaling"], 1.0);
  EXPECT_LT(full["duration"].get<double>(), defaults["duration"].get<double>());
  const json mixed = trajectoryReport("--full-speed --velocity-scaling 0.3", directory.path() / "mixed");
  EXPECT_EQ(mixed["velocity_scaling"], 0.3);
  EXPECT_EQ(mixed["scaling_from"], (json{{"velocity", "request"}, {"acceleration", "full speed"}}));

  // A robot whose MoveIt joint_limits.yaml gives default scaling factors runs with them.
  const fs::path data = directory.path() / "data";
  fs::copy(test::testDataDirectory().parent_path().parent_path() / "data", data, fs::copy_options::recursive);
  const fs::path limits = data / "models/robots/panda/panda.joint_limits.yaml";
  const std::string text = test::readFileText(limits);
  std::ofstream(limits) << "default_velocity_scaling_factor: 0.3\ndefault_acceleration_scaling_factor: 0.2\n" << text;
  const json robots = trajectoryReport((data / "problems/desk/panda_desk.xml").string(), directory.path() / "robot");
  EXPECT_EQ(robots["velocity_scaling"], 0.3);
  EXPECT_EQ(robots["acceleration_scaling"], 0.2);
  EXPECT_EQ(robots["scaling_from"], (json{{"velocity", "joint_limits.yaml"}, {"acceleration", "joint_limits.yaml"}}));
  EXPECT_THAT(run("run --velocity-scaling 0 --out " + (directory.path() / "bad").string()).output, HasSubstr("--velocity-scaling"));
}

}  // namespace
}  // namespace lang2manip::test
