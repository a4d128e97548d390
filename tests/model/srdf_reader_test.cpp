#include "lang2manip/model/srdf_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "model_test_support.hpp"

namespace lang2manip {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using test::errorMessage;

Joint joint(const std::string& name, JointType type, const std::string& parent,
            const std::string& child, double lower = -1.0, double upper = 1.0) {
  Joint result;
  result.name = name;
  result.type = type;
  result.parentLink = parent;
  result.childLink = child;
  result.limits = {lower, upper, 1.0, 1.0, false};
  return result;
}

// base -j1-> l1 -j2-> l2 -fixed-> hand -fixed-> tcp ; hand -finger-> left ; hand -mimic-> right
RobotModelData gripperArm() {
  RobotModelData data;
  data.name = "g";
  for (const char* name : {"base", "l1", "l2", "hand", "tcp", "left", "right"}) {
    data.links.push_back({name, {}, {}});
  }
  data.joints = {joint("j1", JointType::kRevolute, "base", "l1"),
                 joint("j2", JointType::kRevolute, "l1", "l2"),
                 joint("hand_joint", JointType::kFixed, "l2", "hand"),
                 joint("tcp_joint", JointType::kFixed, "hand", "tcp"),
                 joint("finger", JointType::kPrismatic, "hand", "left", 0.0, 0.04),
                 joint("finger_mimic", JointType::kPrismatic, "hand", "right", 0.0, 0.04)};
  data.joints.back().mimic = JointMimic{"finger", 1.0, 0.0};
  return data;
}

const char* kSrdf = R"(<?xml version="1.0"?>
<robot name="g">
  <group name="arm"><chain base_link="base" tip_link="tcp"/></group>
  <group name="hand"><joint name="finger"/><joint name="finger_mimic"/></group>
  <end_effector name="gripper" parent_link="hand" group="hand" parent_group="arm"/>
  <group_state name="home" group="arm"><joint name="j1" value="0.1"/><joint name="j2" value="-0.2"/></group_state>
  <group_state name="open" group="hand"><joint name="finger" value="0.035"/></group_state>
  <group_state name="close" group="hand"><joint name="finger" value="0.001"/></group_state>
  <disable_collisions link1="base" link2="l1" reason="Adjacent"/>
</robot>)";

TEST(SrdfReader, ReadsGroupsStatesPairsAndResolvesTheManipulator) {
  const RobotSemantics semantics = readSrdfString(kSrdf, "g.srdf", gripperArm());
  EXPECT_FALSE(semantics.inferred);
  ASSERT_EQ(semantics.groups.size(), 2U);
  EXPECT_EQ(semantics.groups[0].chains[0], (std::pair<std::string, std::string>{"base", "tcp"}));
  ASSERT_EQ(semantics.disabledCollisions.size(), 1U);
  EXPECT_EQ(semantics.disabledCollisions[0].reason, "Adjacent");
  ASSERT_EQ(semantics.manipulators.size(), 1U);
  const Manipulator& arm = semantics.manipulators[0];
  EXPECT_THAT(arm.armJoints, ElementsAre("j1", "j2"));
  EXPECT_EQ(arm.toolFrame, "tcp");
  EXPECT_THAT(arm.gripperJoints, ElementsAre("finger"));
  EXPECT_THAT(arm.gripperOpen, ElementsAre(0.035));
  EXPECT_THAT(arm.gripperClosed, ElementsAre(0.001));
}

TEST(SrdfReader, InfersArmToolFrameAndGripperWithoutSrdf) {
  const RobotSemantics semantics = inferSemantics(gripperArm());
  EXPECT_TRUE(semantics.inferred);
  ASSERT_EQ(semantics.manipulators.size(), 1U);
  const Manipulator& arm = semantics.manipulators[0];
  EXPECT_THAT(arm.armJoints, ElementsAre("j1", "j2"));
  EXPECT_EQ(arm.toolFrame, "tcp");
  EXPECT_THAT(arm.gripperJoints, ElementsAre("finger"));
  EXPECT_THAT(arm.gripperOpen, ElementsAre(0.04));
  EXPECT_THAT(arm.gripperClosed, ElementsAre(0.0));
}

