// The analytic Jacobians (full robot and chain) against central finite differences of FK.

#include <gtest/gtest.h>

#include <string>

#include "kinematics/kinematics_test_robots.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/random.hpp"
#include "lang2manip/kinematics/jacobian.hpp"
#include "lang2manip/kinematics/kinematic_chain.hpp"

namespace lang2manip {
namespace {

constexpr double kStep = 1e-6;
constexpr double kJacobianTolerance = 1e-6;
constexpr int kConfigurations = 20;

/// Rotation vector of R_b * R_a^T (the small rotation from a to b), in the root frame.
Vector3 rotationDifference(const Matrix3& a, const Matrix3& b) {
  const Eigen::AngleAxisd difference(b * a.transpose());
  return difference.angle() * difference.axis();
}

/// Central finite differences of the pose of `link` at point `offset`.
Eigen::MatrixXd numericJacobian(const RobotModel& model, const VectorX& q, int link,
                                const Vector3& offset) {
  Eigen::MatrixXd jacobian(6, model.variableCount());
  KinematicsData plus(model);
  KinematicsData minus(model);
  for (int i = 0; i < model.variableCount(); ++i) {
    VectorX qPlus = q;
    VectorX qMinus = q;
    qPlus[i] += kStep;
    qMinus[i] -= kStep;
    computeForwardKinematics(model, qPlus, plus);
    computeForwardKinematics(model, qMinus, minus);
    const Pose& a = minus.linkPoses[static_cast<std::size_t>(link)];
    const Pose& b = plus.linkPoses[static_cast<std::size_t>(link)];
    jacobian.col(i).head<3>() = (b * offset - a * offset) / (2.0 * kStep);
    jacobian.col(i).tail<3>() = rotationDifference(a.linear(), b.linear()) / (2.0 * kStep);
  }
  return jacobian;
}

class JacobianTest : public ::testing::TestWithParam<std::string> {};

TEST_P(JacobianTest, MatchesFiniteDifferencesForEveryLink) {
  const RobotModel& model = test::kinematicsRobot(GetParam());
  Random random(7);
  KinematicsData data(model);
  Eigen::MatrixXd jacobian(6, model.variableCount());
  for (int sample = 0; sample < kConfigurations; ++sample) {
    const VectorX q = random.uniformVector(model.lowerLimits(), model.upperLimits());
    const Vector3 offset(random.uniform(-0.1, 0.1), random.uniform(-0.1, 0.1),
                         random.uniform(-0.1, 0.1));
    computeForwardKinematics(model, q, data);
    for (int link = 0; link < static_cast<int>(model.links().size()); ++link) {
      computeLinkJacobian(model, data, link, offset, jacobian);
      const Eigen::MatrixXd numeric = numericJacobian(model, q, link, offset);
      ASSERT_LT((jacobian - numeric).cwiseAbs().maxCoeff(), kJacobianTolerance)
          << model.links()[static_cast<std::size_t>(link)].name << "\n" << jacobian << "\n\n"
          << numeric;
    }
  }
}

TEST_P(JacobianTest, ChainJacobianMatchesTheRobotJacobian) {
  const RobotModel& model = test::kinematicsRobot(GetParam());
  Random random(11);
  for (const Manipulator& manipulator : model.semantics().manipulators) {
    const KinematicChain chain(model, manipulator.baseLink, manipulator.toolFrame);
    const VectorX q = random.uniformVector(model.lowerLimits(), model.upperLimits());
    VectorX qc(chain.dof());
    chain.gather(q, qc);
    Pose X_BT = Pose::Identity();
    Jacobian6 chainJacobian(6, chain.dof());
    chain.poseAndJacobian(qc, X_BT, chainJacobian);
    KinematicsData data(model);
    computeForwardKinematics(model, q, data);
    const Pose X_RB = data.linkPoses[static_cast<std::size_t>(model.linkIndex(chain.baseLink()))];
    const Pose X_RT = data.linkPoses[static_cast<std::size_t>(model.linkIndex(chain.tipLink()))];
    EXPECT_TRUE((X_RB * X_BT).isApprox(X_RT, 1e-9)) << manipulator.name;
    // The base is fixed in these robots, so the robot Jacobian is the chain one turned into R.
    const Eigen::MatrixXd robot = computeLinkJacobian(model, q, chain.tipLink());
    for (int i = 0; i < chain.dof(); ++i) {
      const auto variable = chain.variables()[static_cast<std::size_t>(i)];
      EXPECT_LT((X_RB.linear() * chainJacobian.col(i).head<3>() - robot.col(variable).head<3>())
                    .norm(), 1e-9);
      EXPECT_LT((X_RB.linear() * chainJacobian.col(i).tail<3>() - robot.col(variable).tail<3>())
                    .norm(), 1e-9);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltinRobots, JacobianTest,
                         ::testing::Values("panda", "ur5", "iiwa14", "tx90", "yumi"));

TEST(JacobianBadInput, UnknownLinkAndWrongSize) {
  const RobotModel& model = test::kinematicsRobot("panda");
  try {
    (void)computeLinkJacobian(model, model.middleConfiguration(), "no_such_link");
    FAIL() << "no exception";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("panda_link0"), std::string::npos) << error.what();
  }
  EXPECT_THROW((void)computeLinkJacobian(model, VectorX::Zero(2), "panda_link7"), InputError);
}

TEST(KinematicChainBadInput, BaseMustBeAnAncestorOfTheTip) {
  const RobotModel& model = test::kinematicsRobot("panda");
  try {
    KinematicChain chain(model, "panda_link7", "panda_link0");
    FAIL() << "no exception";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("ancestor"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace lang2manip
