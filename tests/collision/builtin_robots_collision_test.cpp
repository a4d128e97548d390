// Conformance of the exact checker on every built-in robot: named and query states are free,
// configurations folding an arm into itself or into the desk collide and the report names the pair.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "collision_test_support.hpp"
#include "lang2manip/collision/fcl_geometry.hpp"
#include "lang2manip/collision/fcl_mesh_cache.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;

struct RobotCase {
  std::string robot;
  std::string problem;
  /// A joint set (from home) to fold the arm into itself, and the pair that then collides.
  std::string selfJoint;
  double selfValue;
  std::string selfFirst;
  std::string selfSecond;
  /// A joint set (from home) to push the arm into the desk (empty: none), and the link hitting it.
  std::string deskJoint;
  double deskValue;
  std::string deskLink;
};

std::ostream& operator<<(std::ostream& out, const RobotCase& c) { return out << c.robot; }

const RobotCase kCases[] = {
    {"panda", "panda_desk", "panda_joint6", -0.0175, "panda/panda_link5", "panda/panda_link7",
     "panda_joint2", 1.7628, "panda/panda_link5"},
    {"ur5", "ur5_desk", "elbow_joint", 3.14159, "ur5/upper_arm_link", "ur5/wrist_1_link",
     "shoulder_lift_joint", 0.0, "ur5/forearm_link"},
    {"iiwa14", "iiwa14_desk", "iiwa_joint_6", 2.0944, "iiwa14/iiwa_link_5", "iiwa14/iiwa_link_7",
     "iiwa_joint_2", 2.0944, "iiwa14/iiwa_link_5"},
    {"yumi", "yumi_desk", "yumi_joint_2_r", -2.50455, "yumi/yumi_body", "yumi/yumi_link_3_r", "",
     0.0, ""},
    {"tx90", "tx90_desk", "joint_3", 2.53073, "tx90/link_1", "tx90/link_4", "joint_2", 2.57436,
     "tx90/link_4"},
};

bool penetratesPair(const CollisionReport& report, const std::string& a, const std::string& b) {
  for (const CollisionContact& contact : report.contacts) {
    if ((contact.first == a && contact.second == b) || (contact.first == b && contact.second == a)) {
      return contact.penetrationDepth > 0.0;
    }
  }
  return false;
}

class BuiltinRobotCollision : public ::testing::TestWithParam<RobotCase> {};

TEST_P(BuiltinRobotCollision, HomeAndQueryStatesAreFree) {
  const RobotCase& c = GetParam();
  const FclCollisionChecker checker(problemScene(c.problem));
  const auto context = checker.makeContext();
  const RobotModel& model = *checker.scene().robots()[0].model;
  EXPECT_TRUE(checker.isStateValid(0, model.namedConfiguration("home"), *context))
      << contactList(checker.checkState(0, model.namedConfiguration("home"), {}, *context));
  const CollisionReport scene = checker.checkWorld(checker.sceneState(), {true}, *context);
  EXPECT_TRUE(scene.valid) << contactList(scene);
  EXPECT_GT(scene.minimumDistance, 0.0);
  EXPECT_FALSE(scene.closestFirst.empty());
  // Alone (no desk), home is free too.
  const FclCollisionChecker alone(robotOnlyScene(c.robot));
  EXPECT_TRUE(alone.isStateValid(0, model.namedConfiguration("home"), *alone.makeContext()));
}

TEST_P(BuiltinRobotCollision, FoldingTheArmIntoItselfCollidesNamingThePair) {
  const RobotCase& c = GetParam();
  const FclCollisionChecker checker(robotOnlyScene(c.robot));
  const auto context = checker.makeContext();
  const RobotModel& model = *checker.scene().robots()[0].model;
  VectorX q = model.namedConfiguration("home");
  q[model.variableIndex(c.selfJoint)] = c.selfValue;
  EXPECT_FALSE(checker.isStateValid(0, q, *context));
  const CollisionReport report = checker.checkState(0, q, {}, *context);
  EXPECT_FALSE(report.valid);
  EXPECT_TRUE(penetratesPair(report, c.selfFirst, c.selfSecond)) << contactList(report);
  EXPECT_LT(report.minimumDistance, 0.0);
}

TEST_P(BuiltinRobotCollision, PushingTheArmIntoTheDeskCollidesWithTheDesk) {
  const RobotCase& c = GetParam();
  if (c.deskJoint.empty()) GTEST_SKIP() << c.robot << ": covered by the self-collision case";
  const FclCollisionChecker checker(problemScene(c.problem));
  const auto context = checker.makeContext();
  const RobotModel& model = *checker.scene().robots()[0].model;
  VectorX q = model.namedConfiguration("home");
  q[model.variableIndex(c.deskJoint)] = c.deskValue;
  EXPECT_FALSE(checker.isStateValid(0, q, *context));
  const CollisionReport report = checker.checkState(0, q, {}, *context);
  EXPECT_TRUE(penetratesPair(report, c.deskLink, "desk")) << contactList(report);
}

