// `lang2manip run`: the paper's task end to end (offline and through an LLM protocol on loopback),
// the files it writes, determinism, a task that fails (partial results, exit status 2), and the
// errors of its arguments.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>

#include "cli/cli_run.hpp"
#include "fake_llm_server.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;

json readJson(const fs::path& file) { return json::parse(readFileText(file), nullptr, false); }

json pickStep(const std::string& object) { return {{"action", "pick"}, {"object", object}}; }
json placeIn(const std::string& object) {
  return {{"action", "place"}, {"object", object}, {"params", {{"relation", "in"}, {"target", "holder"}}}};
}

/// Budgets of an optimized build; the sanitized binary runs about ten times slower.
#if defined(__SANITIZE_ADDRESS__)
const std::string kBudgets = " --time-limit 50 --ik-timeout 0.1";
#else
const std::string kBudgets;
#endif

double secondsOf(const json& duration) { return duration["sec"].get<double>() + duration["nanosec"].get<double>() * 1e-9; }

/// Within each segment's arm and gripper trajectories times increase strictly from the segment's
/// start; segments follow each other; the last ends at the duration.
void expectTimesIncrease(const json& trajectory) {
  double end = 0.0;
  for (const json& segment : trajectory["segments"]) {
    EXPECT_GE(segment["start_time"].get<double>(), end - 1e-9);
    for (const char* part : {"arm", "gripper"}) {
      if (!segment.contains(part)) continue;
      double last = -1.0;
      for (const json& point : segment[part]["points"]) {
        const double t = secondsOf(point["time_from_start"]);
        EXPECT_GT(t, last) << part;
        last = t;
      }
      end = segment["start_time"].get<double>() + last;
    }
  }
  EXPECT_NEAR(end, trajectory["duration"].get<double>(), 1e-6);
}

