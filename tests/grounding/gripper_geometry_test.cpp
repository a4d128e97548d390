// Gripper descriptions by forward kinematics of the finger geometry: sliding, rotating, mimic-
// driven and reversed fingers, three-finger hands, Kautham's Robotiq and RG6 models, tools without
// gripper, and grippers that cannot grasp.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "grounding_test_support.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/grounding/gripper_geometry.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

/// A two-joint arm ending in a palm box whose +z points away from the arm, then `tool`.
std::string armWith(const std::string& tool) {
  return R"(<robot name="probe">
  <link name="base"/>
  <link name="upper"><collision><origin xyz="0 0 0.2"/><geometry><box size="0.05 0.05 0.4"/></geometry></collision></link>
  <link name="palm"><collision><origin xyz="0 0 0.02"/><geometry><box size="0.06 0.12 0.04"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="wrist" type="revolute"><parent link="upper"/><child link="palm"/><origin xyz="0 0 0.4"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
)" + tool + "</robot>";
}

/// A finger box 1 cm thick, 2 cm wide and 6 cm long hanging along +z from its joint, inner face
/// on the joint's plane facing `inward` (+1: toward +y).
std::string fingerLink(const std::string& name, double inward) {
  char text[400];
  std::snprintf(text, sizeof text,
                R"(<link name="%s"><collision><origin xyz="0 %g 0.03"/><geometry><box size="0.02 0.01 0.06"/></geometry></collision></link>
)",
                name.c_str(), -0.005 * inward);
  return text;
}

RobotModelPtr probe(const std::string& tool, const UrdfReadOptions& options = {}) {
  return readUrdfString(armWith(tool), "probe.urdf", ".", options);
}

/// Sliding fingers whose joint limits run from open (lower) to closed (upper): open is found by
/// the pads' gap, not by the limits.
std::string reversedSlidingFingers() {
  return fingerLink("left", -1) + fingerLink("right", 1) + R"(
  <joint name="left_slide" type="prismatic"><parent link="palm"/><child link="left"/><origin xyz="0 0 0.04"/>
    <axis xyz="0 -1 0"/><limit lower="-0.03" upper="0" effort="1" velocity="1"/></joint>
  <joint name="right_slide" type="prismatic"><parent link="palm"/><child link="right"/><origin xyz="0 0 0.04"/>
    <axis xyz="0 1 0"/><limit lower="-0.03" upper="0" effort="1" velocity="1"/><mimic joint="left_slide"/></joint>
)";
}

/// Fingers hinged 6 cm apart, turning about x; the right one mimics.
std::string rotatingFingers() {
  return fingerLink("left", -1) + fingerLink("right", 1) + R"(
  <joint name="left_hinge" type="revolute"><parent link="palm"/><child link="left"/><origin xyz="0 0.03 0.04"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>
  <joint name="right_hinge" type="revolute"><parent link="palm"/><child link="right"/><origin xyz="0 -0.03 0.04"/>
    <axis xyz="1 0 0"/><limit lower="-0.5" upper="0" effort="1" velocity="1"/><mimic joint="left_hinge" multiplier="-1"/></joint>
)";
}

/// Three fingers 120 degrees apart, each hinged 3 cm from the axis and turning inward.
std::string threeFingers() {
  std::string text;
  for (int f = 0; f < 3; ++f) {
    const double angle = 2.0 * M_PI * f / 3.0;
    const std::string name = "finger" + std::to_string(f);
    char joint[600];
    std::snprintf(joint, sizeof joint,
                  R"(<link name="%s_base"/>
  <joint name="%s_mount" type="fixed"><parent link="palm"/><child link="%s_base"/><origin xyz="0 0 0.04" rpy="0 0 %.17g"/></joint>
  <joint name="%s_hinge" type="revolute"><parent link="%s_base"/><child link="%s"/><origin xyz="0 0.03 0"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.5" effort="1" velocity="1"/>%s</joint>
)",
                  name.c_str(), name.c_str(), name.c_str(), angle, name.c_str(), name.c_str(), name.c_str(),
                  f == 0 ? "" : "<mimic joint=\"finger0_hinge\"/>");
    text += fingerLink(name, -1) + joint;
  }
  return text;
}