INSTANTIATE_TEST_SUITE_P(AllRobots, BuiltinRobotCollision, ::testing::ValuesIn(kCases),
                         [](const auto& param) { return param.param.robot; });

TEST(BuiltinRobotCollision, CapsuleTriplesBecomeOneCapsule) {
  const RobotModelPtr panda = builtinRobot("panda");
  FclGeometryBuilder builder;
  const Link& link1 = panda->links()[static_cast<std::size_t>(panda->linkIndex("panda_link1"))];
  ASSERT_EQ(link1.collisions.size(), 3U);
  const std::vector<FclShape> shapes = builder.build(link1.collisions);
  ASSERT_EQ(shapes.size(), 1U);
  EXPECT_EQ(shapes[0].geometry->getNodeType(), fcl::GEOM_CAPSULE);
}

TEST(BuiltinRobotCollision, MeshesAreBuiltOncePerMeshAndScale) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)};
  mesh->triangles = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  Shape a;
  a.geometry = MeshGeometry{mesh, Vector3::Ones(), "m"};
  Shape b = a;
  b.origin.translation() = Vector3(1, 0, 0);
  Shape scaled;
  scaled.geometry = MeshGeometry{mesh, Vector3::Constant(2), "m"};
  FclGeometryBuilder builder;
  const auto first = builder.build({a, b});
  const auto second = builder.build({scaled});
  ASSERT_EQ(first.size(), 2U);
  EXPECT_EQ(first[0].geometry, first[1].geometry);
  EXPECT_NE(first[0].geometry, second[0].geometry);
  EXPECT_EQ(builder.meshCount(), 2U);
  EXPECT_EQ(first[0].geometry->getNodeType(), fcl::BV_OBBRSS);
  EXPECT_NEAR(second[0].localHalfExtent.x(), 1.0, 1e-9);
}

TEST(BuiltinRobotCollision, MeshBvhsAreSharedAcrossBuildersWhileTheMeshLives) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)};
  mesh->triangles = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  Shape shape;
  shape.geometry = MeshGeometry{mesh, Vector3::Constant(0.5), "m"};
  const std::size_t buildsBefore = meshBvhCacheStatistics().builds;
  const auto first = FclGeometryBuilder().build({shape});
  const auto second = FclGeometryBuilder().build({shape});
  EXPECT_EQ(first[0].geometry, second[0].geometry);
  EXPECT_EQ(meshBvhCacheStatistics().builds, buildsBefore + 1);
  const std::size_t liveWithMesh = meshBvhCacheStatistics().liveEntries;
  shape.geometry = Box{Vector3::Ones()};
  mesh.reset();
  EXPECT_EQ(meshBvhCacheStatistics().liveEntries, liveWithMesh - 1);
  // The BVH stays valid for the geometries that hold it.
  EXPECT_EQ(first[0].geometry->getNodeType(), fcl::BV_OBBRSS);
}

TEST(BuiltinRobotCollision, ParallelPrebuildingGivesTheSameBvhsAsBuildingOneByOne) {
  std::vector<std::shared_ptr<TriangleMesh>> meshes;
  std::vector<MeshGeometry> geometries;
  for (int m = 0; m < 6; ++m) {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->vertices = {Vector3(0, 0, 0), Vector3(1 + m, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)};
    mesh->triangles = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    meshes.push_back(mesh);
    geometries.push_back(MeshGeometry{mesh, Vector3::Ones(), "m"});
  }
  std::vector<const MeshGeometry*> pointers;
  for (const MeshGeometry& geometry : geometries) pointers.push_back(&geometry);
  pointers.push_back(&geometries.front());
  const std::size_t buildsBefore = meshBvhCacheStatistics().builds;
  prebuildMeshBvhs(pointers, 3);
  EXPECT_EQ(meshBvhCacheStatistics().builds, buildsBefore + 6);
  for (std::size_t m = 0; m < geometries.size(); ++m) {
    const auto bvh = sharedMeshBvh(geometries[m]);
    ASSERT_NE(bvh, nullptr);
    EXPECT_NEAR(bvh->aabb_local.max_.x(), 1.0 + static_cast<double>(m), 1e-12);
  }
  EXPECT_EQ(meshBvhCacheStatistics().builds, buildsBefore + 6);
}

}  // namespace
}  // namespace lang2manip::test
