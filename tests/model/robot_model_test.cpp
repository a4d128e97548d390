#include "lang2manip/model/robot_model.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>
#include <numbers>

#include "model_test_support.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;
using test::errorMessage;

Joint revolute(const std::string& name, const std::string& parent, const std::string& child) {
  Joint joint;
  joint.name = name;
  joint.type = JointType::kRevolute;
  joint.parentLink = parent;
  joint.childLink = child;
  joint.limits = {-1.0, 1.0, 1.0, 1.0, false};
  return joint;
}

RobotModelData chainData() {
  RobotModelData data;
  data.name = "chain";
  data.source = "chain.urdf";
  // Links and joints deliberately out of order.
  data.links = {{"c", {}, {}}, {"a", {}, {}}, {"b", {}, {}}};
  data.joints = {revolute("j2", "b", "c"), revolute("j1", "a", "b")};
  return data;
}

TEST(RobotModelTest, OrdersLinksAndJointsParentFirst) {
  const RobotModel model(chainData());
  EXPECT_EQ(model.links()[0].name, "a");
  EXPECT_EQ(model.joints()[0].name, "j1");
  EXPECT_EQ(model.variableNames(), (std::vector<std::string>{"j1", "j2"}));
  EXPECT_EQ(model.parentJoint(model.linkIndex("c")), model.jointIndex("j2"));
  EXPECT_EQ(model.parentJoint(model.rootLink()), -1);
}

TEST(RobotModelTest, MimicJointsFollowTheirSource) {
  RobotModelData data = chainData();
  data.links.push_back({"d", {}, {}});
  Joint mimic = revolute("j3", "c", "d");
  mimic.mimic = JointMimic{"j1", -2.0, 0.1};
  data.joints.push_back(mimic);
  const RobotModel model(std::move(data));
  EXPECT_EQ(model.variableCount(), 2);
  const VectorX q = Eigen::Vector2d(0.3, 0.0);
  EXPECT_NEAR(model.jointValue(model.jointIndex("j3"), q), -0.5, 1e-12);
  EXPECT_THAT(errorMessage([&] { static_cast<void>(model.variableIndex("j3")); }),
              HasSubstr("no joint variable \"j3\"; its variables are: j1, j2"));
}

TEST(RobotModelTest, JointTransformsComposeIntoLinkPoses) {
  RobotModelData data = chainData();
  data.joints[0].origin.translation() = Vector3(1, 0, 0);  // j2: b -> c
  const RobotModel model(std::move(data));
  const std::vector<Pose> poses = model.linkPoses(Eigen::Vector2d(std::numbers::pi / 2, 0.0));
  EXPECT_TRUE(poses[static_cast<std::size_t>(model.linkIndex("c"))].translation().isApprox(
      Vector3(0, 1, 0), 1e-12));
}

TEST(RobotModelTest, RejectsCycleTwoRootsDuplicatesAndUnknownLinks) {
  RobotModelData twoRoots = chainData();
  twoRoots.links.push_back({"lonely", {}, {}});
  EXPECT_THAT(errorMessage([&] { RobotModel{twoRoots}; }),
              HasSubstr("chain.urdf: robot \"chain\" has 2 root links"));
  RobotModelData cycle = chainData();
  cycle.joints.push_back(revolute("j0", "c", "a"));
  EXPECT_THAT(errorMessage([&] { RobotModel{cycle}; }), HasSubstr("cycle"));
  RobotModelData duplicate = chainData();
  duplicate.links.push_back({"a", {}, {}});
  EXPECT_THAT(errorMessage([&] { RobotModel{duplicate}; }), HasSubstr("link \"a\" is defined twice"));
  RobotModelData unknown = chainData();
  unknown.joints[0].childLink = "zz";
  EXPECT_THAT(errorMessage([&] { RobotModel{unknown}; }), HasSubstr("unknown link \"zz\""));
  RobotModelData twoParents = chainData();
  twoParents.joints.push_back(revolute("j9", "a", "c"));
  EXPECT_THAT(errorMessage([&] { RobotModel{twoParents}; }), HasSubstr("two parent joints"));
}

TEST(RobotModelTest, RejectsBadNumbers) {
  RobotModelData nanLimit = chainData();
  nanLimit.joints[0].limits.upper = std::nan("");
  EXPECT_THAT(errorMessage([&] { RobotModel{nanLimit}; }), HasSubstr("finite"));
  RobotModelData inverted = chainData();
  inverted.joints[0].limits = {1.0, -1.0, 1.0, 1.0, false};
  EXPECT_THAT(errorMessage([&] { RobotModel{inverted}; }), HasSubstr("above upper limit"));
  RobotModelData zeroAxis = chainData();
  zeroAxis.joints[0].axis = Vector3::Zero();
  EXPECT_THAT(errorMessage([&] { RobotModel{zeroAxis}; }), HasSubstr("zero or non-finite axis"));
  RobotModelData badMimic = chainData();
  badMimic.joints[0].mimic = JointMimic{"nope", 1.0, 0.0};
  EXPECT_THAT(errorMessage([&] { RobotModel{badMimic}; }), HasSubstr("mimics unknown joint \"nope\""));
}