TEST(RunCli, ThePaperTaskOfflineSucceedsAndWritesEveryFile) {
  const TempDirectory directory;
  const RunResult result = run("run" + kBudgets + " --out " + directory.path().string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("SUCCESS: \"put the marker and eraser in the holder\" on panda_desk"));
  EXPECT_THAT(result.output, HasSubstr("goal marker in holder: holds"));
  for (const char* file : {"plan.json", "observation.txt", "observation.json", "prompt.txt", "trajectory.json", "trajectory.csv",
                           "robot_trajectory.json", "report.json", "scene.glb", "viewer.json"}) {
    EXPECT_TRUE(fs::exists(directory.path() / file)) << file;
  }
  const json report = readJson(directory.path() / "report.json");
  ASSERT_TRUE(report.is_object());
  EXPECT_TRUE(report["success"].get<bool>());
  ASSERT_EQ(report["goals"].size(), 2u);
  for (const json& goal : report["goals"]) EXPECT_TRUE(goal["holds"].get<bool>()) << goal.dump();
  ASSERT_EQ(report["actions"].size(), 4u);
  for (const json& action : report["actions"]) EXPECT_EQ(action["status"], "succeeded");
  EXPECT_TRUE(report["verification"]["collision_free"].get<bool>());
  EXPECT_TRUE(report["verification"]["disturbed_objects"].empty());
  for (const char* stage : {"observation", "planning", "grasp", "ik", "motion", "verification", "total"}) {
    EXPECT_TRUE(report["seconds"].contains(stage)) << stage;
  }
  EXPECT_GE(report["counts"]["motion_planner_calls"].get<int>(), 4);
  EXPECT_GT(report["counts"]["ik_calls"].get<int>(), 0);
  EXPECT_GT(report["counts"]["collision_checks"].get<long>(), 0);
  EXPECT_EQ(report["counts"]["llm_calls"].get<int>(), 0);
  EXPECT_TRUE(report["final_poses"].contains("marker"));
  EXPECT_EQ(report["trajectory"]["timing"], "time-optimal");
  EXPECT_EQ(report["trajectory"]["stops_inside_runs"], 0);
  EXPECT_GT(report["trajectory"]["blended_corners"].get<int>(), 0);
  EXPECT_NEAR(report["trajectory"]["duration"].get<double>(), report["trajectory_duration"].get<double>(), 1e-9);
  EXPECT_GT(report["path_length"]["transits_planned"].get<double>(), 0.0);
  EXPECT_LE(report["path_length"]["transits_simplified"].get<double>(), report["path_length"]["transits_planned"].get<double>());
  EXPECT_GT(report["path_length"]["executed"].get<double>(), 0.0);
  EXPECT_EQ(report["actions"][0]["motions"][1]["path_length"].size(), 2u) << "the transit's planned and simplified lengths";
  const json trajectory = readJson(directory.path() / "trajectory.json");
  EXPECT_EQ(trajectory["format_version"], 2);
  EXPECT_EQ(trajectory["robot"], "panda");
  ASSERT_EQ(trajectory["segments"].size(), 4u);
  const json& pick = trajectory["segments"][2];
  EXPECT_EQ(pick["description"], "pick eraser");
  EXPECT_EQ(pick["arm"]["joint_names"][0], "panda_joint1") << "the URDF's own joint names";
  EXPECT_EQ(pick["arm"]["joint_names"].size(), 7u);
  EXPECT_EQ(pick["gripper"]["joint_names"], json::array({"panda_finger_joint1"}));
  expectTimesIncrease(trajectory);
  EXPECT_EQ(readFileText(directory.path() / "trajectory.csv").rfind("action,time,panda_joint1,", 0), 0u);
  const json moveit = readJson(directory.path() / "robot_trajectory.json");
  EXPECT_EQ(moveit["joint_trajectory"]["joint_names"].size(), 7u) << "the arm's joints, as MoveIt executes a group";
  EXPECT_EQ(moveit["joint_trajectory"]["header"]["frame_id"], "panda_link0");
  double last = -1.0;
  for (const json& point : moveit["joint_trajectory"]["points"]) {
    EXPECT_GT(secondsOf(point["time_from_start"]), last);
    last = secondsOf(point["time_from_start"]);
    EXPECT_EQ(point["positions"].size(), 7u);
  }
  EXPECT_NEAR(last, trajectory["duration"].get<double>(), 1e-6);
  const json gripper = readJson(directory.path() / "gripper_trajectory.json");
  EXPECT_EQ(gripper["joint_names"], json::array({"panda_finger_joint1"}));
  for (const auto& [key, value] : gripper.items()) {
    EXPECT_TRUE(key == "header" || key == "joint_names" || key == "points") << key << ": not a JointTrajectory field";
  }
  EXPECT_NEAR(secondsOf(gripper["points"].back()["time_from_start"]), last, 1e-6);
  const json events = readJson(directory.path() / "gripper_events.json")["events"];
  ASSERT_EQ(events.size(), 4u);
  const std::vector<std::pair<std::string, std::string>> expected{
      {"attach", "marker"}, {"detach", "marker"}, {"attach", "eraser"}, {"detach", "eraser"}};
  double previous = 0.0;
  for (std::size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(events[i]["event"], expected[i].first);
    EXPECT_EQ(events[i]["object"], expected[i].second);
    EXPECT_EQ(events[i]["link"], "panda_hand_tcp");
    EXPECT_GT(events[i]["time"].get<double>(), previous);
    previous = events[i]["time"].get<double>();
  }
  EXPECT_EQ(readJson(directory.path() / "plan.json")["actions"].size(), 4u);
  EXPECT_THAT(readFileText(directory.path() / "prompt.txt"), HasSubstr("put the marker and eraser in the holder"));
}

TEST(RunCli, StepsALaterStepUndoesAreNotGoals) {
  // Holding the marker is a step on the way to putting it in the holder, not a goal that fails.
  for (const char* task : {"pick up the marker and then put it in the holder", "grab the eraser, then drop it on the desk"}) {
    const TempDirectory directory;
    const RunResult result = run(std::string("run --task \"") + task + "\"" + kBudgets + " --out " + directory.path().string());
    EXPECT_EQ(result.exitCode, 0) << result.output;
    const json report = readJson(directory.path() / "report.json");
    ASSERT_EQ(report["goals"].size(), 1u) << report["goals"].dump();
    EXPECT_THAT(report["goals"][0]["goal"].get<std::string>(), Not(HasSubstr("holding")));
  }
}

TEST(RunCli, TheSameSeedGivesTheSameTrajectory) {
  const TempDirectory first, second;
  ASSERT_EQ(run("run iiwa14_desk --seed 5" + kBudgets + " --out " + first.path().string()).exitCode, 0);
  ASSERT_EQ(run("run iiwa14_desk --seed 5" + kBudgets + " --out " + second.path().string()).exitCode, 0);
  EXPECT_EQ(readFileText(first.path() / "trajectory.json"), readFileText(second.path() / "trajectory.json"));
}

