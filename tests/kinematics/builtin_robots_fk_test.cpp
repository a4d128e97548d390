// The built-in robot models (data/models/robots) against the published kinematic facts they were
// written from (docs/robots.md): forward kinematics at every reference configuration, joint
// limits, SRDF semantics and the gripper closing directions.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "lang2manip/kinematics/forward_kinematics.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/urdf_reader.hpp"

namespace lang2manip {
namespace {

constexpr double kFkTolerance = 1e-4;
constexpr double kHalfPi = std::numbers::pi / 2.0;

using JointNames = std::vector<std::string>;

const JointNames kPandaArm = {"panda_joint1", "panda_joint2", "panda_joint3", "panda_joint4",
                              "panda_joint5", "panda_joint6", "panda_joint7"};
const JointNames kUr5Arm = {"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                            "wrist_1_joint",      "wrist_2_joint",       "wrist_3_joint"};
const JointNames kIiwaArm = {"iiwa_joint_1", "iiwa_joint_2", "iiwa_joint_3", "iiwa_joint_4",
                             "iiwa_joint_5", "iiwa_joint_6", "iiwa_joint_7"};
const JointNames kTx90Arm = {"joint_1", "joint_2", "joint_3", "joint_4", "joint_5", "joint_6"};
// ABB's chain order 1, 2, 7, 3, 4, 5, 6.
const JointNames kYumiRightArm = {"yumi_joint_1_r", "yumi_joint_2_r", "yumi_joint_7_r",
                                  "yumi_joint_3_r", "yumi_joint_4_r", "yumi_joint_5_r",
                                  "yumi_joint_6_r"};
const JointNames kYumiLeftArm = {"yumi_joint_1_l", "yumi_joint_2_l", "yumi_joint_7_l",
                                 "yumi_joint_3_l", "yumi_joint_4_l", "yumi_joint_5_l",
                                 "yumi_joint_6_l"};

/// The model of built-in robot `name`, read once per test binary.
const RobotModel& builtinRobot(const std::string& name) {
  static std::map<std::string, RobotModelPtr> cache;
  auto found = cache.find(name);
  if (found == cache.end()) {
    found = cache.emplace(name, readUrdfFile(builtinRobotUrdf(name))).first;
  }
  return *found->second;
}

/// A configuration with `values` for the joints `joints` (by name) and 0 elsewhere.
VectorX configuration(const RobotModel& model, const JointNames& joints,
                      const std::vector<double>& values) {
  VectorX q = VectorX::Zero(model.variableCount());
  for (std::size_t i = 0; i < joints.size(); ++i) q[model.variableIndex(joints[i])] = values[i];
  return q;
}

/// Largest coefficient difference of two rotations, up to the sign of the quaternion.
double quaternionError(const Quaternion& a, const Quaternion& b) {
  const double same = (a.coeffs() - b.coeffs()).cwiseAbs().maxCoeff();
  const double opposite = (a.coeffs() + b.coeffs()).cwiseAbs().maxCoeff();
  return std::min(same, opposite);
}

// ------------------------------------------------------------------ FK against robots.md

struct FkReference {
  std::string name;
  std::string robot;
  std::string link;
  JointNames joints;
  std::vector<double> q;
  Vector3 position;
  /// w, x, y, z as in robots.md.
  std::vector<double> wxyz;
};

std::vector<FkReference> fkReferences() {
  return {
      {"panda_zero", "panda", "panda_link8", kPandaArm, {0, 0, 0, 0, 0, 0, 0},
       {0.08800, 0, 0.92600}, {0, 1, 0, 0}},
      {"panda_ready", "panda", "panda_link8", kPandaArm, {0, -0.785, 0, -2.356, 0, 1.571, 0.785},
       {0.30702, 0, 0.59027}, {0, 0.92396, -0.38250, 0}},
      {"panda_random", "panda", "panda_link8", kPandaArm, {0.5, -0.3, 0.2, -1.8, 0.4, 1.2, -0.6},
       {0.27617, 0.31899, 0.64497}, {0.15840, -0.75468, -0.61682, 0.15778}},
      {"panda_tcp_ready", "panda", "panda_hand_tcp", kPandaArm,
       {0, -0.785, 0, -2.356, 0, 1.571, 0.785}, {0.30702, 0, 0.48687}, {0, 1, 0.0002, 0}},
      {"ur5_zero", "ur5", "tool0", kUr5Arm, {0, 0, 0, 0, 0, 0}, {0.81725, 0.19145, -0.00549},
       {0, 0, 0.70711, 0.70711}},
      {"ur5_up", "ur5", "tool0", kUr5Arm, {0, -kHalfPi, 0, -kHalfPi, 0, 0},
       {0, 0.19145, 1.00106}, {0.70711, -0.70711, 0, 0}},
      {"ur5_random", "ur5", "tool0", kUr5Arm, {0.3, -1.2, 1.5, -0.8, 1.1, 0.4},
       {0.56667, 0.32862, 0.32146}, {0.24486, 0.23333, 0.48159, 0.80850}},
      {"iiwa14_zero", "iiwa14", "iiwa_link_ee", kIiwaArm, {0, 0, 0, 0, 0, 0, 0}, {0, 0, 1.30600},
       {1, 0, 0, 0}},
      {"iiwa14_bent", "iiwa14", "iiwa_link_ee", kIiwaArm, {0, 0.5, 0, -1.2, 0, 0.7, 0},
       {0.68313, 0, 0.58414}, {0.36236, 0, 0.93204, 0}},
      {"iiwa14_random", "iiwa14", "iiwa_link_ee", kIiwaArm, {0.3, -0.4, 0.5, -1.5, 0.6, 1.0, -0.7},
       {0.12142, 0.32997, 0.84745}, {0.44934, -0.59354, 0.62691, 0.22977}},
      {"tx90_zero", "tx90", "tool0", kTx90Arm, {0, 0, 0, 0, 0, 0}, {0.05, 0.05, 1.428},
       {1, 0, 0, 0}},
      {"tx90_bent", "tx90", "tool0", kTx90Arm, {0, 0.5, 1.2, 0, 0.8, 0}, {0.73506, 0.05, 0.71610},
       {0.31532, 0, 0.94898, 0}},
      {"tx90_random", "tx90", "tool0", kTx90Arm, {0.4, -0.3, 1.0, 0.6, -0.9, 1.2},
       {0.17164, 0.07883, 1.29827}, {0.51457, 0.15812, -0.17040, 0.82534}},
      {"yumi_right_zero", "yumi", "yumi_link_7_r", kYumiRightArm, {0, 0, 0, 0, 0, 0, 0},
       {0.56446, 0.00153, 0.41839}, {0.37727, -0.87438, 0.06720, -0.29767}},
      {"yumi_right_sync", "yumi", "yumi_link_7_r", kYumiRightArm,
       {0, -2.2689, -2.3562, 0.5236, 0, 0.6981, 0}, {-0.01587, -0.18401, 0.20014},
       {0.52326, -0.11117, 0.84227, 0.06653}},
      {"yumi_right_random", "yumi", "yumi_link_7_r", kYumiRightArm,
       {0.3, -1.0, 0.5, -0.6, 0.4, 0.9, -0.5}, {0.34772, -0.38827, 0.87886},
       {0.55772, -0.41941, -0.13242, -0.70393}},
      {"yumi_left_zero", "yumi", "yumi_link_7_l", kYumiLeftArm, {0, 0, 0, 0, 0, 0, 0},
       {0.56460, -0.00065, 0.41741}, {0.37552, 0.87516, 0.06774, 0.29748}},
      {"yumi_left_sync", "yumi", "yumi_link_7_l", kYumiLeftArm,
       {0, -2.2689, 2.3562, 0.5236, 0, 0.6981, 0}, {-0.01638, 0.18460, 0.20061},
       {0.52253, 0.11125, 0.84285, -0.06476}},
      {"yumi_left_random", "yumi", "yumi_link_7_l", kYumiLeftArm,
       {-0.3, -1.0, -0.5, -0.6, -0.4, 0.9, 0.5}, {0.34784, 0.38726, 0.87948},
       {0.55650, 0.42095, -0.13281, 0.70389}},
  };
}

class BuiltinRobotFkTest : public ::testing::TestWithParam<FkReference> {};

TEST_P(BuiltinRobotFkTest, MatchesPublishedPose) {
  const FkReference& reference = GetParam();
  const RobotModel& model = builtinRobot(reference.robot);
  const VectorX q = configuration(model, reference.joints, reference.q);
  const Pose X_RL = computeLinkPose(model, q, reference.link);
  const Quaternion expected(reference.wxyz[0], reference.wxyz[1], reference.wxyz[2],
                            reference.wxyz[3]);
  const Quaternion actual(X_RL.rotation());
  EXPECT_LT((X_RL.translation() - reference.position).cwiseAbs().maxCoeff(), kFkTolerance)
      << "position " << X_RL.translation().transpose() << ", expected "
      << reference.position.transpose();
  EXPECT_LT(quaternionError(actual, expected), kFkTolerance)
      << "quaternion (w x y z) " << actual.w() << " " << actual.vec().transpose()
      << ", expected " << expected.w() << " " << expected.vec().transpose();
}

INSTANTIATE_TEST_SUITE_P(RobotsMd, BuiltinRobotFkTest, ::testing::ValuesIn(fkReferences()),
                         [](const ::testing::TestParamInfo<FkReference>& testInfo) {
                           return testInfo.param.name;
                         });

// ------------------------------------------------------------------ model structure and limits

/// One manipulator of a built-in robot: tool frame, arm joints (root to tip), gripper joint and
/// its open value (closed is 0 for every built-in gripper).
struct ArmExpectation {
  std::string toolFrame;
  JointNames armJoints;
  std::string gripperJoint;
  double gripperOpen;
};

struct RobotExpectation {
  std::string robot;
  int variableCount;
  std::string root;
  std::vector<ArmExpectation> arms;
};

std::vector<RobotExpectation> robotExpectations() {
  return {
      {"panda", 8, "panda_link0", {{"panda_hand_tcp", kPandaArm, "panda_finger_joint1", 0.04}}},
      {"ur5", 7, "base_link", {{"gripper_tcp", kUr5Arm, "gripper_finger_joint", 0.0425}}},
      {"iiwa14", 8, "iiwa_link_0", {{"gripper_tcp", kIiwaArm, "gripper_finger_joint", 0.0425}}},
      {"tx90", 7, "base_link", {{"gripper_tcp", kTx90Arm, "gripper_finger_joint", 0.0425}}},
      {"yumi",
       16,
       "yumi_body",
       {{"yumi_tcp_r", kYumiRightArm, "gripper_r_joint", 0.025},
        {"yumi_tcp_l", kYumiLeftArm, "gripper_l_joint", 0.025}}},
  };
}

class BuiltinRobotTest : public ::testing::TestWithParam<RobotExpectation> {};

TEST_P(BuiltinRobotTest, HasTheExpectedStructure) {
  const RobotExpectation& expected = GetParam();
  const RobotModel& model = builtinRobot(expected.robot);
  EXPECT_EQ(model.name(), expected.robot);
  EXPECT_EQ(model.links()[static_cast<std::size_t>(model.rootLink())].name, expected.root);
  EXPECT_EQ(model.variableCount(), expected.variableCount);
}

TEST_P(BuiltinRobotTest, ReadsItsSrdf) {
  const RobotExpectation& expected = GetParam();
  const RobotSemantics& semantics = builtinRobot(expected.robot).semantics();
  EXPECT_FALSE(semantics.inferred);
  EXPECT_NE(semantics.source.find(expected.robot + ".srdf"), std::string::npos)
      << semantics.source;
  ASSERT_EQ(semantics.manipulators.size(), expected.arms.size());
  for (const ArmExpectation& arm : expected.arms) {
    const auto manipulator = std::find_if(
        semantics.manipulators.begin(), semantics.manipulators.end(),
        [&arm](const Manipulator& m) { return m.toolFrame == arm.toolFrame; });
    ASSERT_NE(manipulator, semantics.manipulators.end()) << "no manipulator ends at "
                                                         << arm.toolFrame;
    EXPECT_EQ(manipulator->baseLink, expected.root);
    EXPECT_EQ(manipulator->armJoints, arm.armJoints);
    ASSERT_EQ(manipulator->gripperJoints, JointNames{arm.gripperJoint});
    ASSERT_EQ(manipulator->gripperOpen.size(), 1U);
    ASSERT_EQ(manipulator->gripperClosed.size(), 1U);
    EXPECT_NEAR(manipulator->gripperOpen[0], arm.gripperOpen, 1e-12);
    EXPECT_NEAR(manipulator->gripperClosed[0], 0.0, 1e-12);
  }
}

TEST_P(BuiltinRobotTest, HomeStatesAreWithinTheLimits) {
  const RobotExpectation& expected = GetParam();
  const RobotModel& model = builtinRobot(expected.robot);
  std::size_t homes = 0;
  for (const NamedState& state : model.semantics().namedStates) {
    if (state.name == "home") ++homes;
    for (const auto& [joint, value] : state.values) {
      const int variable = model.variableIndex(joint);
      EXPECT_GE(value, model.lowerLimits()[variable]) << state.name << " " << joint;
      EXPECT_LE(value, model.upperLimits()[variable]) << state.name << " " << joint;
    }
  }
  EXPECT_EQ(homes, expected.arms.size());
}

INSTANTIATE_TEST_SUITE_P(Builtin, BuiltinRobotTest, ::testing::ValuesIn(robotExpectations()),
                         [](const ::testing::TestParamInfo<RobotExpectation>& testInfo) {
                           return testInfo.param.robot;
                         });

struct LimitReference {
  std::string robot;
  std::string joint;
  double lower;
  double upper;
  double velocity;
  double effort;  // negative: not given in robots.md, not checked
};

std::vector<LimitReference> limitReferences() {
  constexpr double kPi = std::numbers::pi;
  return {
      {"panda", "panda_joint1", -2.8973, 2.8973, 2.1750, 87},
      {"panda", "panda_joint4", -3.0718, -0.0698, 2.1750, 87},
      {"panda", "panda_joint6", -0.0175, 3.7525, 2.6100, 12},
      {"panda", "panda_finger_joint1", 0.0, 0.04, 0.2, -1},
      {"ur5", "shoulder_pan_joint", -2 * kPi, 2 * kPi, 3.15, 150},
      {"ur5", "elbow_joint", -kPi, kPi, 3.15, 150},
      {"ur5", "wrist_3_joint", -2 * kPi, 2 * kPi, 3.2, 28},
      {"ur5", "gripper_finger_joint", 0.0, 0.0425, 0.15, -1},
      {"iiwa14", "iiwa_joint_1", -2.96706, 2.96706, 1.48353, 320},
      {"iiwa14", "iiwa_joint_4", -2.09440, 2.09440, 1.30900, 176},
      {"iiwa14", "iiwa_joint_7", -3.05433, 3.05433, 2.35619, 40},
      {"tx90", "joint_1", -kPi, kPi, 6.98132, 318},
      {"tx90", "joint_2", -2.26893, 2.57436, 6.98132, 166},
      {"tx90", "joint_5", -2.00713, 2.44346, 8.29031, 29},
      {"tx90", "joint_6", -4.71239, 4.71239, 13.26450, 11},
      {"yumi", "yumi_joint_1_r", -2.94088, 2.94088, 3.14159, -1},
      {"yumi", "yumi_joint_2_l", -2.50455, 0.75922, 3.14159, -1},
      {"yumi", "yumi_joint_7_r", -2.94088, 2.94088, 3.14159, -1},
      {"yumi", "yumi_joint_3_l", -2.15548, 1.39626, 3.14159, -1},
      {"yumi", "yumi_joint_4_r", -5.06145, 5.06145, 6.98132, -1},
      {"yumi", "yumi_joint_5_l", -1.53589, 2.40855, 6.98132, -1},
      {"yumi", "yumi_joint_6_r", -3.99680, 3.99680, 6.98132, -1},
      {"yumi", "gripper_l_joint", 0.0, 0.025, 0.025, -1},
  };
}

class BuiltinRobotLimitTest : public ::testing::TestWithParam<LimitReference> {};

TEST_P(BuiltinRobotLimitTest, MatchesPublishedLimits) {
  const LimitReference& reference = GetParam();
  const RobotModel& model = builtinRobot(reference.robot);
  const int variable = model.variableIndex(reference.joint);
  EXPECT_NEAR(model.lowerLimits()[variable], reference.lower, 1e-9);
  EXPECT_NEAR(model.upperLimits()[variable], reference.upper, 1e-9);
  EXPECT_NEAR(model.velocityLimits()[variable], reference.velocity, 1e-9);
  const JointLimits& limits =
      model.joints()[static_cast<std::size_t>(model.jointIndex(reference.joint))].limits;
  if (reference.effort >= 0) {
    EXPECT_NEAR(limits.effort, reference.effort, 1e-9);
  }
  EXPECT_GT(limits.effort, 0.0);
}

INSTANTIATE_TEST_SUITE_P(RobotsMd, BuiltinRobotLimitTest, ::testing::ValuesIn(limitReferences()),
                         [](const ::testing::TestParamInfo<LimitReference>& testInfo) {
                           return testInfo.param.robot + "_" + testInfo.param.joint;
                         });

// ------------------------------------------------------------------ grippers

struct GripperReference {
  std::string robot;
  std::string gripperJoint;
  double open;
  std::string toolFrame;
  std::string leftFinger;
  std::string rightFinger;
  /// Left finger minus right finger when fully open, in the tool frame: the closing direction.
  Vector3 openSeparation;
};

std::vector<GripperReference> gripperReferences() {
  return {
      {"panda", "panda_finger_joint1", 0.04, "panda_hand_tcp", "panda_leftfinger",
       "panda_rightfinger", {0, 0.08, 0}},
      {"ur5", "gripper_finger_joint", 0.0425, "gripper_tcp", "gripper_left_finger",
       "gripper_right_finger", {0, 0.085, 0}},
      {"iiwa14", "gripper_finger_joint", 0.0425, "gripper_tcp", "gripper_left_finger",
       "gripper_right_finger", {0, 0.085, 0}},
      {"tx90", "gripper_finger_joint", 0.0425, "gripper_tcp", "gripper_left_finger",
       "gripper_right_finger", {0, 0.085, 0}},
      // gripper_r_base is turned by pi about z: the fingers separate along the flange x axis;
      // their frames are 0.013 m apart across the pads.
      {"yumi", "gripper_r_joint", 0.025, "yumi_tcp_r", "gripper_r_finger_l", "gripper_r_finger_r",
       {-0.05, -0.013, 0}},
      {"yumi", "gripper_l_joint", 0.025, "yumi_tcp_l", "gripper_l_finger_l", "gripper_l_finger_r",
       {-0.05, -0.013, 0}},
  };
}

class BuiltinGripperTest : public ::testing::TestWithParam<GripperReference> {};

TEST_P(BuiltinGripperTest, OpensAlongItsClosingDirection) {
  const GripperReference& reference = GetParam();
  const RobotModel& model = builtinRobot(reference.robot);
  VectorX q = VectorX::Zero(model.variableCount());
  const auto separation = [&](double opening) {
    q[model.variableIndex(reference.gripperJoint)] = opening;
    const Pose X_RT = computeLinkPose(model, q, reference.toolFrame);
    const Vector3 left = computeLinkPose(model, q, reference.leftFinger).translation();
    const Vector3 right = computeLinkPose(model, q, reference.rightFinger).translation();
    return Vector3(X_RT.rotation().transpose() * (left - right));
  };
  const Vector3 closed = separation(0.0);
  const Vector3 open = separation(reference.open);
  EXPECT_LT((open - reference.openSeparation).cwiseAbs().maxCoeff(), 1e-9)
      << open.transpose();
  EXPECT_NEAR((open - closed).norm(), 2 * reference.open, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Builtin, BuiltinGripperTest, ::testing::ValuesIn(gripperReferences()),
                         [](const ::testing::TestParamInfo<GripperReference>& testInfo) {
                           return testInfo.param.robot + "_" + testInfo.param.gripperJoint;
                         });

}  // namespace
}  // namespace lang2manip
