// Conformance suite run against every registered IK solver: FK -> IK -> FK round trips on random
// reachable poses of every built-in arm, joint limits, failure reasons, approach-axis targets and
// several distinct solutions. The success thresholds are per solver and honest: KDL's NR_JL from
// a single seed fails often by design (it is the baseline).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <map>
#include <string>
#include <vector>

#include "kinematics/kinematics_test_robots.hpp"
#include "lang2manip/core/random.hpp"
#include "lang2manip/kinematics/ik_solver.hpp"

namespace lang2manip {
namespace {

/// Generous budgets: 10x the benchmark's in optimized builds, 1000x in Debug/sanitizer builds,
/// whose unoptimized, instrumented Eigen code is some 500x slower (rates must not depend on it).
#ifdef NDEBUG
constexpr double kTimeout = 0.05;
#else
constexpr double kTimeout = 5.0;
#endif
constexpr int kSamples = 40;
/// Slack on the tolerances when re-checking a solution with our own FK.
constexpr double kCheckSlack = 1e-9;

struct ArmCase {
  std::string robot;
  std::string manipulator;
};

const std::vector<ArmCase> kArms = {{"panda", ""},      {"ur5", ""},
                                    {"iiwa14", ""},     {"tx90", ""},
                                    {"yumi", "right_arm"}, {"yumi", "left_arm"}};

/// Minimum round-trip success rate of each solver (pose targets, seed at mid-limits).
double roundTripThreshold(const std::string& solver) {
  static const std::map<std::string, double> thresholds = {
      {"dls", 0.97}, {"kdl_restarts", 0.85}, {"kdl", 0.05}};
  const auto found = thresholds.find(solver);
  return found == thresholds.end() ? 0.9 : found->second;
}

/// Minimum success rate on approach-axis targets (KDL fixes the free rotation from the seed).
double axisThreshold(const std::string& solver) {
  return solver == "dls" ? 0.97 : 0.0;
}

/// Targets of the joint-limit test, and the successes each solver must reach among them (the
/// limits are narrowed to +-0.4 rad about the middle; measured with seed 3: dls and kdl_restarts
/// 20, kdl 17).
constexpr int kLimitSamples = 20;
int limitedThreshold(const std::string& solver) {
  static const std::map<std::string, int> thresholds = {{"dls", 19}, {"kdl_restarts", 18}, {"kdl", 13}};
  const auto found = thresholds.find(solver);
  return found == thresholds.end() ? 18 : found->second;
}

class IkSolverConformance : public ::testing::TestWithParam<std::string> {
 protected:
  [[nodiscard]] std::unique_ptr<IkSolver> solver() const { return makeIkSolver(GetParam()); }

  static IkRequest request(const RobotModel& model, const std::string& manipulator) {
    IkRequest request;
    request.model = &model;
    request.manipulator = manipulator;
    request.seed = model.middleConfiguration();
    request.timeoutSeconds = kTimeout;
    return request;
  }

  static const Manipulator& arm(const RobotModel& model, const std::string& name) {
    for (const Manipulator& manipulator : model.semantics().manipulators) {
      if (name.empty() || manipulator.name == name) return manipulator;
    }
    throw std::runtime_error("no manipulator " + name);
  }

  /// X_BT of the arm's tool frame in its base for configuration q.
  static Pose toolPose(const RobotModel& model, const Manipulator& manipulator, const VectorX& q) {
    const std::vector<Pose> poses = model.linkPoses(q);
    return poses[static_cast<std::size_t>(model.linkIndex(manipulator.baseLink))].inverse() *
           poses[static_cast<std::size_t>(model.linkIndex(manipulator.toolFrame))];
  }

