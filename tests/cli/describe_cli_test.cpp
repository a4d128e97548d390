// `lang2manip describe`: what was understood of robots and objects, and --write-srdf; --movable
// and --fixed on the commands that load problems.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_run.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

/// A two-joint arm whose fingers turn on hinges 6 cm apart (the right one a mimic), no SRDF.
const char* const kHingedGripperRobot = R"(<robot name="hinged">
  <link name="base"/>
  <link name="upper"><collision><origin xyz="0 0 0.2"/><geometry><box size="0.05 0.05 0.4"/></geometry></collision></link>
  <link name="palm"><collision><origin xyz="0 0 0.02"/><geometry><box size="0.06 0.12 0.04"/></geometry></collision></link>
  <link name="left"><collision><origin xyz="0 0.005 0.03"/><geometry><box size="0.02 0.01 0.06"/></geometry></collision></link>
  <link name="right"><collision><origin xyz="0 -0.005 0.03"/><geometry><box size="0.02 0.01 0.06"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="wrist" type="revolute"><parent link="upper"/><child link="palm"/><origin xyz="0 0 0.4"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="left_hinge" type="revolute"><parent link="palm"/><child link="left"/><origin xyz="0 0.03 0.04"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>
  <joint name="right_hinge" type="revolute"><parent link="palm"/><child link="right"/><origin xyz="0 -0.03 0.04"/>
    <axis xyz="1 0 0"/><limit lower="-0.5" upper="0" effort="1" velocity="1"/><mimic joint="left_hinge" multiplier="-1"/></joint>
</robot>
)";

/// The hinged robot without its fingers (a bare palm), written as bare.urdf in `directory`.
fs::path writeBareRobot(const TempDirectory& directory) {
  std::string robot = kHingedGripperRobot;
  robot.erase(robot.find("  <joint name=\"left_hinge\""), robot.find("</robot>") - robot.find("  <joint name=\"left_hinge\""));
  robot.erase(robot.find("  <link name=\"left\">"), robot.find("  <joint name=\"shoulder\"") - robot.find("  <link name=\"left\">"));
  const fs::path urdf = directory.path() / "bare.urdf";
  std::ofstream(urdf) << robot;
  return urdf;
}

TEST(DescribeCli, TheBuiltInPandaIsDescribedFromItsSrdfAndItsFingers) {
  const RunResult result = run("describe panda_desk", false);
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("semantics SRDF"));
  EXPECT_THAT(result.output, HasSubstr("tool frame panda_hand_tcp"));
  EXPECT_THAT(result.output, HasSubstr("gripper: parallel"));
  EXPECT_THAT(result.output, HasSubstr("opening 0 .. 0.08 m between pads"));
  EXPECT_THAT(result.output, HasSubstr("approach axis (0, 0, 1)"));
  EXPECT_THAT(result.output, HasSubstr("measured: 2 of 2 pads' contact faces found on their collision surfaces; approach axis "
                                       "along a tool frame axis; confidence high"));
  EXPECT_THAT(result.output, HasSubstr("object holder: movable, role container (given by its model)"));
}

TEST(DescribeCli, AGripperMeasuredLessSurelySaysSo) {
  // Fingers mounted askew on the palm: the approach axis found between them is oblique to the
  // tool frame, so the description is less sure than the Panda's.
  const TempDirectory directory;
  std::string robot = kHingedGripperRobot;
  for (const char* hinge : {"<origin xyz=\"0 0.03 0.04\"/>", "<origin xyz=\"0 -0.03 0.04\"/>"}) {
    const std::string origin = hinge;
    robot.replace(robot.find(origin), origin.size(), origin.substr(0, origin.size() - 2) + " rpy=\"0.8 0.3 0\"/>");
  }
  std::ofstream(directory.path() / "leaning.urdf") << robot;
  const RunResult result = run("describe " + (directory.path() / "leaning.urdf").string(), false);
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("approach axis oblique to the tool frame; confidence medium")) << result.output;
}

TEST(DescribeCli, AnInferredGripperIsWrittenAsAnSrdfThatReadsBackTheSame) {
  const TempDirectory directory;
  const fs::path urdf = directory.path() / "hinged.urdf";
  std::ofstream(urdf) << kHingedGripperRobot;
  const fs::path srdf = directory.path() / "written.srdf";
  const RunResult inferred = run("describe " + urdf.string() + " --write-srdf " + srdf.string(), false);
  ASSERT_EQ(inferred.exitCode, 0) << inferred.output;
  EXPECT_THAT(inferred.output, HasSubstr("inferred from the kinematic tree"));
  EXPECT_THAT(inferred.output, HasSubstr("arm joints shoulder wrist\n"));
  EXPECT_THAT(inferred.output, HasSubstr("joint left_hinge: open 0, closed 0.5"));
  const std::string written = readFileText(srdf);
  EXPECT_THAT(written, HasSubstr("<chain base_link=\"base\" tip_link=\"palm\"/>"));
  EXPECT_THAT(written, HasSubstr("<group_state name=\"open\" group=\"gripper\">"));
  // The pairs the allowed-collision matrix lets touch, with MoveIt's reasons.
  EXPECT_THAT(written, HasSubstr("reason=\"Adjacent\"/>"));
  // Beside the URDF, under its name, the SRDF is what the robot is read with.
  fs::copy_file(srdf, directory.path() / "hinged.srdf");
  const RunResult reread = run("describe " + urdf.string(), false);
  ASSERT_EQ(reread.exitCode, 0) << reread.output;
  EXPECT_THAT(reread.output, HasSubstr("semantics SRDF"));
  EXPECT_THAT(reread.output, HasSubstr("arm joints shoulder wrist\n"));
  EXPECT_THAT(reread.output, HasSubstr("joint left_hinge: open 0, closed 0.5"));
}

