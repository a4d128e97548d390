// Object semantics inferred from a scene's geometry (Kautham obstacles carry no
// <lang2manip_object>): supports, containers with their hollow, movable objects, and the user's
// --movable / --fixed.

#include <cmath>
#include <memory>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "grounding_test_support.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/grounding/grasp_planner.hpp"
#include "lang2manip/grounding/object_semantics.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/model/triangle_mesh.hpp"
#include "lang2manip/symbolic/resting_height.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;

Shape boxAt(const Vector3& size, const Vector3& centre) {
  Shape shape;
  shape.geometry = Box{size};
  shape.origin.translation() = centre;
  return shape;
}

/// An object whose semantics are left to inference, with its frame at the centre of its bottom.
SceneObject untagged(const std::string& name, std::vector<Shape> shapes, const Vector3& position) {
  SceneObject object;
  object.name = name;
  object.kind = name;
  object.collisions = std::move(shapes);
  object.pose.translation() = position;
  object.semantics = SemanticsSource::kInferred;
  return object;
}

/// The Panda desk with the desk, a block, a cup (open box of 5 walls), a tall cabinet and a
/// floating ball left to inference.
Scene inferenceScene() {
  Scene scene = deskScene("panda");
  for (const char* name : {"marker", "eraser", "holder"}) scene.removeObject(name);
  scene.object("desk").semantics = SemanticsSource::kInferred;
  scene.addObject(untagged("block", {boxAt({0.04, 0.04, 0.04}, {0, 0, 0.02})}, {0.1, -0.2, 0.75}));
  std::vector<Shape> cup{boxAt({0.08, 0.08, 0.005}, {0, 0, 0.0025})};
  for (double side : {-1.0, 1.0}) {
    cup.push_back(boxAt({0.005, 0.08, 0.1}, {side * 0.0375, 0, 0.05}));
    cup.push_back(boxAt({0.08, 0.005, 0.1}, {0, side * 0.0375, 0.05}));
  }
  scene.addObject(untagged("cup", cup, {0.1, 0.2, 0.75}));
  scene.addObject(untagged("cabinet", {boxAt({0.3, 0.2, 0.5}, {0, 0, 0.25})}, {0.4, 0.3, 0.75}));
  scene.addObject(untagged("ball", {boxAt({0.03, 0.03, 0.03}, {0, 0, 0.015})}, {0.0, 0.0, 1.2}));
  return scene;
}

const ObjectSemanticsDecision& decisionFor(const std::vector<ObjectSemanticsDecision>& decisions, const std::string& name) {
  for (const ObjectSemanticsDecision& decision : decisions) {
    if (decision.object == name) return decision;
  }
  throw std::runtime_error("no decision for " + name);
}

TEST(ObjectSemantics, SupportsContainersAndMovableObjectsAreInferredWithTheReason) {
  Scene scene = inferenceScene();
  const std::vector<ObjectSemanticsDecision> decisions = inferObjectSemantics(scene);
  EXPECT_EQ(scene.object("desk").role, ObjectRole::kSupport);
  EXPECT_FALSE(scene.object("desk").movable);
  EXPECT_TRUE(scene.object("block").movable);
  EXPECT_THAT(decisionFor(decisions, "block").reason, HasSubstr("rests on desk"));
  EXPECT_EQ(scene.object("cup").role, ObjectRole::kContainer);
  EXPECT_TRUE(scene.object("cup").movable) << "0.08 m fits the Panda's 0.08 m opening";
  ASSERT_TRUE(scene.object("cup").cavity.has_value());
  EXPECT_NEAR(scene.object("cup").cavity->min().z(), 0.005, 2e-3);
  EXPECT_NEAR(scene.object("cup").cavity->sizes().x(), 0.07, 2e-3);
  EXPECT_FALSE(scene.object("cabinet").movable);
  EXPECT_THAT(decisionFor(decisions, "cabinet").reason, HasSubstr("the widest gripper opens 0.080 m"));
  EXPECT_FALSE(scene.object("ball").movable);
  EXPECT_THAT(decisionFor(decisions, "ball").reason, HasSubstr("rests on nothing"));
  EXPECT_EQ(decisionFor(decisions, "block").source, SemanticsSource::kInferred);
}