TEST(RobotModelTest, ChecksConfigurationsAndNames) {
  const RobotModel model(chainData());
  EXPECT_THAT(errorMessage([&] { model.checkConfiguration(VectorX::Zero(3), "start"); }),
              HasSubstr("start for robot \"chain\" has 3 values; the robot has 2 joint variables (j1, j2)"));
  EXPECT_THAT(errorMessage([&] { model.checkConfiguration(Eigen::Vector2d(0, std::nan("")), "q"); }),
              HasSubstr("value of joint \"j2\" is not finite"));
  EXPECT_THAT(errorMessage([&] { static_cast<void>(model.linkIndex("hand")); }),
              HasSubstr("no link \"hand\"; its links are: a, b, c"));
  EXPECT_THAT(errorMessage([&] { static_cast<void>(model.namedConfiguration("home")); }),
              HasSubstr("no named state \"home\""));
}

TEST(RobotModelTest, ContinuousJointsSpanOneTurn) {
  RobotModelData data = chainData();
  data.joints[1].type = JointType::kContinuous;
  const RobotModel model(std::move(data));
  EXPECT_NEAR(model.upperLimits()[0] - model.lowerLimits()[0], 2 * std::numbers::pi, 1e-12);
}

TEST(RobotModelTest, AccelerationAndJerkLimitsAreUnknownUnlessGivenAndMustBePositive) {
  RobotModelData data = chainData();
  data.joints[1].limits.acceleration = 4.0;  // j1 (the joints are listed child first)
  const RobotModel model(data);
  EXPECT_EQ(model.accelerationLimit(model.variableIndex("j1")), 4.0);
  EXPECT_FALSE(model.accelerationLimit(model.variableIndex("j2")));
  EXPECT_FALSE(model.jerkLimit(model.variableIndex("j1")));
  data.joints[1].limits.acceleration = 0.0;
  EXPECT_EQ(errorMessage([&] { RobotModel{data}; }),
            "chain.urdf: joint \"j1\" acceleration limit must be a positive finite number, got 0");
  data.joints[1].limits.acceleration.reset();
  data.joints[1].limits.jerk = std::numeric_limits<double>::infinity();
  EXPECT_EQ(errorMessage([&] { RobotModel{data}; }),
            "chain.urdf: joint \"j1\" jerk limit must be a positive finite number, got inf");
}

TEST(RobotModelTest, SetJointLimitsChecksAndUpdatesTheVariableLimits) {
  RobotModelData data = chainData();
  data.joints[0].type = JointType::kContinuous;  // j2
  RobotModel model(std::move(data));
  const int j1 = model.jointIndex("j1");
  JointLimits limits = model.joints()[static_cast<std::size_t>(j1)].limits;
  limits.lower = -0.5;
  limits.velocity = 3.0;
  limits.acceleration = 6.0;
  limits.jerk = 60.0;
  model.setJointLimits(j1, limits);
  const int v1 = model.variableIndex("j1");
  EXPECT_EQ(model.lowerLimits()[v1], -0.5);
  EXPECT_EQ(model.velocityLimits()[v1], 3.0);
  EXPECT_EQ(model.accelerationLimit(v1), 6.0);
  EXPECT_EQ(model.jerkLimit(v1), 60.0);
  // A continuous joint keeps its turn whatever the limits say.
  const int j2 = model.jointIndex("j2");
  model.setJointLimits(j2, limits);
  EXPECT_NEAR(model.lowerLimits()[model.variableIndex("j2")], -std::numbers::pi, 1e-12);
  // Bad limits are refused and change nothing.
  limits.lower = 2.0;
  EXPECT_THAT(errorMessage([&] { model.setJointLimits(j1, limits); }),
              HasSubstr("chain.urdf: joint \"j1\" has lower limit 2 above upper limit 1"));
  limits.lower = -0.5;
  limits.acceleration = -1.0;
  EXPECT_THAT(errorMessage([&] { model.setJointLimits(j1, limits); }), HasSubstr("acceleration limit must be a positive"));
  EXPECT_EQ(model.accelerationLimit(v1), 6.0);
  EXPECT_EQ(model.lowerLimits()[v1], -0.5);
}

}  // namespace
}  // namespace lang2manip