TEST(RunCli, AnLlmPlanThatCannotBeGroundedIsRepaired) {
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  json unreachable = {{"action", "place"}, {"object", "marker"}, {"params", {{"position", {1.6, 0.0, 0.0}}}}};
  server.enqueueAnswer(json({{"actions", {pickStep("marker"), unreachable}}}).dump());
  server.enqueueAnswer(json({{"actions", {pickStep("marker"), placeIn("marker"), pickStep("eraser"), placeIn("eraser")}}}).dump());
  const TempDirectory directory;
  const std::string environment = "env -u OPENAI_API_KEY OPENAI_BASE_URL=" + server.baseUrl() + " OPENAI_API_KEY=sk-test";
  const RunResult result = run("run --llm openai:gpt-test" + kBudgets + " --out " + directory.path().string(), true, environment);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const json report = readJson(directory.path() / "report.json");
  ASSERT_EQ(report["rounds"].size(), 2u);
  EXPECT_EQ(report["rounds"][0]["outcome"], "grounding failed");
  EXPECT_THAT(report["rounds"][0]["failure"].get<std::string>(), HasSubstr("step 2"));
  EXPECT_EQ(report["counts"]["llm_calls"].get<int>(), 2);
  EXPECT_EQ(report["counts"]["executions"].get<int>(), 2);
  EXPECT_EQ(report["task_planner"], "openai:gpt-test");
  ASSERT_EQ(server.requests().size(), 2u);
  EXPECT_THAT(server.requests()[1].body, HasSubstr("could not be executed"));
}

/// The paper's desk scene with a robot of ../shared/data/kautham at (x, 0) behind the desk, the
/// robot's URDF and the desk objects referred to by absolute paths.
fs::path writeKauthamRobotAtDesk(const fs::path& directory, const fs::path& robot, double x, const std::string& robotExtra = "",
                                 double z = 0.752) {
  const fs::path desk = fs::path(LANG2MANIP_TEST_DATA_DIR) / ".." / ".." / "data" / "models" / "obstacles" / "desk";
  std::string problem = "<Problem name=\"" + robot.stem().string() + "_desk\">\n  <Robot robot=\"" + robot.string() + "\">" + robotExtra +
                        "<Home X=\"" + std::to_string(x) + "\" Y=\"0\" Z=\"" + std::to_string(z) +
                        "\" WX=\"0\" WY=\"0\" WZ=\"1\" TH=\"0\"/></Robot>\n";
  for (const auto& [name, file, ox, oy] : {std::tuple{"desk", "desk.urdf", 0.0, 0.0}, std::tuple{"marker", "marker.urdf", 0.02, -0.18},
                                           std::tuple{"eraser", "eraser.urdf", -0.02, 0.17}, std::tuple{"holder", "pen_holder.urdf", 0.12, 0.02}}) {
    problem += "  <Obstacle obstacle=\"" + (desk / file).string() + "\"><Home X=\"" + std::to_string(ox) + "\" Y=\"" + std::to_string(oy) +
               "\" Z=\"" + (std::string(name) == "desk" ? "0" : "0.75") + "\" WX=\"0\" WY=\"0\" WZ=\"1\" TH=\"0\"/><KauthamName name=\"" + name +
               "\"/></Obstacle>\n";
  }
  const fs::path file = directory / (robot.stem().string() + "_desk.xml");
  std::ofstream(file) << problem + "</Problem>\n";
  return file;
}

// Kautham's TX90 with its Robotiq 2F gripper and UR3e with its OnRobot RG6 (linkage fingers,
// mimic joints, tool frames at the palm, no SRDF) at the desk, unchanged: the paper task runs as
// on the built-in robots.
TEST(RunCli, ThePaperTaskSucceedsWithKauthamsGripperRobots) {
  const auto shared = sharedDataDirectory();
  if (!shared) GTEST_SKIP() << "../shared/data is absent";
  for (const auto& [robot, x] : {std::pair{"tx90_robotniq.urdf", -0.45}, std::pair{"ur3e_gripper_rg6.urdf", -0.25}}) {
    SCOPED_TRACE(robot);
    const TempDirectory directory;
    const fs::path problem = writeKauthamRobotAtDesk(directory.path(), *shared / "kautham/models/robots" / robot, x);
    const RunResult result = run("run " + problem.string() + " --task \"put the marker in the holder\"" + kBudgets + " --out " +
                                 (directory.path() / "out").string());
    EXPECT_EQ(result.exitCode, 0) << result.output;
    EXPECT_THAT(result.output, HasSubstr("SUCCESS"));
    const json report = readJson(directory.path() / "out" / "report.json");
    ASSERT_TRUE(report.is_object());
    EXPECT_TRUE(report["success"].get<bool>());
  }
}

