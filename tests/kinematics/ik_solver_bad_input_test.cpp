// Bad input to the IK interface: each error is an InputError whose message says what is wrong
// (and lists the valid names where there are names).

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>

#include "kinematics/kinematics_test_robots.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/kinematics/ik_solver.hpp"

namespace lang2manip {
namespace {

void expectInputError(const std::function<void()>& call, const std::string& fragment) {
  try {
    call();
    FAIL() << "no exception; expected one mentioning \"" << fragment << "\"";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
  }
}

IkRequest validRequest() {
  const RobotModel& model = test::kinematicsRobot("panda");
  IkRequest request;
  request.model = &model;
  request.seed = model.middleConfiguration();
  request.target = IkTarget::pose(Vector3(0.4, 0.0, 0.4), Quaternion(0.0, 1.0, 0.0, 0.0));
  return request;
}

class IkSolverBadInput : public ::testing::TestWithParam<std::string> {
 protected:
  void expectRejected(const IkRequest& request, const std::string& fragment) const {
    const auto solver = makeIkSolver(GetParam());
    expectInputError([&] { (void)solver->solve(request); }, fragment);
  }
};

TEST(IkSolverRegistry, UnknownSolverListsTheValidOnes) {
  expectInputError([] { (void)makeIkSolver("trac_ik"); },
                   "unknown IK solver \"trac_ik\"; valid solvers: dls, kdl, kdl_restarts");
  EXPECT_EQ(defaultIkSolverName(), "dls");
  for (const std::string& name : ikSolverNames()) EXPECT_EQ(makeIkSolver(name)->name(), name);
}

TEST_P(IkSolverBadInput, UnknownLinksListTheLinks) {
  IkRequest request = validRequest();
  request.tipLink = "panda_link42";
  expectRejected(request, "panda_hand");
  request.tipLink = "";
  request.baseLink = "world_link";
  expectRejected(request, "panda_link0");
}

TEST_P(IkSolverBadInput, UnknownManipulatorListsTheManipulators) {
  IkRequest request = validRequest();
  request.manipulator = "left_arm";
  expectRejected(request, "valid manipulators: ");
}

TEST_P(IkSolverBadInput, SeedOfTheWrongSizeOrNotFinite) {
  IkRequest request = validRequest();
  request.seed = VectorX::Zero(3);
  expectRejected(request, "IK seed for robot \"panda\" has 3 values");
  request = validRequest();
  request.seed[2] = std::numeric_limits<double>::quiet_NaN();
  expectRejected(request, "is not finite");
}

TEST_P(IkSolverBadInput, LimitsOfTheWrongSize) {
  IkRequest request = validRequest();
  request.lowerLimits = VectorX::Zero(2);
  request.upperLimits = VectorX::Zero(2);
  expectRejected(request, "IK joint limits have 2 and 2 values");
}

TEST_P(IkSolverBadInput, TargetNotFiniteOrQuaternionNotUnit) {
  IkRequest request = validRequest();
  request.target.position.x() = std::numeric_limits<double>::quiet_NaN();
  expectRejected(request, "IK target position is not finite");
  request = validRequest();
  request.target.orientation = Quaternion(1.0, 0.1, 0.0, 0.0);
  expectRejected(request, "not a unit quaternion");
  request.target.orientation = Quaternion(std::numeric_limits<double>::quiet_NaN(), 0, 0, 0);
  expectRejected(request, "IK target orientation is not finite");
  request = validRequest();
  request.target = IkTarget::positionAndAxis(Vector3(0.4, 0, 0.4), Vector3::Zero());
  expectRejected(request, "approach axis must be a finite, non-zero vector");
}

TEST_P(IkSolverBadInput, TimeBudgetMustBePositive) {
  IkRequest request = validRequest();
  request.timeoutSeconds = 0.0;
  expectRejected(request, "IK time budget must be > 0 seconds");
  request.timeoutSeconds = -1.0;
  expectRejected(request, "IK time budget must be > 0 seconds");
}

TEST_P(IkSolverBadInput, NoModelAndBadCounts) {
  IkRequest request = validRequest();
  request.solutionCount = 0;
  expectRejected(request, "IK solution count must be >= 1");
  request = validRequest();
  request.model = nullptr;
  expectRejected(request, "IK request has no robot model");
  request = validRequest();
  request.maxAttempts = -1;
  expectRejected(request, "IK attempt cap must be >= 0");
}

INSTANTIATE_TEST_SUITE_P(EverySolver, IkSolverBadInput, ::testing::ValuesIn(ikSolverNames()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           return param.param;
                         });

}  // namespace
}  // namespace lang2manip