TEST(GripperGeometry, TheBuiltInGrippersKeepTheirToolFrameAndOpening) {
  for (const char* robot : {"panda", "ur5", "iiwa14", "tx90", "yumi"}) {
    const Scene scene = deskScene(robot);
    const GripperGeometry gripper = describeGripper(*scene.robots().front().model);
    SCOPED_TRACE(robot);
    EXPECT_EQ(gripper.fingerCount, 2);
    EXPECT_TRUE(gripper.graspFrame.translation().isZero(1e-12)) << "the built-in tool frames are TCPs between the pads";
    EXPECT_GT(gripper.maxOpening, 0.04);
    EXPECT_NEAR(gripper.minOpening, 0.0, 2e-3);
    EXPECT_GT(gripper.padDepth, 0.01);
    EXPECT_GE(gripper.fingerLength, gripper.padDepth);
    EXPECT_EQ(gripper.padLinks.size(), 2u);
  }
  const Scene panda = deskScene("panda");
  EXPECT_NEAR(describeGripper(*panda.robots().front().model).maxOpening, 0.08, 1e-6);
}

/// Sliding fingers (joints 6 cm apart when open, 2 cm when closed) whose 6 cm long body carries
/// a 6 mm lip at its root and a pad raised 2 mm over the outer 3 cm: the pads hold objects.
std::string paddedFingers() {
  std::string text;
  for (const auto& [name, side] : {std::pair{"left", 1.0}, {"right", -1.0}}) {
    char link[900];
    std::snprintf(link, sizeof link, R"(<link name="%s">
    <collision><origin xyz="0 %g 0.03"/><geometry><box size="0.02 0.01 0.06"/></geometry></collision>
    <collision><origin xyz="0 %g 0.0015"/><geometry><box size="0.02 0.006 0.003"/></geometry></collision>
    <collision><origin xyz="0 %g 0.045"/><geometry><box size="0.02 0.002 0.03"/></geometry></collision></link>
  <joint name="%s_slide" type="prismatic"><parent link="palm"/><child link="%s"/><origin xyz="0 %g 0.04"/>
    <axis xyz="0 %g 0"/><limit lower="-0.02" upper="0" effort="1" velocity="1"/>%s</joint>
)",
                  name, 0.005 * side, -0.003 * side, -0.001 * side, name, name, 0.03 * side, side,
                  side > 0 ? "" : R"(<mimic joint="left_slide"/>)");
    text += link;
  }
  return text;
}

TEST(GripperGeometry, TheGapIsMeasuredWhereThePadsMeetAnObject) {
  const GripperGeometry gripper = describeGripper(*probe(paddedFingers()));
  // Between the raised pads, not between the lips at the roots (4.8 cm open, 0.8 cm closed).
  EXPECT_NEAR(gripper.maxOpening, 0.056, 1e-9);
  EXPECT_NEAR(gripper.minOpening, 0.016, 1e-9);
  EXPECT_NEAR(gripper.padDepth, 0.03, 1e-9);
  // The grasp frame is in the middle of the pads (palm frame: 4 cm to the roots, then 4.5 cm).
  EXPECT_NEAR(gripper.graspFrame.translation().z(), 0.085, 1e-9);
  EXPECT_NEAR(gripper.fingertipOffset(), 0.015, 1e-9);
  // The finger slabs follow the finger: the ones beside the pads stay out of the lips' reach.
  ASSERT_FALSE(gripper.fingerSlabsCurve.empty());
  const double lipsInner = 0.024;
  EXPECT_LT(gripper.fingerBounds.min().y(), -lipsInner + 1e-9);
  for (const AlignedBox3& slab : gripper.fingerSlabsCurve.back()) {
    if (slab.min().z() < 0.0) continue;  // beside the pads, past the grasp frame
    EXPECT_GE(std::min(std::abs(slab.min().y()), std::abs(slab.max().y())), 0.028 - 1e-9);
  }
}