// Franka's official Panda with its hand, expanded from its xacro with its default arguments. Its
// "_sc" links are the real robot's self-collision envelope (capsules 3 cm larger than the arm,
// reaching into the desk): recognised without an SRDF (fixed, no visual, covering their parent)
// and checked only against each other, as a MoveIt configuration does, so the paper task runs as
// the user brings the robot; describe says so.
TEST(RunCli, ThePaperTaskSucceedsWithTheOfficialPandaFromItsXacro) {
  const auto shared = sharedDataDirectory();
  if (!shared) GTEST_SKIP() << "../shared/data is absent";
  const TempDirectory directory;
  const fs::path xacro = *shared / "robots/franka_description/robots/panda/panda.urdf.xacro";
  const fs::path problem = writeKauthamRobotAtDesk(directory.path(), xacro, -0.4, "<XacroArg name=\"hand\" value=\"true\"/>");
  RunResult result = run("check " + problem.string() + " --config 0 -0.785 0 -2.356 0 1.571 0.785 0.04");
  EXPECT_EQ(result.exitCode, 0) << result.output;
  result = run("describe " + problem.string());
  EXPECT_THAT(result.output, HasSubstr("collisions off by default: panda_link0_sc, panda_link1_sc"));
  EXPECT_THAT(result.output, HasSubstr("self-collision envelopes"));
  result = run("run " + problem.string() + " --task \"put the marker in the holder\"" + kBudgets + " --out " +
               (directory.path() / "out").string());
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("SUCCESS"));
}

// Universal Robots' official UR5e from its xacro, with a gripper of our own attached by a xacro
// (tests/data/robots/ur5e_with_gripper.urdf.xacro), on a 20 cm mount: its zero configuration
// (the arm level) would reach into the desk otherwise.
TEST(RunCli, ThePaperTaskSucceedsWithTheOfficialUr5eAndAGripperOfOurOwn) {
  const auto shared = sharedDataDirectory();
  if (!shared) GTEST_SKIP() << "../shared/data is absent";
  const TempDirectory directory;
  const fs::path problem = writeKauthamRobotAtDesk(
      directory.path(), fs::path(LANG2MANIP_TEST_DATA_DIR) / "robots" / "ur5e_with_gripper.urdf.xacro", -0.35, "", 0.95);
  const RunResult result = run("run " + problem.string() + " --task \"put the marker in the holder\"" + kBudgets + " --out " +
                                   (directory.path() / "out").string(),
                               true, "LANG2MANIP_PACKAGE_PATH=" + (*shared / "robots").string());
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("SUCCESS"));
}

// An arm of four joints (no wrist roll: its hand turns with where it is) at the desk: grasps and
// placements take the turn of the hand the arm reaches, where the object still fits between the
// fingers and still stands where it was asked to (tests/data/robots/four_joint_arm.urdf).
TEST(RunCli, AnArmOfFourJointsGraspsAndPlacesAtTheTurnItReaches) {
  const TempDirectory directory;
  const fs::path problem = writeKauthamRobotAtDesk(directory.path(), fs::path(LANG2MANIP_TEST_DATA_DIR) / "robots" / "four_joint_arm.urdf", -0.35);
  const RunResult result = run("run " + problem.string() + " --task \"put the eraser in the holder\"" + kBudgets + " --out " +
                               (directory.path() / "out").string());
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("SUCCESS"));
  const std::string report = readFileText(directory.path() / "out" / "report.json");
  EXPECT_THAT(report, HasSubstr("turned"));
}

