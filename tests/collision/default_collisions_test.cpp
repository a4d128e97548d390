// SRDF <disable_default_collisions> and <enable_collisions>: a link whose collisions are off by
// default (a self-collision envelope) is checked against nothing but the pairs enabled for it.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "collision_test_support.hpp"
#include "lang2manip/model/srdf_writer.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;

/// base -turn-> arm -tilt-> tip, the tip's joint just above an envelope box fixed to the base
/// around the arm.
const char* const kEnvelopeRobot = R"(<robot name="enveloped">
  <link name="base"><collision><origin xyz="0 0 0.05"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="arm"><collision><origin xyz="0 0 0.3"/><geometry><box size="0.05 0.05 0.4"/></geometry></collision></link>
  <link name="envelope"><collision><origin xyz="0 0 0.3"/><geometry><box size="0.25 0.25 0.6"/></geometry></collision></link>
  <link name="tip"><collision><origin xyz="0 0 0.1"/><geometry><box size="0.04 0.04 0.2"/></geometry></collision></link>
  <joint name="turn" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="wrap" type="fixed"><parent link="base"/><child link="envelope"/></joint>
  <joint name="tilt" type="revolute"><parent link="arm"/><child link="tip"/><origin xyz="0 0 0.65"/><axis xyz="0 1 0"/>
    <limit lower="-2.5" upper="2.5" effort="1" velocity="1"/></joint>
</robot>
)";

const char* const kEnvelopeSemantics = R"(<robot name="enveloped">
  <group name="arm"><chain base_link="base" tip_link="tip"/></group>
  <disable_default_collisions link="envelope"/>
  <enable_collisions link1="envelope" link2="tip"/>
</robot>
)";

/// The robot with a box 5 cm beside its arm, inside the envelope; with the SRDF when `semantics`;
/// the envelope drawn (a visual: a real cover, no envelope to infer) when `visible`.
Scene envelopedScene(const TempDirectory& directory, bool semantics, bool visible = false) {
  const auto srdf = directory.path() / "enveloped.srdf";
  std::ofstream(srdf) << kEnvelopeSemantics;
  UrdfReadOptions options;
  if (semantics) options.srdf = srdf;
  std::string urdf = kEnvelopeRobot;
  if (visible) {
    const std::string link = "<link name=\"envelope\">";
    urdf.replace(urdf.find(link), link.size(), link + "<visual><geometry><box size=\"0.25 0.25 0.6\"/></geometry></visual>");
  }
  Scene scene;
  SceneRobot robot;
  robot.name = "enveloped";
  robot.model = readUrdfString(urdf, "enveloped.urdf", directory.path(), options);
  robot.configuration = VectorX::Zero(2);
  scene.addRobot(robot);
  SceneObject post;
  post.name = "post";
  post.kind = "post";
  post.pose.translation() = Vector3(0.1, 0.0, 0.4);
  post.collisions.push_back(Shape{Box{Vector3(0.04, 0.04, 0.2)}, Pose::Identity(), std::nullopt, "post"});
  scene.addObject(post);
  return scene;
}