TEST(SrdfReader, InfersTwoArmsOnATwoArmRobot) {
  RobotModelData data;
  data.name = "dual";
  for (const char* name : {"body", "r1", "r2", "r3", "l1", "l2", "l3"}) data.links.push_back({name, {}, {}});
  data.joints = {joint("r_j1", JointType::kRevolute, "body", "r1"),
                 joint("r_j2", JointType::kRevolute, "r1", "r2"),
                 joint("r_j3", JointType::kRevolute, "r2", "r3"),
                 joint("l_j1", JointType::kRevolute, "body", "l1"),
                 joint("l_j2", JointType::kRevolute, "l1", "l2"),
                 joint("l_j3", JointType::kRevolute, "l2", "l3")};
  const RobotSemantics semantics = inferSemantics(data);
  ASSERT_EQ(semantics.manipulators.size(), 2U);
  EXPECT_THAT(semantics.manipulators[0].armJoints, ElementsAre("r_j1", "r_j2", "r_j3"));
  EXPECT_THAT(semantics.manipulators[1].armJoints, ElementsAre("l_j1", "l_j2", "l_j3"));
  EXPECT_EQ(semantics.manipulators[0].name, "arm_r3");
}

// base -torso (prismatic)-> t -j1-> l1 -j2-> l2 -j3-> hand; hand -finger-> left; hand -mimic-> right
TEST(SrdfReader, APrismaticTorsoIsPartOfTheArmNotAFinger) {
  RobotModelData data = gripperArm();
  data.links.push_back({"t", {}, {}});
  data.joints.push_back(joint("torso", JointType::kPrismatic, "t", "base", 0.0, 0.4));
  data.links.push_back({"world", {}, {}});
  data.joints.push_back(joint("mount", JointType::kFixed, "world", "t"));
  const RobotSemantics semantics = inferSemantics(data);
  ASSERT_EQ(semantics.manipulators.size(), 1U);
  EXPECT_THAT(semantics.manipulators[0].armJoints, ElementsAre("torso", "j1", "j2"));
  EXPECT_THAT(semantics.manipulators[0].gripperJoints, ElementsAre("finger"));
}

TEST(SrdfReader, AServoHornThatTurnsFreelyOnTheHandIsNoFinger) {
  // The fingers slide; the servo that drives them through a linkage the URDF does not hold shows
  // only as a continuous joint turning a horn on the hand.
  RobotModelData data = gripperArm();
  data.links.push_back({"horn", {}, {}});
  data.joints.push_back(joint("servo", JointType::kContinuous, "hand", "horn"));
  const RobotSemantics semantics = inferSemantics(data);
  ASSERT_EQ(semantics.manipulators.size(), 1U);
  EXPECT_THAT(semantics.manipulators[0].armJoints, ElementsAre("j1", "j2"));
  EXPECT_THAT(semantics.manipulators[0].gripperJoints, ElementsAre("finger"));
  EXPECT_THAT(semantics.manipulators[0].idleHandJoints, ElementsAre("servo"));
  EXPECT_EQ(semantics.manipulators[0].gripperOpen.size(), 1U);
}

// An arm carrying a hand of three fingers with three joints each, none a mimic: one gripper.
TEST(SrdfReader, TheFingersOfAHandAreOneGripper) {
  RobotModelData data;
  data.name = "hand";
  for (const char* name : {"base", "l1", "l2", "palm", "mount0", "mount1", "mount2"}) data.links.push_back({name, {}, {}});
  data.joints = {joint("j1", JointType::kRevolute, "base", "l1"), joint("j2", JointType::kRevolute, "l1", "l2"),
                 joint("wrist", JointType::kRevolute, "l2", "palm")};
  for (int f = 0; f < 3; ++f) {
    const std::string finger = "f" + std::to_string(f);
    data.joints.push_back(joint(finger + "_mount", JointType::kFixed, "palm", "mount" + std::to_string(f)));
    std::string parent = "mount" + std::to_string(f);
    for (int k = 0; k < 3; ++k) {
      const std::string link = finger + "_" + std::to_string(k);
      data.links.push_back({link, {}, {}});
      data.joints.push_back(joint(link + "_joint", JointType::kRevolute, parent, link, 0.0, 1.0));
      parent = link;
    }
  }
  const RobotSemantics semantics = inferSemantics(data);
  ASSERT_EQ(semantics.manipulators.size(), 1U);
  EXPECT_THAT(semantics.manipulators[0].armJoints, ElementsAre("j1", "j2", "wrist"));
  EXPECT_EQ(semantics.manipulators[0].gripperJoints.size(), 9U);
  EXPECT_EQ(semantics.manipulators[0].toolFrame, "palm");
}