// Universal Robots' official UR5e with nothing on its flange: it cannot pick, but it pushes.
TEST(RunCli, ARobotWithoutGripperPushes) {
  const auto shared = sharedDataDirectory();
  if (!shared) GTEST_SKIP() << "../shared/data is absent";
  const TempDirectory directory;
  const fs::path problem = writeKauthamRobotAtDesk(directory.path(), *shared / "robots/ur_description/urdf/ur5e.xacro", -0.35, "", 0.95);
  const std::string environment = "LANG2MANIP_PACKAGE_PATH=" + (*shared / "robots").string();
  RunResult result = run("run " + problem.string() + " --movable eraser --task \"push the eraser 5 cm to the left\"" + kBudgets +
                             " --out " + (directory.path() / "out").string(),
                         true, environment);
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("SUCCESS"));
  const json report = readJson(directory.path() / "out" / "report.json");
  EXPECT_TRUE(report["success"].get<bool>()) << report.dump(2);
  result = run("run " + problem.string() + " --movable eraser --rounds 1 --task \"pick up the eraser\"" + kBudgets + " --out " +
                   (directory.path() / "pick").string(),
               true, environment);
  EXPECT_EQ(result.exitCode, 2) << result.output;
  EXPECT_THAT(result.output, HasSubstr("robot ur5e_robot has no gripper"));
}

// Kautham's own gripper scenes, as they are: which obstacles move is inferred.
TEST(RunCli, APickSucceedsOnKauthamsGripperScenesAsTheyAre) {
  const auto shared = sharedDataDirectory();
  if (!shared) GTEST_SKIP() << "../shared/data is absent";
  for (const auto& [scene, task] : {std::pair{"OMPL_geo_demos/UR3e/ur3e_fib_upc.xml", "pick up the wood piece"},
                                    std::pair{"OMPL_geo_demos/TX90_IOC/OMPL_RRTConnect_TX90_gripper_TwoCan.xml", "pick up the can"}}) {
    SCOPED_TRACE(scene);
    const TempDirectory directory;
    const RunResult result = run("run " + (*shared / "kautham" / scene).string() + " --task \"" + task + "\"" + kBudgets + " --out " +
                                 directory.path().string());
    EXPECT_EQ(result.exitCode, 0) << result.output;
    EXPECT_THAT(result.output, HasSubstr("SUCCESS"));
  }
}

// Kautham's TX90 without its gripper: nothing is movable unless the user says so, and a pick is
// refused with the reason, as a failed step (exit 2), not a crash.
TEST(RunCli, APickByARobotWithoutGripperIsRefusedSayingSo) {
  const auto shared = sharedDataDirectory();
  if (!shared) GTEST_SKIP() << "../shared/data is absent";
  const TempDirectory directory;
  const RunResult result = run("run " + (*shared / "kautham/OMPL_geo_demos/TX90_IOC/OMPL_RRTConnect_TX90_TwoCan.xml").string() +
                               " --movable can --task \"pick up the can\" --rounds 1" + kBudgets + " --out " + directory.path().string());
  EXPECT_EQ(result.exitCode, 2) << result.output;
  EXPECT_THAT(result.output, HasSubstr("pick can: robot TX90 has no gripper"));
  EXPECT_THAT(result.output, HasSubstr("it can move and push"));
}

TEST(BenchTaskCli, RandomizedTrialsPrintSuccessFeasibilityAndTheBaselineRatio) {
  const RunResult result = run("bench task --trials 2 --seed 4 --json", false);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const json figures = json::parse(result.output, nullptr, false);
  ASSERT_TRUE(figures.is_object()) << result.output;
  ASSERT_EQ(figures["results"].size(), 2u);
  for (const json& configuration : figures["results"]) {
    EXPECT_EQ(configuration["trials"].get<int>(), 2);
    if (kBudgets.empty()) {
      EXPECT_GE(configuration["task_success"].get<int>(), 1) << configuration.dump();
    }
    EXPECT_GT(configuration["motion_queries"].get<int>(), 0);
    EXPECT_GT(configuration["seconds_median"].get<double>(), 0.0);
  }
  EXPECT_GT(figures["median_time_ratio"].get<double>(), 0.0);
  const RunResult text = run("bench task --trials 1");
  EXPECT_THAT(text.output, HasSubstr(kBudgets.empty() ? "task success 1/1" : "task success "));
  EXPECT_THAT(text.output, HasSubstr("median time ratio (paper configuration / lang2manip)"));
  EXPECT_THAT(run("bench task --trials 0").output, HasSubstr("--trials must be at least 1"));
  EXPECT_THAT(run("bench task --spread -1").output, HasSubstr("--spread must be a length >= 0"));
  EXPECT_THAT(run("bench task --baseline-ik nope").output, HasSubstr("nope"));
}

