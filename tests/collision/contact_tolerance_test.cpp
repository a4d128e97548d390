// Bodies resting on each other within the scene's contact tolerance are in contact, not in
// collision: primitive pairs, mesh pairs (FCL's depth is meaningless there) and the reports.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <utility>

#include "collision_test_support.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/model/mesh_loader.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

constexpr double kResting = 0.0003;
constexpr double kSunk = 0.002;

const CollisionContact* contactOf(const CollisionReport& report, const std::string& body) {
  for (const CollisionContact& contact : report.contacts) {
    if (contact.first == body || contact.second == body) return &contact;
  }
  return nullptr;
}

/// panda_desk with the Panda's base `depth` into the desk (link0 stands 1 mm above it).
Scene pandaSunkBy(double depth, double tolerance = Scene::kDefaultContactTolerance) {
  Scene scene = problemScene("panda_desk");
  scene.robot("panda").basePose.translation().z() -= 0.001 + depth;
  scene.setContactTolerance(tolerance);
  return scene;
}

bool homeIsValid(const Scene& scene) {
  const FclCollisionChecker checker(scene);
  return checker.isStateValid(0, scene.robots().front().configuration, *checker.makeContext());
}

TEST(ContactTolerance, BaseRestingOnTheDeskIsInContactNotInCollision) {
  EXPECT_TRUE(homeIsValid(pandaSunkBy(kResting)));
  EXPECT_FALSE(homeIsValid(pandaSunkBy(kResting, 0.0)));
  EXPECT_TRUE(homeIsValid(pandaSunkBy(kResting, 0.001)));
  EXPECT_FALSE(homeIsValid(pandaSunkBy(kSunk)));
  const Scene sunk = pandaSunkBy(kSunk);
  const FclCollisionChecker checker(sunk);
  const CollisionReport report = checker.checkWorld(checker.sceneState(), {true}, *checker.makeContext());
  const CollisionContact* contact = contactOf(report, "desk");
  ASSERT_NE(contact, nullptr) << contactList(report);
  EXPECT_NEAR(contact->penetrationDepth, kSunk, 1e-4);
  const Scene resting = pandaSunkBy(kResting);
  const FclCollisionChecker restingChecker(resting);
  const CollisionReport touching =
      restingChecker.checkWorld(restingChecker.sceneState(), {true}, *restingChecker.makeContext());
  EXPECT_TRUE(touching.valid) << contactList(touching);
  EXPECT_EQ(touching.minimumDistance, 0.0);
  EXPECT_EQ(touching.closestSecond, "desk");
}

/// A one-joint robot whose base and arm are meshes (a 0.1 x 0.2 x 0.3 m box each).
RobotModelPtr meshRobot() {
  const std::string box = (testDataDirectory() / "meshes" / "box_ascii.stl").string();
  const std::string mesh = "<geometry><mesh filename=\"" + box + "\" scale=\"0.1 0.1 0.1\"/></geometry>";
  const std::string urdf =
      "<robot name=\"block\"><link name=\"base\"><collision>" + mesh + "</collision></link>"
      "<link name=\"arm\"><collision><origin xyz=\"0 0 0.3\"/>" + mesh + "</collision></link>"
      "<joint name=\"turn\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/>"
      "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint></robot>";
  return readUrdfString(urdf, "block.urdf", testDataDirectory());
}

/// The mesh robot on a mesh table whose top is at z = 0.3, its base `depth` into the table.
Scene meshRobotSunkBy(double depth) {
  Scene scene;
  SceneRobot robot;
  robot.name = "block";
  robot.model = meshRobot();
  robot.configuration = VectorX::Zero(1);
  robot.basePose.translation() = Vector3(0.2, 0.3, 0.3 - depth);
  scene.addRobot(robot);
  SceneObject table;
  table.name = "table";
  table.kind = "table";
  // Wound inwards, as meshes often are: FCL's own depth is then wrong (about 0.3 m here).
  TriangleMesh inwards = loadTriangleMesh((testDataDirectory() / "meshes" / "box_ascii.stl").string());
  for (std::array<int, 3>& triangle : inwards.triangles) std::swap(triangle[1], triangle[2]);
  MeshGeometry top{std::make_shared<const TriangleMesh>(std::move(inwards)), Vector3(1.0, 1.0, 0.1),
                   "box_ascii.stl"};
  table.collisions.push_back(Shape{top, Pose::Identity(), std::nullopt, "top"});
  scene.addObject(table);
  return scene;
}

TEST(ContactTolerance, MeshesRestingOnMeshesAreInContact) {
  EXPECT_TRUE(homeIsValid(meshRobotSunkBy(0.0)));
  EXPECT_TRUE(homeIsValid(meshRobotSunkBy(kResting)));
  EXPECT_FALSE(homeIsValid(meshRobotSunkBy(kSunk)));
  Scene strict = meshRobotSunkBy(kResting);
  strict.setContactTolerance(0.0);
  EXPECT_FALSE(homeIsValid(strict));
  const Scene sunk = meshRobotSunkBy(kSunk);
  const FclCollisionChecker checker(sunk);
  const CollisionReport report = checker.checkState(0, VectorX::Zero(1), {true}, *checker.makeContext());
  const CollisionContact* contact = contactOf(report, "table");
  ASSERT_NE(contact, nullptr) << contactList(report);
  EXPECT_NEAR(contact->penetrationDepth, kSunk, 2e-4);
  EXPECT_NEAR(report.minimumDistance, -kSunk, 2e-4);
}

TEST(ContactTolerance, DeepCollisionsStayCollisions) {
  const Scene deep = meshRobotSunkBy(0.15);
  const FclCollisionChecker checker(deep);
  const CollisionReport report = checker.checkState(0, VectorX::Zero(1), {true}, *checker.makeContext());
  EXPECT_FALSE(report.valid);
  const CollisionContact* contact = contactOf(report, "table");
  ASSERT_NE(contact, nullptr) << contactList(report);
  EXPECT_NEAR(contact->penetrationDepth, 0.15, 2e-4);
}

TEST(ContactToleranceBadInput, OutOfRangeValuesAreRefused) {
  Scene scene;
  for (const double bad : {-0.001, 0.5, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()}) {
    EXPECT_THAT([&] { scene.setContactTolerance(bad); },
                ThrowsMessage<InputError>(HasSubstr("is not in [0, 0.01] m")));
  }
  EXPECT_EQ(scene.contactTolerance(), Scene::kDefaultContactTolerance);
}

}  // namespace
}  // namespace lang2manip::test