/// A closed bowl surface: a spherical wall of radius `radius` (outer) and `radius - wall` (inner)
/// from the bottom up to the rim at height `radius`, a flat ring at the rim; frame at the bottom.
Shape hemisphericalBowl(double radius, double wall) {
  constexpr int kSegments = 32, kRings = 8;
  auto mesh = std::make_shared<TriangleMesh>();
  const auto ringAt = [&](double r, double z) {
    const int first = static_cast<int>(mesh->vertices.size());
    for (int k = 0; k < kSegments; ++k) {
      const double angle = 2.0 * 3.14159265358979323846 * k / kSegments;
      mesh->vertices.emplace_back(r * std::cos(angle), r * std::sin(angle), z);
    }
    return first;
  };
  const auto band = [&](int a, int b) {
    for (int k = 0; k < kSegments; ++k) {
      const int next = (k + 1) % kSegments;
      mesh->triangles.push_back({a + k, a + next, b + k});
      mesh->triangles.push_back({a + next, b + next, b + k});
    }
  };
  std::vector<int> outer, inner;
  for (int ring = 1; ring <= kRings; ++ring) {  // from near the bottom to the rim
    const double polar = 0.5 * 3.14159265358979323846 * ring / kRings;
    outer.push_back(ringAt(radius * std::sin(polar), radius - radius * std::cos(polar)));
    inner.push_back(ringAt((radius - wall) * std::sin(polar), radius - (radius - wall) * std::cos(polar)));
  }
  for (std::size_t i = 0; i + 1 < outer.size(); ++i) band(outer[i], outer[i + 1]), band(inner[i + 1], inner[i]);
  band(outer.back(), inner.back());  // the rim
  band(inner.front(), outer.front());  // a small foot ring closes the bottom
  Shape shape;
  shape.geometry = MeshGeometry{mesh, Vector3::Ones(), "test:hemispherical_bowl"};
  return shape;
}

TEST(ObjectSemantics, ARoundBowlsCavityIsMeasuredAsItIsNotAsASlab) {
  Scene scene = inferenceScene();
  scene.addObject(untagged("round_bowl", {hemisphericalBowl(0.07, 0.004)}, {0.1, 0.0, 0.75}));
  (void)inferObjectSemantics(scene);
  const SceneObject& bowl = scene.object("round_bowl");
  EXPECT_EQ(bowl.role, ObjectRole::kContainer);
  ASSERT_TRUE(bowl.cavity);
  // A hemisphere of inner radius 6.6 cm holds the most in a box whose floor is raised about 0.42
  // of its depth: some 8 x 8 cm and 3.5 cm high, square in plan (it was a thin slab).
  EXPECT_NEAR(bowl.cavity->sizes().x(), bowl.cavity->sizes().y(), 2e-3);
  EXPECT_GT(bowl.cavity->sizes().x(), 0.07);
  EXPECT_GT(bowl.cavity->sizes().z(), 0.03);
  EXPECT_GT(bowl.cavity->min().z(), 0.015);
  EXPECT_NEAR(bowl.cavity->max().z(), 0.07, 2e-3);
}

TEST(ObjectSemantics, ObjectsTheirModelsDescribeAreLeftAsGiven) {
  Scene scene = deskScene("panda");
  const std::vector<ObjectSemanticsDecision> decisions = inferObjectSemantics(scene);
  EXPECT_EQ(decisionFor(decisions, "holder").source, SemanticsSource::kGiven);
  EXPECT_EQ(scene.object("holder").role, ObjectRole::kContainer);
  EXPECT_TRUE(scene.object("marker").movable);
}

TEST(ObjectSemantics, TheUsersWordComesLast) {
  Scene scene = inferenceScene();
  const std::vector<ObjectSemanticsDecision> decisions = inferObjectSemantics(scene, {{"cabinet"}, {"block"}});
  EXPECT_TRUE(scene.object("cabinet").movable);
  EXPECT_FALSE(scene.object("block").movable);
  EXPECT_EQ(scene.object("block").semantics, SemanticsSource::kUser);
  EXPECT_EQ(decisionFor(decisions, "cabinet").reason, "movable: --movable");
}

TEST(ObjectSemanticsBadInput, ContradictingOrUnknownNamesAreRefused) {
  Scene scene = inferenceScene();
  try {
    static_cast<void>(inferObjectSemantics(scene, {{"block"}, {"block"}}));
    FAIL() << "block cannot be both";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("\"block\" is named both --movable and --fixed"));
  }
  try {
    static_cast<void>(inferObjectSemantics(scene, {{"unicorn"}, {}}));
    FAIL() << "no object is named unicorn";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("unicorn"));
    EXPECT_THAT(error.what(), HasSubstr("block"));
  }
}

/// Adds the closed surface of the box [low, high] to `mesh`.
void addBoxSurface(TriangleMesh& mesh, const Vector3& low, const Vector3& high) {
  const int first = static_cast<int>(mesh.vertices.size());
  for (int corner = 0; corner < 8; ++corner) {
    mesh.vertices.emplace_back((corner & 1) ? high.x() : low.x(), (corner & 2) ? high.y() : low.y(), (corner & 4) ? high.z() : low.z());
  }
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    mesh.triangles.push_back({first + f[0], first + f[1], first + f[2]});
    mesh.triangles.push_back({first + f[0], first + f[2], first + f[3]});
  }
}