/// One jaw hinged on the palm 1 cm beside a fixed jaw (both 8 cm long along +z); it opens by
/// turning up to 0.6 rad away from the fixed one.
std::string jawAgainstFixedJaw() {
  return R"(<link name="fixed_jaw"><collision><origin xyz="0 -0.005 0.08"/><geometry><box size="0.02 0.01 0.08"/></geometry></collision></link>
  <joint name="fixed_jaw_mount" type="fixed"><parent link="palm"/><child link="fixed_jaw"/></joint>
  <link name="jaw"><collision><origin xyz="0 0.005 0.04"/><geometry><box size="0.02 0.01 0.08"/></geometry></collision></link>
  <joint name="jaw_hinge" type="revolute"><parent link="palm"/><child link="jaw"/><origin xyz="0 0.01 0.04"/><axis xyz="1 0 0"/>
    <limit lower="-0.6" upper="0" effort="1" velocity="1"/></joint>
)";
}

TEST(GripperGeometry, OneJawClosingAgainstAFixedJawIsAGripper) {
  const RobotModelPtr model = probe(jawAgainstFixedJaw());
  const Manipulator& arm = model->semantics().manipulators.front();
  EXPECT_EQ(arm.armJoints, (std::vector<std::string>{"shoulder", "wrist"}));
  EXPECT_EQ(arm.gripperJoints, std::vector<std::string>{"jaw_hinge"});
  const GripperGeometry gripper = describeGripper(*model);
  EXPECT_TRUE(gripper.fixedJaw);
  EXPECT_EQ(gripper.padLinks, (std::vector<std::string>{"jaw", "palm"}));
  // Closed (0 rad) the faces are 1 cm apart; open, the jaw's tip stands 8 sin(0.6) cm farther.
  EXPECT_NEAR(gripper.closedValues.front(), 0.0, 1e-12);
  EXPECT_NEAR(gripper.minOpening, 0.01, 1e-9);
  EXPECT_NEAR(gripper.maxOpening, 0.01 + 0.08 * std::sin(0.6), 1e-9);
  // The jaws reach along the palm's +z: that is where a grasp approaches.
  const Vector3 approachInTool = gripper.graspFrame.linear() * gripper.approachAxis;
  EXPECT_NEAR(approachInTool.z(), 1.0, 1e-9);
}

TEST(GripperGeometry, AWristsLastJointIsNoJaw) {
  // A short flange on a pitch joint: the palm that carries it lies behind its hinge.
  const RobotModelPtr model = probe(R"(<link name="flange"><collision><origin xyz="0 0 0.02"/><geometry><box size="0.03 0.03 0.04"/></geometry></collision></link>
  <joint name="pitch" type="revolute"><parent link="palm"/><child link="flange"/><origin xyz="0 0 0.04"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
)");
  const Manipulator& arm = model->semantics().manipulators.front();
  EXPECT_EQ(arm.armJoints, (std::vector<std::string>{"shoulder", "wrist", "pitch"}));
  EXPECT_TRUE(arm.gripperJoints.empty());
}

TEST(GripperGeometry, AnSrdfWhoseOpenAndClosedStatesAreSwappedIsRefusedWithTheFix) {
  // The pads touch at 0 and are 6 cm apart at -0.03; the SRDF calls 0 "open".
  const TempDirectory directory;
  std::ofstream(directory.path() / "probe.urdf") << armWith(reversedSlidingFingers());
  std::ofstream(directory.path() / "probe.srdf") << R"(<robot name="probe">
    <group name="arm"><chain base_link="base" tip_link="palm"/></group>
    <group name="hand"><joint name="left_slide"/><joint name="right_slide"/></group>
    <group_state name="open" group="hand"><joint name="left_slide" value="0"/></group_state>
    <group_state name="close" group="hand"><joint name="left_slide" value="-0.03"/></group_state>
    <end_effector name="hand" parent_link="palm" group="hand" parent_group="arm"/></robot>)";
  const RobotModelPtr model = readUrdfFile(directory.path() / "probe.urdf");
  EXPECT_THAT([&] { describeGripper(*model); },
              ThrowsMessage<InputError>(AllOf(HasSubstr("gripper of probe/arm: the SRDF's state \"open\" puts the pads 0.0 mm apart"),
                                              HasSubstr("its state \"close\" 60.0 mm: the two are swapped (joint left_slide"),
                                              HasSubstr("swap their values in the SRDF"))));
}

