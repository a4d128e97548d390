// Bodies resting on each other within the scene's contact tolerance are in contact, not in
// collision: primitive pairs, mesh pairs (FCL's depth is meaningless there) and the reports.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <utility>

#include "collision_test_support.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/model/mesh_loader.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;
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

/// ASCII STL of a closed round column of `segments` sides, radius 5 cm and 10 cm high, its
/// bottom at z = 0: a bottom fan, a top fan and the sides.
std::string roundColumnStl(int segments) {
  std::vector<Vector3> bottom, top;
  for (int k = 0; k < segments; ++k) {
    const double angle = 2.0 * M_PI * k / segments;
    bottom.emplace_back(0.05 * std::cos(angle), 0.05 * std::sin(angle), 0.0);
    top.emplace_back(bottom.back().x(), bottom.back().y(), 0.1);
  }
  std::string stl = "solid column\n";
  const auto facet = [&stl](const Vector3& a, const Vector3& b, const Vector3& c) {
    const Vector3 n = (b - a).cross(c - a).normalized();
    char text[512];
    std::snprintf(text, sizeof text,
                  "facet normal %g %g %g\n outer loop\n  vertex %.9g %.9g %.9g\n  vertex %.9g %.9g %.9g\n  vertex %.9g %.9g %.9g\n endloop\nendfacet\n",
                  n.x(), n.y(), n.z(), a.x(), a.y(), a.z(), b.x(), b.y(), b.z(), c.x(), c.y(), c.z());
    stl += text;
  };
  for (int k = 0; k < segments; ++k) {
    const std::size_t a = static_cast<std::size_t>(k), b = static_cast<std::size_t>((k + 1) % segments);
    facet(Vector3(0, 0, 0), bottom[b], bottom[a]);
    facet(Vector3(0, 0, 0.1), top[a], top[b]);
    facet(bottom[a], bottom[b], top[b]);
    facet(bottom[a], top[b], top[a]);
  }
  return stl + "endsolid column\n";
}

TEST(ContactTolerance, AMeshBaseFlushOnABoxTableIsInContact) {
  // A vendor's base mesh whose bottom face lies exactly on the table's top (zero depth): the
  // contact normals FCL reports there need not separate the two; a short translation along an
  // axis still does. Pressed 2 mm in, it collides.
  const TempDirectory directory;
  for (const int segments : {7, 16, 40}) {
    const fs::path stl = directory.path() / ("column" + std::to_string(segments) + ".stl");
    std::ofstream(stl) << roundColumnStl(segments);
    const std::string urdf = "<robot name=\"column\"><link name=\"base\"><collision><geometry><mesh filename=\"" + stl.string() +
                             "\"/></geometry></collision></link><link name=\"arm\"/><joint name=\"turn\" type=\"revolute\"><parent link=\"base\"/>"
                             "<child link=\"arm\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint></robot>";
    for (const double depth : {0.0, kResting, kSunk}) {
      Scene scene;
      SceneRobot robot;
      robot.name = "column";
      robot.model = readUrdfString(urdf, "column.urdf", directory.path());
      robot.configuration = VectorX::Zero(1);
      robot.basePose.translation() = Vector3(0.1, 0.2, 0.3 - depth);
      scene.addRobot(robot);
      SceneObject table;
      table.name = "table";
      table.kind = "table";
      table.collisions.push_back(Shape{Box{Vector3(1.0, 1.0, 0.3)}, Pose(Eigen::Translation3d(0.0, 0.0, 0.15)), std::nullopt, "top"});
      scene.addObject(table);
      EXPECT_EQ(homeIsValid(scene), depth < kSunk) << segments << " sides, " << depth << " m deep";
    }
  }
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