TEST(DefaultCollisions, ALinkWhoseDefaultIsOffTouchesTheWorldFreely) {
  const TempDirectory directory;
  const Scene plain = envelopedScene(directory, false, true);
  const FclCollisionChecker strict(plain);
  const CollisionReport hit = strict.checkState(0, VectorX::Zero(2), {}, *strict.makeContext());
  EXPECT_FALSE(hit.valid);
  EXPECT_THAT(contactList(hit), HasSubstr("enveloped/envelope - post"));
  // Without an SRDF, a fixed link without a visual covering its parent is taken for an envelope.
  const Scene inferred = envelopedScene(directory, false);
  EXPECT_EQ(inferred.robots()[0].model->semantics().defaultCollisionsDisabled, std::vector<std::string>{"envelope"});
  const FclCollisionChecker guessed(inferred);
  EXPECT_TRUE(guessed.isStateValid(0, VectorX::Zero(2), *guessed.makeContext()));
  const Scene quiet = envelopedScene(directory, true);
  const FclCollisionChecker checker(quiet);
  const auto context = checker.makeContext();
  EXPECT_TRUE(checker.isStateValid(0, VectorX::Zero(2), *context)) << contactList(checker.checkState(0, VectorX::Zero(2), {}, *context));
  // The tip is still checked against the world and, enabled, against the envelope.
  const AllowedCollisionMatrix& matrix = checker.allowedCollisions(0);
  const RobotModel& model = *quiet.robots()[0].model;
  EXPECT_EQ(matrix.reason(model.linkIndex("envelope"), model.linkIndex("arm")), AllowedReason::kAdjacent);
  EXPECT_EQ(matrix.reason(model.linkIndex("envelope"), model.linkIndex("tip")), AllowedReason::kNone);
  VectorX folded(2);
  folded << 0.0, 2.5;  // the tip folds down beside the arm, into the envelope
  const CollisionReport self = checker.checkState(0, folded, {}, *context);
  EXPECT_THAT(contactList(self), HasSubstr("enveloped/envelope - enveloped/tip"));
}

/// Two fingers sliding apart along y from a base, their pads meeting face to face when both are
/// at 0 (zero depth) and overlapping by `overlap` metres beyond that at their lower limit.
std::string fingersUrdf(double overlap) {
  const std::string lower = std::to_string(-overlap / 2.0);
  std::string urdf = "<robot name=\"pads\">\n"
                     "  <link name=\"base\"><collision><origin xyz=\"0 0 -0.05\"/><geometry><box size=\"0.1 0.1 0.02\"/></geometry></collision></link>\n";
  for (const char* side : {"left", "right"}) {
    const std::string sign = std::string(side) == "left" ? "" : "-";
    urdf += "  <link name=\"" + std::string(side) + "\"><collision><origin xyz=\"0 " + sign +
            "0.01 0\"/><geometry><box size=\"0.02 0.02 0.04\"/></geometry></collision></link>\n"
            "  <joint name=\"" + side + "_slide\" type=\"prismatic\"><parent link=\"base\"/><child link=\"" + side +
            "\"/><axis xyz=\"0 " + sign + "1 0\"/><limit lower=\"" + lower + "\" upper=\"0.04\" effort=\"1\" velocity=\"1\"/></joint>\n";
  }
  return urdf + "</robot>\n";
}

TEST(SelfContact, LinksWhoseFacesMeetAtZeroDepthTouchAndDeeperOverlapCollides) {
  // Pads that meet face to face (a vendor's closed fingers) touch: the state is free; pressed
  // 4 mm into each other they collide, and the report names the pair. The pair is checked
  // (never/always sampling off), so only the contact tolerance decides.
  const TempDirectory directory;
  Scene scene;
  SceneRobot robot;
  robot.name = "pads";
  robot.model = readUrdfString(fingersUrdf(0.004), "pads.urdf", directory.path(), {});
  robot.configuration = VectorX::Zero(2);
  scene.addRobot(robot);
  FclCheckerSettings settings;
  settings.allowedCollisions.disableNever = false;
  settings.allowedCollisions.disableAlways = false;
  settings.allowedCollisions.disableDefault = false;
  const FclCollisionChecker checker(scene, settings);
  const auto context = checker.makeContext();
  EXPECT_TRUE(checker.isStateValid(0, VectorX::Zero(2), *context)) << contactList(checker.checkState(0, VectorX::Zero(2), {}, *context));
  const VectorX pressed = VectorX::Constant(2, -0.002);
  const CollisionReport report = checker.checkState(0, pressed, {}, *context);
  EXPECT_FALSE(report.valid);
  EXPECT_THAT(contactList(report), HasSubstr("pads/left - pads/right"));
}

