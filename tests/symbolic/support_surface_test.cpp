// The flat tops objects may rest on, from collision shapes.

#include <gtest/gtest.h>

#include "lang2manip/symbolic/support_surface.hpp"

namespace lang2manip {
namespace {

SceneObject objectWith(const Geometry& geometry, const Matrix3& rotation = Matrix3::Identity()) {
  SceneObject object;
  object.name = "thing";
  Shape shape;
  shape.geometry = geometry;
  object.collisions.push_back(shape);
  object.pose.linear() = rotation;
  object.pose.translation() = Vector3(0.2, 0.1, 0.8);
  return object;
}

TEST(SupportSurface, ALevelBoxTopIsItsFace) {
  const SupportSurface surface = supportSurface(objectWith(Box{Vector3(0.10, 0.06, 0.04)}));
  ASSERT_TRUE(surface.top.has_value()) << surface.why;
  EXPECT_NEAR(surface.top->sizes().x(), 0.10, 1e-9);
  EXPECT_NEAR(surface.top->sizes().y(), 0.06, 1e-9);
  EXPECT_NEAR(surface.top->max().z(), 0.82, 1e-9);
  EXPECT_TRUE(footprintFits(Vector3(0.05, 0.09, 0.2), *surface.top));  // turned a quarter
  EXPECT_FALSE(footprintFits(Vector3(0.075, 0.075, 0.01), *surface.top));
  EXPECT_TRUE(footprintFits(Vector3(0.105, 0.065, 0.01), *surface.top));  // within the slack: equal blocks stack
}

TEST(SupportSurface, ATurnedBoxOffersTheSquareInsideItsFace) {
  const Matrix3 yaw = Eigen::AngleAxisd(M_PI / 4.0, Vector3::UnitZ()).toRotationMatrix();
  const SupportSurface surface = supportSurface(objectWith(Box{Vector3(0.10, 0.06, 0.04)}, yaw));
  ASSERT_TRUE(surface.top.has_value());
  EXPECT_NEAR(surface.top->sizes().x(), 0.06 / std::sqrt(2.0), 1e-9);
  // On its side, the box's level face is another one.
  const Matrix3 side = Eigen::AngleAxisd(M_PI / 2.0, Vector3::UnitX()).toRotationMatrix();
  const SupportSurface onSide = supportSurface(objectWith(Box{Vector3(0.10, 0.06, 0.04)}, side));
  ASSERT_TRUE(onSide.top.has_value());
  EXPECT_NEAR(onSide.top->sizes().y(), 0.04, 1e-9);
}

TEST(SupportSurface, RoundTiltedAndOpenTopsOfferNone) {
  const Matrix3 lying = Eigen::AngleAxisd(M_PI / 2.0, Vector3::UnitY()).toRotationMatrix();
  EXPECT_EQ(supportSurface(objectWith(Cylinder{0.01, 0.13}, lying)).why, "its top is round (a cylinder lying on its side)");
  EXPECT_TRUE(supportSurface(objectWith(Cylinder{0.03, 0.10})).top.has_value());  // standing: its disk
  EXPECT_EQ(supportSurface(objectWith(Sphere{0.03})).why, "its top is round (a sphere)");
  const Matrix3 tilted = Eigen::AngleAxisd(0.4, Vector3::UnitX()).toRotationMatrix();
  EXPECT_EQ(supportSurface(objectWith(Box{Vector3(0.1, 0.1, 0.1)}, tilted)).why, "its top is not level (a box standing tilted)");
  SceneObject cup = objectWith(Box{Vector3(0.08, 0.08, 0.1)});
  cup.cavity = AlignedBox3(Vector3(-0.03, -0.03, -0.04), Vector3(0.03, 0.03, 0.05));
  EXPECT_EQ(supportSurface(cup).why, "it is open at the top (a container: put things in it)");
}

}  // namespace
}  // namespace lang2manip