TEST(GripperGeometry, OpeningsComeFromThePadsNotFromTheJointValues) {
  const RobotModelPtr model = probe(reversedSlidingFingers());
  const GripperGeometry gripper = describeGripper(*model);
  // The limits say open = 0 (upper); the pads are 6 cm apart at -0.03 and touch at 0.
  ASSERT_EQ(gripper.gripperJoints, std::vector<std::string>{"left_slide"});
  EXPECT_NEAR(gripper.openValues.front(), -0.03, 1e-12);
  EXPECT_NEAR(gripper.closedValues.front(), 0.0, 1e-12);
  EXPECT_NEAR(gripper.maxOpening, 0.06, 1e-9);
  EXPECT_NEAR(gripper.minOpening, 0.0, 1e-9);
  EXPECT_NEAR(std::abs(gripper.closingAxis.y()), 1.0, 1e-9);
  const VectorX half = withGripperOpening(*model, gripper, model->middleConfiguration(), 0.03);
  EXPECT_NEAR(half[model->variableIndex("left_slide")], -0.015, 1e-6);
  EXPECT_NEAR(gripperOpening(*model, gripper, half), 0.03, 1e-6);
}

TEST(GripperGeometry, RotatingFingersOpenAsTheirGeometrySays) {
  const RobotModelPtr model = probe(rotatingFingers());
  const GripperGeometry gripper = describeGripper(*model);
  // Inner faces on the hinges, 6 cm apart at 0 rad; the upper limit (0.5 rad) swings the 6 cm
  // fingertips 6 * sin(0.5) = 2.88 cm inward each, leaving 2.4 mm: open is the lower limit.
  EXPECT_NEAR(gripper.maxOpening, 0.06, 1e-9);
  EXPECT_NEAR(gripper.minOpening, 0.06 - 0.12 * std::sin(0.5), 1e-9);
  EXPECT_NEAR(gripper.openValues.front(), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(gripper.closingAxis.y()), 1.0, 1e-9);
  EXPECT_EQ(gripper.fingerCount, 2);
  // The palm is the tool frame, 4 cm below the finger roots: the grasp frame moves between the
  // pads, along the approach axis.
  EXPECT_GT(gripper.graspFrame.translation().z(), 0.04);
  EXPECT_NEAR(gripper.graspFrame.translation().y(), 0.0, 1e-9);
  // Widths map back to joint values through forward kinematics, not linearly.
  for (double width : {gripper.minOpening, 0.5 * (gripper.minOpening + gripper.maxOpening), gripper.maxOpening}) {
    const VectorX q = withGripperOpening(*model, gripper, model->middleConfiguration(), width);
    EXPECT_NEAR(gripperOpening(*model, gripper, q), width, 2e-4);
  }
}

TEST(GripperGeometry, AThreeFingerHandIsOneGripper) {
  const RobotModelPtr model = probe(threeFingers());
  const GripperGeometry gripper = describeGripper(*model);
  EXPECT_EQ(gripper.fingerCount, 3);
  EXPECT_EQ(gripper.padLinks.size(), 3u);
  EXPECT_EQ(gripper.gripperJoints, std::vector<std::string>{"finger0_hinge"});
  EXPECT_GT(gripper.maxOpening, gripper.minOpening + 0.01);
  EXPECT_EQ(gripper.fingerLinks.size(), 3u);
}

TEST(GripperGeometry, ACoupledAndADecoupledRobotDescribeTheSameGripper) {
  const RobotModelPtr coupled = probe(rotatingFingers());
  UrdfReadOptions options;
  options.ignoreMimic = true;
  const RobotModelPtr decoupled = probe(rotatingFingers(), options);
  const GripperGeometry a = describeGripper(*coupled);
  const GripperGeometry b = describeGripper(*decoupled);
  EXPECT_EQ(b.gripperJoints, (std::vector<std::string>{"left_hinge", "right_hinge"}));
  EXPECT_NEAR(b.openValues[1], -b.openValues[0], 1e-12);
  EXPECT_NEAR(a.maxOpening, b.maxOpening, 1e-9);
  EXPECT_NEAR(a.minOpening, b.minOpening, 1e-9);
}