TEST(SelfContact, APartNoArmMovesThatOverlapsWhereTheRobotStartsIsAllowed) {
  // A bellows on a slide of its own under the torso (the arm's first joint lifts the torso; no
  // arm joint drives the slide) sits 2 cm into the base at 0, as a vendor left it; the arm is
  // checked against it as ever.
  const TempDirectory directory;
  Scene scene;
  SceneRobot robot;
  robot.name = "torso";
  robot.model = readUrdfString(R"(<robot name="torso">
  <link name="base"><collision><origin xyz="0 0 0.05"/><geometry><box size="0.3 0.3 0.1"/></geometry></collision></link>
  <link name="bellows"><collision><origin xyz="0.3 0 -0.04"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="torso"><collision><origin xyz="0 0 0.1"/><geometry><box size="0.04 0.04 0.1"/></geometry></collision></link>
  <link name="upper"><collision><origin xyz="0 0 0.25"/><geometry><box size="0.04 0.04 0.3"/></geometry></collision></link>
  <link name="fore"><collision><origin xyz="0 0 0.15"/><geometry><box size="0.04 0.04 0.3"/></geometry></collision></link>
  <joint name="lift" type="prismatic"><parent link="base"/><child link="torso"/><origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="0.3" effort="1" velocity="1"/></joint>
  <joint name="bellows_slide" type="prismatic"><parent link="torso"/><child link="bellows"/><origin xyz="-0.12 0 0"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="0.3" effort="1" velocity="1"/></joint>
  <joint name="shoulder" type="revolute"><parent link="torso"/><child link="upper"/><origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/><origin xyz="0 0 0.4"/><axis xyz="0 1 0"/>
    <limit lower="-2.5" upper="2.5" effort="1" velocity="1"/></joint>
  <link name="wrist"/><link name="hand"><collision><origin xyz="0 0 0.02"/><geometry><box size="0.04 0.04 0.04"/></geometry></collision></link>
  <link name="fore_roll"/>
  <joint name="forearm_roll" type="revolute"><parent link="fore"/><child link="fore_roll"/><origin xyz="0 0 0.3"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="wrist_pitch" type="revolute"><parent link="fore_roll"/><child link="wrist"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="wrist_roll" type="revolute"><parent link="wrist"/><child link="hand"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
</robot>)",
                               "torso.urdf", directory.path(), {});
  robot.configuration = VectorX::Zero(7);
  scene.addRobot(robot);
  ASSERT_FALSE(robot.model->semantics().manipulators.empty());
  ASSERT_EQ(robot.model->semantics().manipulators.front().armJoints, (std::vector<std::string>{"lift", "shoulder", "elbow", "forearm_roll", "wrist_pitch", "wrist_roll"}));
  const FclCollisionChecker checker(scene);
  const RobotModel& model = *scene.robots()[0].model;
  EXPECT_EQ(checker.allowedCollisions(0).reason(model.linkIndex("base"), model.linkIndex("bellows")), AllowedReason::kDefault);
  EXPECT_EQ(allowedReasonName(AllowedReason::kDefault), "default");
  const auto context = checker.makeContext();
  EXPECT_TRUE(checker.isStateValid(0, VectorX::Zero(7), *context)) << contactList(checker.checkState(0, VectorX::Zero(7), {}, *context));
  // Only parts no arm joint drives: the arm's links are not allowed against the bellows for
  // where they stand at 0.
  for (const char* link : {"torso", "upper", "fore", "hand"}) {
    EXPECT_NE(checker.allowedCollisions(0).reason(model.linkIndex(link), model.linkIndex("bellows")), AllowedReason::kDefault) << link;
    EXPECT_NE(checker.allowedCollisions(0).reason(model.linkIndex(link), model.linkIndex("base")), AllowedReason::kDefault) << link;
  }
}

TEST(DefaultCollisions, AreWrittenBackByTheSrdfWriter) {
  const TempDirectory directory;
  const Scene quiet = envelopedScene(directory, true);
  const RobotModel& model = *quiet.robots()[0].model;
  const std::string written = srdfString(model, model.semantics());
  EXPECT_THAT(written, HasSubstr("<disable_default_collisions link=\"envelope\"/>"));
  EXPECT_THAT(written, HasSubstr("<enable_collisions link1=\"envelope\" link2=\"tip\"/>"));
}

}  // namespace
}  // namespace lang2manip::test