/// A shelf unit as one mesh, as a Kautham kitchen is: a low board (its top 2 cm above its
/// frame), a back panel and a high board over the back part, so that its bounds reach 60 cm
/// above the low board where objects stand.
Shape shelfUnitMesh() {
  auto mesh = std::make_shared<TriangleMesh>();
  addBoxSurface(*mesh, {-0.15, -0.15, 0.0}, {0.15, 0.15, 0.02});
  addBoxSurface(*mesh, {0.13, -0.15, 0.0}, {0.15, 0.15, 0.6});
  addBoxSurface(*mesh, {0.05, -0.15, 0.58}, {0.15, 0.15, 0.6});
  Shape shape;
  shape.geometry = MeshGeometry{mesh, Vector3::Ones(), "test:shelf_unit"};
  return shape;
}

TEST(ObjectSemantics, ObjectsRestOnASurfaceInsideTheBoundsOfTheirSupport) {
  // Blocks 3 mm above the low board and 2 mm into it rest on it (how such files are written);
  // one 5 cm above it rests on nothing. Resting is measured on the shelf's geometry, not on the
  // top of its bounds (0.6 m higher).
  Scene scene = emptyDeskScene("panda");
  scene.addObject(untagged("shelf_unit", {shelfUnitMesh()}, {0.15, -0.2, 0.75}));
  scene.addObject(untagged("above", {boxAt({0.04, 0.04, 0.04}, {0, 0, 0.02})}, {0.08, -0.27, 0.773}));
  scene.addObject(untagged("sunk", {boxAt({0.04, 0.04, 0.04}, {0, 0, 0.02})}, {0.08, -0.13, 0.768}));
  scene.addObject(untagged("floating", {boxAt({0.04, 0.04, 0.04}, {0, 0, 0.02})}, {0.02, -0.2, 0.82}));
  for (const char* block : {"above", "sunk"}) {
    const AlignedBox3 bounds = scene.object(block).worldBounds();
    const std::optional<double> height =
        restingHeight(scene.object("shelf_unit"), Vector3(bounds.center().x(), bounds.center().y(), bounds.min().z()), 0.015);
    ASSERT_TRUE(height) << block;
    EXPECT_NEAR(*height, 0.77, 5e-4) << block;
  }
  const std::vector<ObjectSemanticsDecision> decisions = inferObjectSemantics(scene);
  EXPECT_TRUE(scene.object("above").movable);
  EXPECT_THAT(decisionFor(decisions, "above").reason, HasSubstr("rests on shelf_unit"));
  EXPECT_TRUE(scene.object("sunk").movable);
  EXPECT_FALSE(scene.object("floating").movable);
  EXPECT_THAT(decisionFor(decisions, "floating").reason, HasSubstr("rests on nothing"));
  const SymbolicState state = observeSymbolicState(scene);
  EXPECT_EQ(state.onTopOf.at("above"), "shelf_unit");
  EXPECT_EQ(state.onTopOf.at("sunk"), "shelf_unit");
  EXPECT_FALSE(state.onTopOf.count("floating"));
  // A top grasp keeps the fingers above the low board, not above the bounds' top.
  GraspRequest request;
  request.object = "above";
  request.direction = GraspDirection::kTop;
  const GraspPlan plan = makeGraspPlanner(defaultGraspPlannerName())->plan(reachFor("panda", scene), request);
  ASSERT_TRUE(plan.success()) << plan.reason;
}

TEST(ObjectSemantics, KauthamScenesAsTheyAre) {
  const auto shared = sharedDataDirectory();
  if (!shared) GTEST_SKIP() << "../shared/data is absent";
  KauthamProblem ur3e = readKauthamProblem(*shared / "kautham/OMPL_geo_demos/UR3e/ur3e_fib_upc.xml");
  static_cast<void>(inferObjectSemantics(ur3e.scene));
  EXPECT_TRUE(ur3e.scene.object("wood_piece").movable);
  EXPECT_EQ(ur3e.scene.object("table").role, ObjectRole::kSupport);
  EXPECT_FALSE(ur3e.scene.object("wall").movable);
  KauthamProblem tx90 = readKauthamProblem(*shared / "kautham/OMPL_geo_demos/TX90_IOC/OMPL_RRTConnect_TX90_gripper_TwoCan.xml");
  static_cast<void>(inferObjectSemantics(tx90.scene));
  EXPECT_TRUE(tx90.scene.object("can").movable);
  KauthamProblem noGripper = readKauthamProblem(*shared / "kautham/OMPL_geo_demos/TX90_IOC/OMPL_RRTConnect_TX90_TwoCan.xml");
  const std::vector<ObjectSemanticsDecision> decisions = inferObjectSemantics(noGripper.scene);
  EXPECT_FALSE(noGripper.scene.object("can").movable);
  EXPECT_THAT(decisionFor(decisions, "can").reason, HasSubstr("no robot has a gripper"));
}

}  // namespace
}  // namespace lang2manip::test