TEST(BenchInstructionsCli, ACorpusIsMeasuredPerClassWithItsFailuresNamed) {
  const TempDirectory directory;
  const fs::path corpus = directory.path() / "corpus.tsv";
  std::ofstream(corpus) << "# two classes\ncontainer\texecute\tput the eraser in the holder\n"
                           "rotate\trefuse\trotate the holder by 90 degrees\n"
                           "rotate\texecute\tturn the holder upside down twice\n";
  const RunResult result = run("bench instructions " + corpus.string() + " --problems panda_desk --json", false);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const json figures = json::parse(result.output, nullptr, false);
  ASSERT_TRUE(figures.is_object()) << result.output;
  EXPECT_EQ(figures["classes"]["container"]["execute"], 1);
  if (kBudgets.empty()) {
    EXPECT_EQ(figures["classes"]["container"]["executed_after_repair"], 1);
  }
  EXPECT_EQ(figures["classes"]["rotate"]["refuse"], 1);
  EXPECT_EQ(figures["classes"]["rotate"]["refused_cleanly"], 1);
  ASSERT_GE(figures["failures"].size(), 1u);
  EXPECT_EQ(figures["failures"].back()["line"], 4);
  const RunResult text = run("bench instructions " + corpus.string() + " --problems panda_desk --class rotate");
  EXPECT_THAT(text.output, HasSubstr("first round  after repair"));
  EXPECT_THAT(text.output, HasSubstr("line 4 [rotate, execute]"));
  EXPECT_THAT(run("bench instructions " + corpus.string() + " --class nothing").output, HasSubstr("no instruction of class \"nothing\""));
  EXPECT_THAT(run("bench instructions " + (directory.path() / "none.tsv").string()).output, HasSubstr("none.tsv"));
  EXPECT_THAT(run("bench instructions " + corpus.string() + " --problems nowhere").output, HasSubstr("nowhere"));
}

TEST(RunCliBadInput, EveryArgumentErrorIsNamed) {
  const TempDirectory directory;
  const std::string out = " --out " + (directory.path() / "out").string();
  RunResult result = run("run --task \"  \"" + out);
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("--task must not be empty"));
  result = run("run --planner NotAPlanner" + out);
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("unknown planner \"NotAPlanner\""));
  result = run("run --ik magic" + out);
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("--ik: "));
  EXPECT_THAT(result.output, HasSubstr("magic"));
  EXPECT_THAT(result.output, HasSubstr("dls"));
  result = run("run --arm tentacle" + out);
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("--arm: "));
  EXPECT_THAT(result.output, HasSubstr("unknown manipulator \"tentacle\""));
  result = run("run --rounds 0" + out);
  EXPECT_THAT(result.output, HasSubstr("--rounds 0: must be at least 1"));
  result = run("run --time-limit -1" + out);
  EXPECT_THAT(result.output, HasSubstr("--time-limit must be a positive number"));
  result = run("run --ik-timeout 0" + out);
  EXPECT_THAT(result.output, HasSubstr("--ik-timeout must be a positive number"));
  result = run("run --seed -3" + out);
  EXPECT_THAT(result.output, HasSubstr("--seed -3: must be >= 0"));
  for (const std::string scaling : {"1.5", "0", "-1", "nan", "1e-09"}) {
    result = run("run --velocity-scaling " + scaling + out);
    EXPECT_EQ(result.exitCode, 1) << scaling;
    EXPECT_THAT(result.output, HasSubstr("--velocity-scaling " + scaling + ": must be in [0.01, 1]"));
  }
  result = run("run --acceleration-scaling 0" + out);
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("--acceleration-scaling 0: must be in [0.01, 1]"));
  result = run("run --timing smooth" + out);
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("--timing: unknown trajectory timing \"smooth\" (known: time-optimal, rest-to-rest)"));
  result = run("run no_such_problem" + out);
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("no_such_problem"));
  result = run("run --llm nonsense" + out);
  EXPECT_EQ(result.exitCode, 1);
  std::ofstream(directory.path() / "file") << "x";
  result = run("run --out " + (directory.path() / "file").string());
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("exists and is not a directory"));
  EXPECT_FALSE(fs::exists(directory.path() / "out" / "report.json")) << "bad arguments write nothing";
}

}  // namespace
}  // namespace lang2manip::test
