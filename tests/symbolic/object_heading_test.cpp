// Which way objects point, which turns leave them looking the same, and the goals built on them
// (at_position, turned, facing) checked on scenes.

#include <cmath>

#include <gtest/gtest.h>

#include "lang2manip/symbolic/object_heading.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"

namespace lang2manip {
namespace {

constexpr double kPi = 3.14159265358979323846;

Shape shapeOf(const Geometry& geometry, const Pose& origin = Pose::Identity()) {
  Shape shape;
  shape.geometry = geometry;
  shape.origin = origin;
  return shape;
}

SceneObject objectWith(std::vector<Shape> shapes, const Matrix3& rotation = Matrix3::Identity(), const std::string& name = "thing") {
  SceneObject object;
  object.name = name;
  object.collisions = std::move(shapes);
  object.pose.linear() = rotation;
  object.pose.translation() = Vector3(0.2, 0.1, 0.8);
  object.movable = true;
  return object;
}

Matrix3 yaw(double angle) { return verticalTurn(angle); }
Matrix3 lying() { return Eigen::AngleAxisd(kPi / 2.0, Vector3::UnitY()).toRotationMatrix(); }

TEST(ObjectHeading, TheLongSideOfABoxFollowsItsYawAndASquareHasNone) {
  const SceneObject bar = objectWith({shapeOf(Box{Vector3(0.10, 0.02, 0.02)})});
  EXPECT_NEAR(*longSideYaw(bar, Matrix3::Identity()), 0.0, 1e-9);
  EXPECT_NEAR(*longSideYaw(bar, yaw(0.7)), 0.7, 1e-9);
  EXPECT_NEAR(*longSideYaw(bar, yaw(-0.7)), kPi - 0.7, 1e-9);  // a line: either end
  EXPECT_FALSE(longSideYaw(objectWith({shapeOf(Box{Vector3(0.05, 0.05, 0.1)})}), Matrix3::Identity()).has_value());
  EXPECT_FALSE(longSideYaw(objectWith({shapeOf(Box{Vector3(0.05, 0.045, 0.1)})}), Matrix3::Identity()).has_value());
  // A lying cylinder points along its axis.
  const SceneObject pen = objectWith({shapeOf(Cylinder{0.01, 0.13})});
  EXPECT_NEAR(*longSideYaw(pen, lying()), 0.0, 1e-9);
  EXPECT_FALSE(longSideYaw(pen, Matrix3::Identity()).has_value());  // standing: round footprint
}

TEST(ObjectHeading, SymmetryFromTheShapes) {
  EXPECT_EQ(turnSymmetry(objectWith({shapeOf(Cylinder{0.03, 0.1})})), 0.0);
  EXPECT_EQ(turnSymmetry(objectWith({shapeOf(Sphere{0.03})})), 0.0);
  EXPECT_NEAR(turnSymmetry(objectWith({shapeOf(Cylinder{0.01, 0.13})}, lying())), kPi, 1e-12);
  EXPECT_NEAR(turnSymmetry(objectWith({shapeOf(Box{Vector3(0.10, 0.02, 0.02)})}, yaw(0.3))), kPi, 1e-12);
  EXPECT_NEAR(turnSymmetry(objectWith({shapeOf(Box{Vector3(0.05, 0.05, 0.1)})})), kPi / 2.0, 1e-12);
  // A cup of four walls and a floor is square; with a handle on one side it is not symmetric.
  std::vector<Shape> cup;
  Pose at = Pose::Identity();
  at.translation() = Vector3(0.0, 0.0, -0.045);
  cup.push_back(shapeOf(Box{Vector3(0.08, 0.08, 0.01)}, at));
  for (int side = 0; side < 4; ++side) {
    Pose wall = Pose::Identity();
    wall.linear() = yaw(side * kPi / 2.0);
    wall.translation() = wall.linear() * Vector3(0.035, 0.0, 0.0);
    cup.push_back(shapeOf(Box{Vector3(0.01, 0.08, 0.1)}, wall));
  }
  EXPECT_NEAR(turnSymmetry(objectWith(cup)), kPi / 2.0, 1e-12);
  Pose handle = Pose::Identity();
  handle.translation() = Vector3(0.05, 0.0, 0.0);
  cup.push_back(shapeOf(Box{Vector3(0.02, 0.01, 0.05)}, handle));
  EXPECT_EQ(turnSymmetry(objectWith(cup)), 2.0 * kPi);
  SceneObject meshed = objectWith({shapeOf(MeshGeometry{})});
  EXPECT_EQ(turnSymmetry(meshed), 2.0 * kPi);  // meshes are not analysed
  EXPECT_EQ(turnSymmetry(objectWith({})), 2.0 * kPi);
}

TEST(ObjectHeading, AnglesAndTurns) {
  EXPECT_NEAR(reducedAngle(3.0 * kPi / 2.0, 2.0 * kPi), -kPi / 2.0, 1e-12);
  EXPECT_NEAR(reducedAngle(kPi, 2.0 * kPi), kPi, 1e-12);
  EXPECT_NEAR(reducedAngle(0.6 * kPi, kPi), -0.4 * kPi, 1e-12);
  EXPECT_EQ(reducedAngle(1.0, 0.0), 0.0);
  const Matrix3 from = lying();
  const TurnBetween turn = turnBetween(from, yaw(0.8) * from);
  EXPECT_NEAR(turn.yaw, 0.8, 1e-9);
  EXPECT_NEAR(turn.tilt, 0.0, 1e-9);
  const Matrix3 tipped = Eigen::AngleAxisd(0.3, Vector3::UnitX()).toRotationMatrix();
  const TurnBetween tippedTurn = turnBetween(Matrix3::Identity(), yaw(-2.0) * tipped);
  EXPECT_NEAR(tippedTurn.yaw, -2.0, 1e-9);
  EXPECT_NEAR(tippedTurn.tilt, 0.3, 1e-9);
  EXPECT_EQ(degreesText(kPi / 2.0), "90 deg");
}

Scene sceneWith(const SceneObject& a, const SceneObject& b) {
  Scene scene;
  scene.addObject(a);
  scene.addObject(b);
  return scene;
}

TEST(PoseGoals, AtPositionTurnedAndFacingAreCheckedFromGeometry) {
  const SceneObject bar = objectWith({shapeOf(Box{Vector3(0.10, 0.02, 0.02)})}, Matrix3::Identity(), "bar");
  SceneObject cube = objectWith({shapeOf(Box{Vector3(0.04, 0.04, 0.04)})}, Matrix3::Identity(), "cube");
  cube.pose.translation() = Vector3(0.2, 0.4, 0.8);  // straight left of the bar (+y)
  const Scene before = sceneWith(bar, cube);
  GoalCheckOptions options;
  options.initialScene = &before;

  Goal at;
  at.kind = GoalKind::kAtPosition;
  at.object = "bar";
  at.position = Vector3(0.2, 0.11, 0.0);
  EXPECT_TRUE(checkGoalInScene(before, at, options).holds);  // 1 cm off: within 2 cm
  at.position = Vector3(0.2, 0.13, 0.0);
  EXPECT_FALSE(checkGoalInScene(before, at, options).holds);

  Goal turned;
  turned.kind = GoalKind::kTurned;
  turned.object = "bar";
  turned.angle = kPi / 2.0;
  EXPECT_FALSE(checkGoalInScene(before, turned, options).holds);
  SceneObject turnedBar = bar;
  turnedBar.pose.linear() = yaw(kPi / 2.0);
  const Scene after = sceneWith(turnedBar, cube);
  const GoalCheck check = checkGoalInScene(after, turned, options);
  EXPECT_TRUE(check.holds) << check.explanation;
  turned.angle = -kPi / 2.0;  // the bar looks the same turned either way
  EXPECT_TRUE(checkGoalInScene(after, turned, options).holds);
  turnedBar.pose.translation().x() += 0.05;  // turned, but somewhere else
  EXPECT_FALSE(checkGoalInScene(sceneWith(turnedBar, cube), turned, options).holds);
  turned.position = turnedBar.pose.translation();  // where the instruction put it before the turn (no robot: base = world)
  EXPECT_TRUE(checkGoalInScene(sceneWith(turnedBar, cube), turned, options).holds);
  turned.position.reset();
  EXPECT_THROW((void)checkGoalInScene(after, turned, {}), InputError);  // needs the initial scene

  Goal facing;
  facing.kind = GoalKind::kFacing;
  facing.object = "bar";
  facing.target = "cube";
  EXPECT_FALSE(checkGoalInScene(before, facing, options).holds);  // along x, the cube is along y
  EXPECT_TRUE(checkGoalInScene(after, facing, options).holds) << checkGoalInScene(after, facing, options).explanation;
  facing.object = "cube";
  facing.target = "bar";
  EXPECT_EQ(checkGoalInScene(after, facing, options).explanation, "cube has no long side to point with");
}

}  // namespace
}  // namespace lang2manip