TEST(GripperGeometry, AToolWithoutGripperIsDescribedAndCannotPick) {
  const RobotModelPtr model = probe(R"(<link name="tool0"/>
  <joint name="flange" type="fixed"><parent link="palm"/><child link="tool0"/><origin xyz="0 0 0.04"/></joint>
)");
  const GripperGeometry gripper = describeGripper(*model);
  EXPECT_FALSE(gripper.hasGripper());
  EXPECT_EQ(gripper.fingerCount, 0);
  EXPECT_FALSE(gripper.fingerBounds.isEmpty());
  EXPECT_DOUBLE_EQ(gripperOpening(*model, gripper, model->middleConfiguration()), 0.0);
  const std::string reason = noGripperReason(*model, gripper, "pick marker");
  EXPECT_THAT(reason, HasSubstr("pick marker: robot probe has no gripper"));
  EXPECT_THAT(reason, HasSubstr("it can move and push"));
  EXPECT_TRUE(noGripperReason(*probe(rotatingFingers()), describeGripper(*probe(rotatingFingers())), "pick").empty());
}

TEST(GripperGeometry, TheWristBehindAShortFlangeIsSweptAboutItsRoll) {
  // A 12 cm wide wrist, then a roll joint and a 2 cm flange: the wrist turns about the tool's
  // axis, so it reaches 8.5 cm (half its diagonal) from that axis in every direction, 2-6 cm
  // behind the tool frame. After the probe's pitch joint, no sweep is taken.
  const RobotModelPtr model = probe(R"(<link name="wrist_body"><collision><origin xyz="0 0 0.02"/><geometry><box size="0.12 0.12 0.04"/></geometry></collision></link>
  <link name="flange"><collision><origin xyz="0 0 0.01"/><geometry><box size="0.04 0.04 0.02"/></geometry></collision></link>
  <link name="tool0"/>
  <joint name="mount" type="fixed"><parent link="palm"/><child link="wrist_body"/><origin xyz="0 0 0.04"/></joint>
  <joint name="roll" type="revolute"><parent link="wrist_body"/><child link="flange"/><origin xyz="0 0 0.04"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="tip" type="fixed"><parent link="flange"/><child link="tool0"/><origin xyz="0 0 0.02"/></joint>
)");
  const GripperGeometry gripper = describeGripper(*model);
  ASSERT_FALSE(gripper.wristBounds.empty());
  AlignedBox3 wrist;
  for (const AlignedBox3& box : gripper.wristBounds) wrist.extend(box);
  EXPECT_NEAR(wrist.max().x(), 0.06 * std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(wrist.min().y(), -0.06 * std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(wrist.max().z(), -0.02, 1e-6);
  EXPECT_TRUE(describeGripper(*probe(R"(<link name="tool0"/>
  <joint name="flange" type="fixed"><parent link="palm"/><child link="tool0"/><origin xyz="0 0 0.04"/></joint>
)")).wristBounds.empty());
}

TEST(GripperGeometry, TheApproachAxisCanBeGiven) {
  const std::string flange = R"(<link name="tool0"/>
  <joint name="flange" type="fixed"><parent link="palm"/><child link="tool0"/><origin xyz="0 0 0.04"/></joint>
)";
  // A tool without gripper approaches along its +z unless told otherwise.
  UrdfReadOptions sideways;
  sideways.approachAxes[""] = Vector3(-2, 0, 0);
  const RobotModelPtr bare = probe(flange);
  const RobotModelPtr turned = probe(flange, sideways);
  EXPECT_TRUE(describeGripper(*bare).graspFrame.linear().isIdentity(1e-12));
  const GripperGeometry tool = describeGripper(*turned);
  const Matrix3 R_TH = tool.graspFrame.linear();
  EXPECT_TRUE((R_TH * tool.approachAxis).isApprox(-Vector3::UnitX(), 1e-12));
  EXPECT_NEAR(R_TH.determinant(), 1.0, 1e-12);
  // The palm reaches 4 cm behind the flange along the old +z: now across the approach axis.
  EXPECT_NEAR(describeGripper(*bare).fingerReachBehind(), 0.04, 1e-9);
  EXPECT_NEAR(tool.fingerReachBehind(), 0.03, 1e-9);
  // A gripper's measured approach (+z here) can be overridden by a direction the fingers close across.
  UrdfReadOptions wrongName;
  wrongName.approachAxes["left_arm"] = Vector3(1, 0, 0);
  EXPECT_THAT([&] { (void)probe(rotatingFingers(), wrongName); },
              ThrowsMessage<InputError>(HasSubstr("approach axis for manipulator \"left_arm\": robot \"probe\" has the manipulators")));
  const RobotModelPtr given = probe(rotatingFingers(), sideways);
  const GripperGeometry fingers = describeGripper(*given);
  EXPECT_TRUE((fingers.graspFrame.linear() * fingers.approachAxis).isApprox(-Vector3::UnitX(), 1e-12));
  UrdfReadOptions acrossTheFingers;
  acrossTheFingers.approachAxes[""] = Vector3(0, 1, 0);
  EXPECT_THAT([&] { (void)describeGripper(*probe(rotatingFingers(), acrossTheFingers)); },
              ThrowsMessage<InputError>(HasSubstr("it does not open")));
  EXPECT_THAT([&] { (void)describeGripper(*probe(rotatingFingers(), acrossTheFingers)); },
              ThrowsMessage<InputError>(HasSubstr("or the approach axis given)")));
}

TEST(GripperGeometryBadInput, FingersThatDoNotOpenOrHaveNoGeometryAreRefusedWithTheReason) {
  std::string stuck = rotatingFingers();
  for (const char* limits : {"lower=\"0\" upper=\"0.5\"", "lower=\"-0.5\" upper=\"0\""}) {
    stuck.replace(stuck.find(limits), std::string(limits).size(), "lower=\"0.2\" upper=\"0.2\"");
  }
  try {
    static_cast<void>(describeGripper(*probe(stuck)));
    FAIL() << "a finger whose limits leave it no travel does not open";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("gripper of probe/arm"));
    EXPECT_THAT(error.what(), HasSubstr("do not move across the approach axis"));
  }
  const std::string bare = R"(<link name="left"/><link name="right"/>
  <joint name="left_slide" type="prismatic"><parent link="palm"/><child link="left"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.04" effort="1" velocity="1"/></joint>
  <joint name="right_slide" type="prismatic"><parent link="palm"/><child link="right"/><axis xyz="0 -1 0"/>
    <limit lower="0" upper="0.04" effort="1" velocity="1"/><mimic joint="left_slide"/></joint>
)";
  try {
    static_cast<void>(describeGripper(*probe(bare)));
    FAIL() << "fingers without collision geometry cannot grasp";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("left_slide"));
    EXPECT_THAT(error.what(), HasSubstr("move no link with collision geometry"));
  }
}