Shape boxShape(const Vector3& size, const Vector3& centre = Vector3::Zero()) {
  Shape shape;
  shape.geometry = Box{size};
  shape.origin.translation() = centre;
  return shape;
}

TEST(SrdfReader, AMobileManipulatorsWheelsAndHeadAreNotItsDefaultArm) {
  // Two wheels (one continuous joint each) and a pan-tilt head on the base, then the arm: the
  // wheels are no arms, the arm with the gripper comes first (the default), the head after it.
  RobotModelData data = gripperArm();
  for (const char* name : {"left_wheel", "right_wheel", "head_pan_link", "head_tilt_link"}) data.links.push_back({name, {}, {}});
  data.joints.insert(data.joints.begin(), joint("left_wheel_joint", JointType::kContinuous, "base", "left_wheel"));
  data.joints.insert(data.joints.begin(), joint("right_wheel_joint", JointType::kContinuous, "base", "right_wheel"));
  data.joints.insert(data.joints.begin(), joint("head_pan", JointType::kRevolute, "base", "head_pan_link"));
  data.joints.push_back(joint("head_tilt", JointType::kRevolute, "head_pan_link", "head_tilt_link"));
  const RobotSemantics semantics = inferSemantics(data);
  ASSERT_EQ(semantics.manipulators.size(), 2u);
  EXPECT_THAT(semantics.manipulators[0].armJoints, ElementsAre("j1", "j2"));
  EXPECT_FALSE(semantics.manipulators[0].gripperJoints.empty());
  EXPECT_THAT(semantics.manipulators[1].armJoints, ElementsAre("head_pan", "head_tilt"));
}

TEST(SrdfReader, SelfCollisionEnvelopesAreRecognisedWithoutSrdf) {
  // Each arm link carries a fixed, visual-less envelope larger than it and covering it (Franka's
  // *_sc); a sensor on l2 (small, collision only), a cover with a visual and an envelope that
  // covers too little of its link are not envelopes. Envelopes of links 3 or more joints apart
  // are checked against each other, nothing else.
  RobotModelData data = gripperArm();
  for (Link& link : data.links) link.collisions.push_back(boxShape({0.1, 0.1, 0.3}, {0, 0, 0.15}));
  const auto add = [&](const std::string& name, const std::string& parent, Shape shape, bool visual) {
    Link link{name, {}, {std::move(shape)}};
    if (visual) link.visuals = link.collisions;
    data.links.push_back(link);
    data.joints.push_back(joint(name + "_joint", JointType::kFixed, parent, name));
  };
  add("base_sc", "base", boxShape({0.16, 0.16, 0.36}, {0, 0, 0.15}), false);
  add("l1_sc", "l1", boxShape({0.16, 0.16, 0.36}, {0, 0, 0.15}), false);
  add("hand_sc", "hand", boxShape({0.16, 0.16, 0.36}, {0, 0, 0.15}), false);
  add("sensor", "l2", boxShape({0.02, 0.02, 0.02}, {0, 0, 0.3}), false);
  add("cover", "l2", boxShape({0.16, 0.16, 0.36}, {0, 0, 0.15}), true);
  add("offset_shell", "tcp", boxShape({0.16, 0.16, 0.36}, {0, 0, 0.5}), false);
  EXPECT_THAT(selfCollisionEnvelopes(data), ElementsAre("base_sc", "l1_sc", "hand_sc"));
  const RobotSemantics semantics = inferSemantics(data);
  EXPECT_THAT(semantics.defaultCollisionsDisabled, ElementsAre("base_sc", "l1_sc", "hand_sc"));
  // base -> l1 is one joint, base -> hand three, l1 -> hand two.
  EXPECT_THAT(semantics.enabledCollisions, ElementsAre(std::pair<std::string, std::string>{"base_sc", "hand_sc"}));
}