  /// Checks every solution against the request: target met, within limits, seed elsewhere.
  static void expectValid(const IkRequest& request, const Manipulator& manipulator,
                          const IkResult& result, const VectorX& lower, const VectorX& upper) {
    const RobotModel& model = *request.model;
    for (const VectorX& q : result.solutions) {
      double position = 0.0;
      double orientation = 0.0;
      ikTargetError(request.target, toolPose(model, manipulator, q), position, orientation);
      EXPECT_LE(position, request.positionTolerance + kCheckSlack);
      EXPECT_LE(orientation, request.orientationTolerance + kCheckSlack);
      EXPECT_TRUE((q.array() >= lower.array()).all() && (q.array() <= upper.array()).all());
      for (int joint : model.variableJoints()) {
        const std::string& name = model.joints()[static_cast<std::size_t>(joint)].name;
        const bool inArm = std::find(manipulator.armJoints.begin(), manipulator.armJoints.end(),
                                     name) != manipulator.armJoints.end();
        const int variable = model.variableIndex(name);
        if (!inArm) {
          EXPECT_EQ(q[variable], request.seed[variable]) << name;
        }
      }
    }
  }
};

TEST_P(IkSolverConformance, RoundTripOnRandomReachablePoses) {
  const auto ik = solver();
  for (const ArmCase& arm : kArms) {
    const RobotModel& model = test::kinematicsRobot(arm.robot);
    const Manipulator& manipulator = IkSolverConformance::arm(model, arm.manipulator);
    Random random(42);
    int successes = 0;
    for (int sample = 0; sample < kSamples; ++sample) {
      const VectorX q = random.uniformVector(model.lowerLimits(), model.upperLimits());
      IkRequest query = request(model, arm.manipulator);
      query.target = IkTarget::pose(toolPose(model, manipulator, q));
      query.randomSeed = static_cast<std::uint64_t>(sample);
      const IkResult result = ik->solve(query);
      if (result.status == IkStatus::kSuccess) {
        ++successes;
        ASSERT_EQ(result.solutions.size(), 1U);
        EXPECT_TRUE(result.message.empty());
      } else {
        EXPECT_TRUE(result.solutions.empty());
        EXPECT_FALSE(result.message.empty());
      }
      expectValid(query, manipulator, result, model.lowerLimits(), model.upperLimits());
    }
    const double rate = static_cast<double>(successes) / kSamples;
    EXPECT_GE(rate, roundTripThreshold(GetParam())) << arm.robot << " " << arm.manipulator;
    RecordProperty(arm.robot + "_" + arm.manipulator + "_rate", std::to_string(rate));
  }
}

TEST_P(IkSolverConformance, RespectsGivenJointLimits) {
  const RobotModel& model = test::kinematicsRobot("panda");
  const Manipulator& manipulator = arm(model, "");
  const VectorX middle = model.middleConfiguration();
  const VectorX lower = model.lowerLimits().array().max(middle.array() - 0.4).matrix();
  const VectorX upper = model.upperLimits().array().min(middle.array() + 0.4).matrix();
  Random random(3);
  int successes = 0;
  for (int sample = 0; sample < kLimitSamples; ++sample) {
    const VectorX q = random.uniformVector(lower, upper);
    IkRequest query = request(model, "");
    query.lowerLimits = lower;
    query.upperLimits = upper;
    query.target = IkTarget::pose(toolPose(model, manipulator, q));
    const IkResult result = solver()->solve(query);
    successes += result.status == IkStatus::kSuccess ? 1 : 0;
    expectValid(query, manipulator, result, lower, upper);
  }
  EXPECT_GE(successes, limitedThreshold(GetParam())) << successes << " of " << kLimitSamples;
}

TEST_P(IkSolverConformance, ReportsUnreachableTargets) {
  const RobotModel& model = test::kinematicsRobot("ur5");
  IkRequest query = request(model, "");
  query.target = IkTarget::pose(Vector3(5.0, 0.0, 0.0), Quaternion::Identity());
  const IkResult result = solver()->solve(query);
  EXPECT_EQ(result.status, IkStatus::kUnreachable);
  EXPECT_TRUE(result.solutions.empty());
  EXPECT_NE(result.message.find("reaches at most"), std::string::npos) << result.message;
}

TEST_P(IkSolverConformance, ReportsWhyAReachableLookingTargetFails) {
  // Within the reach bound but out of the workspace (behind the panda's base, at the floor).
  const RobotModel& model = test::kinematicsRobot("panda");
  IkRequest query = request(model, "");
  query.timeoutSeconds = 0.01;
  query.target = IkTarget::pose(Vector3(0.0, 0.0, -0.6), Quaternion::Identity());
  const IkResult result = solver()->solve(query);
  EXPECT_NE(result.status, IkStatus::kSuccess);
  EXPECT_FALSE(result.message.empty());
  EXPECT_GT(result.positionError, query.positionTolerance);
}

TEST_P(IkSolverConformance, AnAttemptCapEndsTheSearchWhateverTimeIsLeft) {
  const RobotModel& model = test::kinematicsRobot("panda");
  IkRequest query = request(model, "");
  query.timeoutSeconds = 30.0;
  query.maxAttempts = 3;
  query.target = IkTarget::pose(Vector3(0.0, 0.0, -0.6), Quaternion::Identity());  // out of the workspace
  const IkResult result = solver()->solve(query);
  EXPECT_NE(result.status, IkStatus::kSuccess);
  EXPECT_LE(result.attempts, 3);
  EXPECT_LT(result.seconds, 5.0);
}

TEST_P(IkSolverConformance, SolvesApproachAxisTargets) {
  const RobotModel& model = test::kinematicsRobot("panda");
  const Manipulator& manipulator = arm(model, "");
  Random random(5);
  int successes = 0;
  constexpr int kAxisSamples = 20;
  for (int sample = 0; sample < kAxisSamples; ++sample) {
    const VectorX q = random.uniformVector(model.lowerLimits(), model.upperLimits());
    const Pose X_BT = toolPose(model, manipulator, q);
    IkRequest query = request(model, "");
    query.target = IkTarget::positionAndAxis(X_BT.translation(), X_BT.linear().col(2));
    const IkResult result = solver()->solve(query);
    successes += result.status == IkStatus::kSuccess ? 1 : 0;
    expectValid(query, manipulator, result, model.lowerLimits(), model.upperLimits());
  }
  EXPECT_GE(static_cast<double>(successes) / kAxisSamples, axisThreshold(GetParam()));
}

TEST_P(IkSolverConformance, FindsSeveralDistinctSolutionsNearestFirst) {
  const RobotModel& model = test::kinematicsRobot("panda");
  const Manipulator& manipulator = arm(model, "");
  VectorX q = model.middleConfiguration();
  q[1] += 0.3;
  IkRequest query = request(model, "");
  query.target = IkTarget::pose(toolPose(model, manipulator, q));
  query.solutionCount = 3;
  query.timeoutSeconds = 0.5;
  const IkResult result = solver()->solve(query);
  ASSERT_EQ(result.status, IkStatus::kSuccess) << result.message;
  expectValid(query, manipulator, result, model.lowerLimits(), model.upperLimits());
  if (GetParam() == "kdl") {
    EXPECT_EQ(result.solutions.size(), 1U);  // one attempt gives one solution
    return;
  }
  ASSERT_EQ(result.solutions.size(), 3U);
  for (std::size_t i = 1; i < result.solutions.size(); ++i) {
    EXPECT_LE((result.solutions[i - 1] - query.seed).norm(),
              (result.solutions[i] - query.seed).norm());
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_GT((result.solutions[i] - result.solutions[j]).cwiseAbs().maxCoeff(), 1e-3);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(EverySolver, IkSolverConformance,
                         ::testing::ValuesIn(ikSolverNames()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           return param.param;
                         });

}  // namespace
}  // namespace lang2manip