TEST(DescribeCli, ARobotWithoutGripperSaysItCannotPick) {
  const TempDirectory directory;
  const fs::path urdf = writeBareRobot(directory);
  const RunResult result = run("describe " + urdf.string(), false);
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("gripper: none (moves and pushes; cannot pick)"));
  EXPECT_THAT(result.output, HasSubstr("approach axis (0, 0, 1) in the tool frame (the tool frame's +z)"));
}

TEST(DescribeCli, TheApproachAxisIsSetOnTheCommandLineAndKeptInTheSrdf) {
  const TempDirectory directory;
  const fs::path urdf = writeBareRobot(directory);
  const fs::path srdf = directory.path() / "written.srdf";
  const RunResult given = run("describe " + urdf.string() + " --approach-axis=-x --write-srdf " + srdf.string(), false);
  ASSERT_EQ(given.exitCode, 0) << given.output;
  EXPECT_THAT(given.output, HasSubstr("approach axis (-1, 0, 0) in the tool frame (given)"));
  EXPECT_THAT(readFileText(srdf), HasSubstr("<lang2manip_approach group=\"arm\" xyz=\"-1 0 0\"/>"));
  fs::copy_file(srdf, directory.path() / "bare.srdf");
  const RunResult reread = run("describe " + urdf.string(), false);
  EXPECT_THAT(reread.output, HasSubstr("approach axis (-1, 0, 0) in the tool frame (given)")) << reread.output;
  const RunResult slanted = run("describe " + urdf.string() + " --approach-axis arm=1,0,1", false);
  EXPECT_THAT(slanted.output, HasSubstr("approach axis (0.7071, 0, 0.7071)")) << slanted.output;
  // Bad values name the option and what is wrong.
  RunResult bad = run("describe " + urdf.string() + " --approach-axis 0,0,0");
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_THAT(bad.output, HasSubstr("--approach-axis \"0,0,0\": approach axis \"0 0 0\" has no direction"));
  bad = run("describe " + urdf.string() + " --approach-axis sideways");
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_THAT(bad.output, HasSubstr("expected [MANIPULATOR=]AXIS with AXIS one of +x, -x, +y, -y, +z, -z or X,Y,Z"));
  bad = run("describe " + urdf.string() + " --approach-axis left_arm=+z");
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_THAT(bad.output, HasSubstr("approach axis for manipulator \"left_arm\": robot \"hinged\" has the manipulators arm"));
}

TEST(DescribeCli, KauthamsRg6IsMeasured) {
  const auto shared = sharedDataDirectory();
  if (!shared) GTEST_SKIP() << "../shared/data is absent";
  const RunResult result = run("describe --json " + (*shared / "kautham/models/robots/ur3e_gripper_rg6.urdf").string(), false);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const nlohmann::json report = nlohmann::json::parse(result.output);
  const nlohmann::json& gripper = report["robots"][0]["manipulators"][0]["gripper"];
  EXPECT_EQ(gripper["kind"], "parallel");
  EXPECT_NEAR(gripper["opening"]["max"].get<double>(), 0.15, 0.01);
  EXPECT_EQ(gripper["pads"], nlohmann::json({"l_tip", "r_tip"}));
}

TEST(SceneOptionsCli, MovableAndFixedOverrideAndMustNotContradict) {
  const RunResult overridden = run("show panda_desk --fixed marker --movable holder", false);
  ASSERT_EQ(overridden.exitCode, 0) << overridden.output;
  EXPECT_THAT(overridden.output, HasSubstr("marker (marker, fixed)"));
  EXPECT_THAT(overridden.output, HasSubstr("user: fixed: --fixed"));
  EXPECT_THAT(overridden.output, HasSubstr("holder (pen_holder, movable, container)"));
  const RunResult both = run("show panda_desk --movable marker,eraser --fixed eraser");
  EXPECT_EQ(both.exitCode, 1) << both.output;
  EXPECT_THAT(both.output, HasSubstr("object \"eraser\" is named both --movable and --fixed"));
  const RunResult unknown = run("observe panda_desk --movable unicorn");
  EXPECT_EQ(unknown.exitCode, 1) << unknown.output;
  EXPECT_THAT(unknown.output, HasSubstr("unicorn"));
  EXPECT_THAT(unknown.output, Not(HasSubstr("terminate")));
}

}  // namespace
}  // namespace lang2manip::test
