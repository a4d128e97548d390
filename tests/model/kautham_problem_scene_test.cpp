// Kautham problems written into a temporary directory: obstacles, obstacle controls, initial
// attachments and object semantics. Expected poses are computed by hand (see the comments).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "kautham_test_support.hpp"
#include "lang2manip/model/kautham_problem.hpp"

namespace lang2manip {
namespace {

using test::controlSet;
using test::simpleControl;
using ::testing::ElementsAre;

constexpr double kSceneTolerance = 1e-9;

const char* const kArmRobot = "  <Robot robot=\"robots/arm.urdf\"/>\n";

std::string obstacleXml(const std::string& name, const std::string& reference, const std::string& inner = "",
                        const std::string& scale = "1.0") {
  return "  <Obstacle obstacle=\"" + reference + "\" scale=\"" + scale + "\">\n    <KauthamName name=\"" +
         name + "\"/>\n" + inner + "  </Obstacle>\n";
}

std::string queryPlanner(const std::string& query) {
  return "  <Planner><Parameters><Name>omplRRT</Name></Parameters><Queries><Query>" + query +
         "</Query></Queries></Planner>\n";
}

class KauthamSceneTest : public test::KauthamDirectoryTest {
 protected:
  void SetUp() override {
    writeModel("robots/arm.urdf", test::armUrdf());
    writeModel("obstacles/crate.urdf", test::boxUrdf("crate_model", "0.1 0.1 0.1"));
    writeModel("obstacles/table.urdf", test::boxUrdf("table_model", "1.0 0.6 0.05"));
    writeModel("obstacles/holder.urdf", test::boxUrdf("holder_model", "0.1 0.1 0.1", R"(
  <lang2manip_object kind="pen_holder" movable="true" role="container">
    <cavity min="-0.04 -0.04 0.004" max="0.04 0.04 0.1"/>
  </lang2manip_object>
)"));
  }
};

TEST_F(KauthamSceneTest, ObstacleControlsMoveObstaclesAndUncontrolledObstaclesStayAtHome) {
  writeControls("arm.cntr", controlSet(simpleControl("u", "arm/upper")));
  writeControls("crates.cntr",
                controlSet("  <Offset><DOF name=\"crate/X1\" value=\"0\"/><DOF name=\"crate/X2\" value=\"0\"/>"
                           "<DOF name=\"crate/X3\" value=\"0.25\"/></Offset>\n" +
                           simpleControl("crate/x", "crate/X") + simpleControl("crate/y", "crate/Y")));
  writeProblem(
      std::string(kArmRobot) +
      obstacleXml("crate", "obstacles/crate.urdf",
                  "    <Limits name=\"X\" min=\"0\" max=\"2\"/><Limits name=\"Y\" min=\"-1\" max=\"1\"/>\n"
                  "    <Home Z=\"0.5\"/>\n") +
      obstacleXml("still", "obstacles/crate.urdf", "    <Home X=\"3\"/>\n") +
      "  <Controls robot=\"controls/arm.cntr\" obstacle=\"controls/crates.cntr\"/>\n" +
      queryPlanner("<InitObs>0.25 0.75</InitObs><Init>0.5</Init><Goal>0.5</Goal>"));
  const KauthamProblem problem = read();
  // x = 0 + 0.25*2 = 0.5, y = -1 + 0.75*2 = 0.5, no Z limits -> 0; yaw 2 pi * 0.25 = pi/2.
  // X_WO = T(0, 0, 0.5) * T(0.5, 0.5, 0) * Rz(pi/2).
  const Pose& X_WO = problem.scene.object("crate").pose;
  EXPECT_TRUE(X_WO.translation().isApprox(Vector3(0.5, 0.5, 0.5), kSceneTolerance));
  EXPECT_TRUE((X_WO.linear() * Vector3::UnitX()).isApprox(Vector3::UnitY(), kSceneTolerance));
  EXPECT_TRUE(problem.scene.object("still").pose.translation().isApprox(Vector3(3, 0, 0), kSceneTolerance));

  const std::vector<Pose> poses = obstaclePosesFromControls(problem, {1.0, 0.0}, "other");
  ASSERT_EQ(poses.size(), 2U);
  // x = 2, y = -1: (0, 0, 0.5) + (2, -1, 0).
  EXPECT_TRUE(poses[0].translation().isApprox(Vector3(2, -1, 0.5), kSceneTolerance));
  EXPECT_TRUE(poses[1].translation().isApprox(Vector3(3, 0, 0), kSceneTolerance));
  EXPECT_THAT(problem.obstacleControls.controlNames(), ElementsAre("crate/x", "crate/y"));
  EXPECT_EQ(problem.obstacleControls.source, controlFile("crates.cntr").lexically_normal().string());
}

TEST_F(KauthamSceneTest, ObstacleControlFileWithOnlyOffsetsPlacesTheObstacle) {
  writeControls("crates.cntr", controlSet("  <Offset><DOF name=\"crate/X\" value=\"0.75\"/></Offset>\n"));
  writeProblem(
      std::string(kArmRobot) +
      obstacleXml("crate", "obstacles/crate.urdf", "    <Limits name=\"X\" min=\"0\" max=\"2\"/>\n") +
      "  <Controls robot=\"\" obstacle=\"controls/crates.cntr\"/>\n");
  // x = 0 + 0.75*2 = 1.5
  EXPECT_TRUE(read().scene.object("crate").pose.translation().isApprox(Vector3(1.5, 0, 0), kSceneTolerance));
}

TEST_F(KauthamSceneTest, InitialAttachedObstacleKeepsItsPoseRelativeToTheLinkAtInit) {
  writeControls("arm.cntr", controlSet(simpleControl("u", "arm/upper")));
  writeProblem(std::string(kArmRobot) +
               obstacleXml("crate", "obstacles/crate.urdf", "    <Home X=\"0.5\" Z=\"0.1\"/>\n") +
               "  <Controls robot=\"controls/arm.cntr\"/>\n" +
               queryPlanner("<Init>0.75</Init><Goal>0.5</Goal>") +
               "  <InitialAttachedObstacle robot=\"arm\" link=\"upper\" obstacle=\"crate\"/>\n");
  const KauthamProblem problem = read();
  ASSERT_EQ(problem.initialAttachments.size(), 1U);
  const Attachment* attachment = problem.scene.findAttachment("crate");
  ASSERT_NE(attachment, nullptr);
  EXPECT_EQ(attachment->robot, "arm");
  EXPECT_EQ(attachment->link, "upper");
  // shoulder q = -1 + 0.75*2 = 0.5; X_WL = T(0, 0, 0.1) * Rz(0.5); X_WO = T(0.5, 0, 0.1).
  // X_LO = X_WL^-1 * X_WO = Rz(-0.5) * T(0.5, 0, 0) = (0.5 cos 0.5, -0.5 sin 0.5, 0), Rz(-0.5).
  const Pose& X_LO = attachment->linkToObject;
  EXPECT_TRUE(X_LO.translation().isApprox(Vector3(0.5 * std::cos(0.5), -0.5 * std::sin(0.5), 0), kSceneTolerance));
  EXPECT_TRUE(
      (X_LO.linear() * Vector3::UnitX()).isApprox(Vector3(std::cos(0.5), -std::sin(0.5), 0), kSceneTolerance));
  EXPECT_TRUE(problem.initialAttachments[0].linkToObject.isApprox(X_LO, kSceneTolerance));
}

TEST_F(KauthamSceneTest, CollisionCanBeDisabledPerObstacle) {
  writeProblem(std::string(kArmRobot) +
               obstacleXml("ghost", "obstacles/crate.urdf", "    <Collision enabled=\"false\"/>\n") +
               obstacleXml("solid", "obstacles/crate.urdf"));
  const KauthamProblem problem = read();
  EXPECT_FALSE(problem.scene.object("ghost").collisionEnabled);
  EXPECT_TRUE(problem.scene.object("solid").collisionEnabled);
}

TEST_F(KauthamSceneTest, Lang2ManipObjectElementGivesKindMovableRoleAndScaledCavity) {
  writeProblem(std::string(kArmRobot) + obstacleXml("holder", "obstacles/holder.urdf", "", "2.0"));
  const SceneObject holder = read().scene.object("holder");
  EXPECT_EQ(holder.kind, "pen_holder");
  EXPECT_TRUE(holder.movable);
  EXPECT_EQ(holder.role, ObjectRole::kContainer);
  ASSERT_TRUE(holder.cavity.has_value());
  EXPECT_TRUE(holder.cavity->min().isApprox(Vector3(-0.08, -0.08, 0.008), kSceneTolerance));
  EXPECT_TRUE(holder.cavity->max().isApprox(Vector3(0.08, 0.08, 0.2), kSceneTolerance));
  EXPECT_TRUE(holder.dimensions().isApprox(Vector3(0.2, 0.2, 0.2), kSceneTolerance));  // scaled box
  EXPECT_DOUBLE_EQ(holder.modelScale, 2.0);
}

TEST_F(KauthamSceneTest, WithoutTheElementAWideFlatObstacleIsASupportAndOthersHaveNoRole) {
  writeProblem(std::string(kArmRobot) + obstacleXml("table", "obstacles/table.urdf") +
               obstacleXml("crate", "obstacles/crate.urdf"));
  const KauthamProblem problem = read();
  const SceneObject& table = problem.scene.object("table");
  EXPECT_EQ(table.kind, "table_model");
  EXPECT_EQ(table.role, ObjectRole::kSupport);
  EXPECT_FALSE(table.movable);
  EXPECT_FALSE(table.cavity.has_value());
  EXPECT_EQ(problem.scene.object("crate").role, ObjectRole::kNone);
}

TEST_F(KauthamSceneTest, ObstacleNameDefaultsToTheUrdfNameAndEntitiesRecordHowTheyWereWritten) {
  writeProblem(
      "  <Robot robot=\"robots/arm.urdf\"><InvKinematic name=\"UR5\"/></Robot>\n"
      "  <Obstacle obstacle=\"obstacles/table.urdf\">\n"
      "    <Home X=\"1\" Y=\"2\" Z=\"3\" WX=\"1\" WY=\"0\" WZ=\"0\" TH=\"3.141592653589793\"/>\n"
      "    <Limits name=\"Z\" min=\"0\" max=\"1\"/>\n"
      "  </Obstacle>\n");
  const KauthamProblem problem = read();
  EXPECT_EQ(problem.robots[0].inverseKinematics, "UR5");
  EXPECT_TRUE(problem.robots[0].isRobot);
  ASSERT_EQ(problem.obstacles.size(), 1U);
  const KauthamEntity& table = problem.obstacles[0];
  EXPECT_EQ(table.name, "table_model");
  EXPECT_FALSE(table.isRobot);
  EXPECT_EQ(table.reference, "obstacles/table.urdf");
  EXPECT_THAT(table.limits.z, ::testing::Optional(std::pair{0.0, 1.0}));
  // A half turn about x: y -> -y; no obstacle controls, so the object sits at Home.
  const Pose& X_WO = problem.scene.object("table_model").pose;
  EXPECT_TRUE(X_WO.translation().isApprox(Vector3(1, 2, 3), kSceneTolerance));
  EXPECT_TRUE((X_WO.linear() * Vector3::UnitY()).isApprox(-Vector3::UnitY(), kSceneTolerance));
  EXPECT_TRUE(problem.scene.object("table_model").poseLimits.z.has_value());
}

}  // namespace
}  // namespace lang2manip