TEST(GripperGeometry, KauthamRobotiqAndRg6GrippersOpenAsTheirVendorsSay) {
  const auto shared = sharedDataDirectory();
  if (!shared) GTEST_SKIP() << "../shared/data is absent";
  struct Case {
    const char* file;
    double opening;  // the vendor's stroke (m)
  };
  for (const Case& c : {Case{"kautham/models/robots/tx90_robotniq.urdf", 0.085}, Case{"kautham/models/robots/ur3e_gripper_rg6.urdf", 0.160}}) {
    SCOPED_TRACE(c.file);
    for (bool decoupled : {false, true}) {
      UrdfReadOptions options;
      options.ignoreMimic = decoupled;
      const RobotModelPtr model = readUrdfFile(*shared / c.file, options);
      const GripperGeometry gripper = describeGripper(*model);
      EXPECT_EQ(gripper.fingerCount, 2);
      EXPECT_NEAR(gripper.maxOpening, c.opening, 0.02);
      EXPECT_LT(gripper.minOpening, 0.02);
      EXPECT_GT(gripper.padDepth, 0.01);
      EXPECT_GT(gripper.graspFrame.translation().norm(), 0.05) << "the tool frame is the palm, the pads are ahead of it";
    }
  }
}

}  // namespace
}  // namespace lang2manip::test
