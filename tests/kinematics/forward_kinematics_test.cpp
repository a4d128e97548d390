#include "lang2manip/kinematics/forward_kinematics.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numbers>

#include "lang2manip/core/random.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "model/model_test_support.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;

RobotModelPtr twoJointArm() { return readUrdfString(test::twoJointUrdf(), "arm.urdf", "."); }

TEST(ForwardKinematics, MatchesHandComputedPoses) {
  const RobotModelPtr model = twoJointArm();
  // shoulder: z-rotation at (0,0,0.3); elbow: y-rotation at (0.5,0,0) in the upper link.
  const double a = std::numbers::pi / 2;
  const double b = 0.3;
  const Pose tip = computeLinkPose(*model, Eigen::Vector2d(a, b), "tip");
  EXPECT_TRUE(tip.translation().isApprox(Vector3(0.0, 0.5, 0.3), 1e-12)) << tip.translation().transpose();
  const Matrix3 expected = (Eigen::AngleAxisd(a, Vector3::UnitZ()) * Eigen::AngleAxisd(b, Vector3::UnitY()))
                               .toRotationMatrix();
  EXPECT_TRUE(tip.linear().isApprox(expected, 1e-12));
}

TEST(ForwardKinematics, WorkspaceResultsEqualTheModelsReferencePoses) {
  const RobotModelPtr model = twoJointArm();
  KinematicsData data(*model);
  Random random(7);
  for (int i = 0; i < 100; ++i) {
    const VectorX q = random.uniformVector(model->lowerLimits(), model->upperLimits());
    computeForwardKinematics(*model, q, data);
    const std::vector<Pose> reference = model->linkPoses(q);
    for (std::size_t l = 0; l < reference.size(); ++l) {
      EXPECT_TRUE(data.linkPoses[l].isApprox(reference[l], 1e-12));
    }
  }
}

TEST(ForwardKinematics, PrismaticAndMimicJoints) {
  const std::string fingers = R"(
  <link name="left"/><link name="right"/>
  <joint name="left_joint" type="prismatic"><parent link="tip"/><child link="left"/>
    <axis xyz="0 1 0"/><limit lower="0" upper="0.04" velocity="1" effort="1"/></joint>
  <joint name="right_joint" type="prismatic"><parent link="tip"/><child link="right"/>
    <axis xyz="0 -1 0"/><limit lower="0" upper="0.04" velocity="1" effort="1"/>
    <mimic joint="left_joint" multiplier="1" offset="0"/></joint>)";
  const RobotModelPtr model = readUrdfString(test::twoJointUrdf(fingers), "hand.urdf", ".");
  ASSERT_EQ(model->variableCount(), 3);
  const VectorX q = Eigen::Vector3d(0, 0, 0.03);
  const Pose left = computeLinkPose(*model, q, "left");
  const Pose right = computeLinkPose(*model, q, "right");
  EXPECT_NEAR((left.translation() - right.translation()).norm(), 0.06, 1e-12);
}

TEST(ForwardKinematics, ConvenienceCallChecksItsArguments) {
  const RobotModelPtr model = twoJointArm();
  EXPECT_THAT(test::errorMessage([&] { computeLinkPose(*model, VectorX::Zero(2), "hand"); }),
              HasSubstr("no link \"hand\"; its links are: base, upper, tip"));
  EXPECT_THAT(test::errorMessage([&] { computeLinkPose(*model, VectorX::Zero(3), "tip"); }),
              HasSubstr("has 3 values"));
  EXPECT_THAT(test::errorMessage([&] { computeLinkPose(*model, Eigen::Vector2d(0, std::nan("")), "tip"); }),
              HasSubstr("not finite"));
}

}  // namespace
}  // namespace lang2manip