TEST(SrdfReader, AnApproachAxisIsReadNormalized) {
  std::string xml = kSrdf;
  xml.insert(xml.find("</robot>"), "  <lang2manip_approach group=\"arm\" xyz=\"0 0 -2\"/>\n");
  const RobotSemantics semantics = readSrdfString(xml, "g.srdf", gripperArm());
  ASSERT_EQ(semantics.manipulators.size(), 1U);
  ASSERT_TRUE(semantics.manipulators[0].approachAxis.has_value());
  EXPECT_TRUE(semantics.manipulators[0].approachAxis->isApprox(-Vector3::UnitZ(), 1e-15));
  EXPECT_FALSE(readSrdfString(kSrdf, "g.srdf", gripperArm()).manipulators[0].approachAxis.has_value());
}

struct BadSrdf {
  const char* name;
  const char* xml;
  const char* expected;
};

class SrdfReaderBadInput : public ::testing::TestWithParam<BadSrdf> {};

TEST_P(SrdfReaderBadInput, ReportsFileLineAndProblem) {
  EXPECT_THAT(errorMessage([] { readSrdfString(GetParam().xml, "bad.srdf", gripperArm()); }),
              HasSubstr(GetParam().expected));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SrdfReaderBadInput,
    ::testing::Values(
        BadSrdf{"Malformed", "<robot name=\"g\">\n<group name=\"a\">\n</robot>", "bad.srdf:3: malformed XML"},
        BadSrdf{"NotSrdf", "<robots/>", "not an SRDF"},
        BadSrdf{"UnknownLink", "<robot name=\"g\">\n<group name=\"a\"><chain base_link=\"base\" tip_link=\"wrist\"/></group></robot>",
                "bad.srdf:2: <chain> names link \"wrist\", which the robot \"g\" does not have"},
        BadSrdf{"UnknownJoint", "<robot name=\"g\">\n<group name=\"a\"><joint name=\"j7\"/></group></robot>",
                "bad.srdf:2: <joint> names joint \"j7\""},
        BadSrdf{"ChainUpsideDown", "<robot name=\"g\">\n<group name=\"a\"><chain base_link=\"tcp\" tip_link=\"base\"/></group></robot>",
                "link \"base\" is not below link \"tcp\""},
        BadSrdf{"UnknownGroup", "<robot name=\"g\">\n<group_state name=\"home\" group=\"legs\"/></robot>",
                "bad.srdf:2: <group_state> refers to unknown group \"legs\""},
        BadSrdf{"NanValue", "<robot name=\"g\"><group name=\"a\"><joint name=\"j1\"/></group>\n"
                            "<group_state name=\"h\" group=\"a\"><joint name=\"j1\" value=\"nan\"/></group_state></robot>",
                "must be a finite number"},
        BadSrdf{"ApproachWithoutDirection",
                "<robot name=\"g\"><group name=\"arm\"><chain base_link=\"base\" tip_link=\"tcp\"/></group>\n"
                "<lang2manip_approach group=\"arm\" xyz=\"0 0 0\"/></robot>",
                "bad.srdf:2: approach axis \"0 0 0\" has no direction"},
        BadSrdf{"ApproachOfNoArm",
                "<robot name=\"g\">\n<lang2manip_approach group=\"legs\" xyz=\"1 0 0\"/></robot>",
                "bad.srdf:2: <lang2manip_approach> names group \"legs\", which is not an arm with a tool frame (arms: arm)"},
        BadSrdf{"ApproachNotThreeNumbers",
                "<robot name=\"g\">\n<lang2manip_approach group=\"arm\" xyz=\"1 0\"/></robot>",
                "bad.srdf:2: approach axis"},
        BadSrdf{"DefaultOffForAnUnknownLink", "<robot name=\"g\">\n<disable_default_collisions link=\"envelope\"/></robot>",
                "bad.srdf:2: <disable_default_collisions> names link \"envelope\", which the robot \"g\" does not have"},
        BadSrdf{"EnabledPairWithoutSecondLink", "<robot name=\"g\">\n<enable_collisions link1=\"base\"/></robot>",
                "bad.srdf:2: <enable_collisions> needs attribute \"link2\""},
        BadSrdf{"MissingAttribute", "<robot name=\"g\">\n<disable_collisions link1=\"base\"/></robot>",
                "bad.srdf:2: <disable_collisions> needs attribute \"link2\""}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

}  // namespace
}  // namespace lang2manip
