// Where a planning space's joint velocity and acceleration limits come from: the robot model's
// (a joint limits file gives accelerations) or JointLimitDefaults.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/planning/trajectory.hpp"
#include "planning_test_support.hpp"

namespace lang2manip::test {
namespace {

std::vector<double> values(const VectorX& vector) { return {vector.data(), vector.data() + vector.size()}; }

std::shared_ptr<const JointPlanningSpace> builtinRobotSpace(const std::string& robot,
                                                            const JointLimitDefaults& defaults = {}) {
  Scene scene;
  SceneRobot sceneRobot;
  sceneRobot.name = robot;
  sceneRobot.model = readUrdfFile(builtinRobotUrdf(robot));
  sceneRobot.configuration = sceneRobot.model->namedConfiguration("home");
  scene.addRobot(sceneRobot);
  return std::make_shared<JointPlanningSpace>(std::make_shared<FclCollisionChecker>(scene),
                                              std::vector<std::string>{robot},
                                              std::vector<std::vector<std::string>>{}, defaults);
}

TEST(JointPlanningSpaceLimits, UsesThePandasDatasheetAccelerationsAndTheDefaultForItsFingers) {
  const auto space = builtinRobotSpace("panda");
  EXPECT_THAT(space->dofNames(), testing::Contains("panda/panda_finger_joint1"));
  // Joints 1-7 from panda.joint_limits.yaml; the finger has none: 2 x 0.2 m/s per second.
  EXPECT_THAT(values(space->jointAccelerationLimits()), testing::ElementsAre(15, 7.5, 10, 12.5, 15, 20, 20, 0.4));
  EXPECT_THAT(values(space->jointVelocityLimits()),
              testing::ElementsAre(2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61, 0.2));
  JointLimitDefaults faster;
  faster.accelerationPerVelocity = 5.0;
  EXPECT_THAT(values(builtinRobotSpace("panda", faster)->jointAccelerationLimits()),
              testing::ElementsAre(15, 7.5, 10, 12.5, 15, 20, 20, 1.0));
}

TEST(JointPlanningSpaceLimits, WithoutAccelerationLimitsEveryJointGetsTheDefault) {
  EXPECT_THAT(values(planarArmSpace()->jointAccelerationLimits()), testing::ElementsAre(3.0, 4.0));
  const auto ur5 = builtinRobotSpace("ur5");
  EXPECT_TRUE(ur5->jointAccelerationLimits().isApprox(2.0 * ur5->jointVelocityLimits()));
}

TEST(JointPlanningSpaceLimits, AJointWithoutVelocityLimitMovesAtTheDocumentedDefault) {
  Scene scene;
  SceneRobot robot;
  robot.name = "turntable";
  robot.model = readUrdfString(R"(<robot name="turntable"><link name="base"/><link name="plate"/>
    <joint name="spin" type="continuous"><parent link="base"/><child link="plate"/><axis xyz="0 0 1"/></joint>
    </robot>)", "turntable.urdf", ".");
  robot.configuration = VectorX::Zero(1);
  scene.addRobot(robot);
  const JointPlanningSpace space(std::make_shared<FclCollisionChecker>(scene), {"turntable"});
  EXPECT_EQ(space.jointVelocityLimits()[0], kDefaultJointVelocityLimit);
  EXPECT_EQ(space.jointAccelerationLimits()[0], 2.0 * kDefaultJointVelocityLimit);
}

TEST(JointPlanningSpaceLimits, TrajectoriesAreTimedWithTheModelsAccelerations) {
  const auto space = builtinRobotSpace("panda");
  const VectorX start = 0.5 * (space->lower() + space->upper());
  VectorX goal = start;
  goal[1] += 1.0;  // panda_joint2: 1 rad at 2.175 rad/s and 7.5 rad/s^2
  const JointTrajectory trajectory = timeParameterize(*space, {start, goal});
  EXPECT_EQ(checkTrajectoryLimits(*space, trajectory), "");
  const double ramp = 2.175 / 7.5;
  const double cruise = (1.0 - 2.175 * ramp) / 2.175;
  EXPECT_NEAR(trajectory.duration(), 2.0 * ramp + cruise, 1e-9);
}

TEST(JointPlanningSpaceLimits, KauthamControlSpacesUseTheModelsAccelerations) {
  const KauthamProblem problem = readKauthamProblem(resolveProblem("panda_desk"));
  const KauthamControlSpace space(std::make_shared<FclCollisionChecker>(problem.scene), problem);
  const std::vector<std::string>& joints = space.trajectoryJointNames();
  const auto joint2 = std::find(joints.begin(), joints.end(), "panda/panda_joint2");
  ASSERT_NE(joint2, joints.end());
  EXPECT_EQ(space.jointAccelerationLimits()[joint2 - joints.begin()], 7.5);
}

}  // namespace
}  // namespace lang2manip::test
