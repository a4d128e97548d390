// Where a planning space's joint velocity and acceleration limits come from: the robot model's
// (a joint limits file gives accelerations) or JointLimitDefaults.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lang2manip/model/builtin_data.hpp"
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

}  // namespace
}  // namespace lang2manip::test
