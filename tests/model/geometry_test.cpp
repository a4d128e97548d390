#include "lang2manip/model/geometry.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <variant>

#include "lang2manip/core/error.hpp"
#include "lang2manip/model/mesh_loader.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;

constexpr double kHalfPi = std::numbers::pi / 2;

void expectBounds(const AlignedBox3& box, const Vector3& min, const Vector3& max,
                  double tolerance) {
  ASSERT_FALSE(box.isEmpty());
  EXPECT_TRUE((box.min() - min).cwiseAbs().maxCoeff() <= tolerance)
      << "min " << box.min().transpose() << " expected " << min.transpose();
  EXPECT_TRUE((box.max() - max).cwiseAbs().maxCoeff() <= tolerance)
      << "max " << box.max().transpose() << " expected " << max.transpose();
}

Shape shapeAt(Geometry geometry, const Pose& origin) {
  Shape shape;
  shape.geometry = std::move(geometry);
  shape.origin = origin;
  return shape;
}

Pose poseOf(const Vector3& translation, const Eigen::AngleAxisd& rotation) {
  Pose pose = Pose::Identity();
  pose.translate(translation);
  pose.rotate(rotation);
  return pose;
}

TEST(Geometry, BoxTurnedAboutZ) {
  const Pose origin = poseOf(Vector3(1, 2, 3), Eigen::AngleAxisd(kHalfPi, Vector3::UnitZ()));
  const AlignedBox3 box = shapeBounds(shapeAt(Box{Vector3(2, 4, 6)}, origin));
  expectBounds(box, Vector3(-1, 1, 0), Vector3(3, 3, 6), 1e-12);
}

TEST(Geometry, BoxTurned45DegreesMatchesItsCorners) {
  const Pose origin = poseOf(Vector3(0, 0, 1), Eigen::AngleAxisd(kHalfPi / 2, Vector3::UnitX()));
  const AlignedBox3 box = shapeBounds(shapeAt(Box{Vector3(1, 2, 2)}, origin));
  const double reach = std::sqrt(2.0);  // half diagonal of the 2 x 2 face
  expectBounds(box, Vector3(-0.5, -reach, 1 - reach), Vector3(0.5, reach, 1 + reach), 1e-12);
}

TEST(Geometry, SphereIgnoresRotation) {
  const Pose origin = poseOf(Vector3(1, 0, 0), Eigen::AngleAxisd(0.3, Vector3::UnitY()));
  expectBounds(shapeBounds(shapeAt(Sphere{0.5}, origin)), Vector3(0.5, -0.5, -0.5),
               Vector3(1.5, 0.5, 0.5), 1e-12);
}

TEST(Geometry, CylinderUprightAndLyingDown) {
  const Cylinder cylinder{0.5, 4.0};
  expectBounds(shapeBounds(shapeAt(cylinder, Pose::Identity())), Vector3(-0.5, -0.5, -2),
               Vector3(0.5, 0.5, 2), 1e-12);
  const Pose lying = poseOf(Vector3(0, 0, 1), Eigen::AngleAxisd(kHalfPi, Vector3::UnitY()));
  expectBounds(shapeBounds(shapeAt(cylinder, lying)), Vector3(-2, -0.5, 0.5),
               Vector3(2, 0.5, 1.5), 1e-12);
}

TEST(Geometry, CylinderTiltedMatchesSampledRim) {
  const Cylinder cylinder{0.3, 1.0};
  const Pose origin =
      poseOf(Vector3(0.1, 0.2, 0.3), Eigen::AngleAxisd(0.7, Vector3(1, 2, 3).normalized()));
  AlignedBox3 sampled;
  for (int i = 0; i < 3600; ++i) {
    const double angle = 2 * std::numbers::pi * i / 3600;
    for (double z : {-0.5, 0.5}) {
      sampled.extend(origin * Vector3(0.3 * std::cos(angle), 0.3 * std::sin(angle), z));
    }
  }
  expectBounds(shapeBounds(shapeAt(cylinder, origin)), sampled.min(), sampled.max(), 1e-6);
}

TEST(Geometry, ScaledMeshUsesItsVertices) {
  MeshGeometry geometry;
  const auto file = test::testDataDirectory() / "meshes" / "tetrahedron_binary.stl";
  geometry.mesh = std::make_shared<const TriangleMesh>(loadTriangleMesh(file.string()));
  geometry.scale = Vector3(2, 3, 4);
  const Pose origin = poseOf(Vector3(10, 0, 0), Eigen::AngleAxisd(kHalfPi, Vector3::UnitZ()));
  // Scaled vertices (0,0,0) (2,0,0) (0,3,0) (0,0,4), turned: (0,0,0) (0,2,0) (-3,0,0) (0,0,4).
  expectBounds(shapeBounds(shapeAt(geometry, origin)), Vector3(7, 0, 0), Vector3(10, 2, 4), 1e-12);
}

TEST(Geometry, MeshWithoutDataHasEmptyBounds) {
  EXPECT_TRUE(shapeBounds(shapeAt(MeshGeometry{}, Pose::Identity())).isEmpty());
}

TEST(Geometry, KindNames) {
  EXPECT_EQ(geometryKindName(Box{}), "box");
  EXPECT_EQ(geometryKindName(Sphere{}), "sphere");
  EXPECT_EQ(geometryKindName(Cylinder{}), "cylinder");
  EXPECT_EQ(geometryKindName(MeshGeometry{}), "mesh");
}

TEST(Geometry, ScaledShapeMultipliesLengthsAndOrigin) {
  const Pose origin = poseOf(Vector3(1, 2, 3), Eigen::AngleAxisd(0.5, Vector3::UnitX()));
  const Shape box = scaledShape(shapeAt(Box{Vector3(1, 2, 3)}, origin), 0.001);
  EXPECT_TRUE(std::get<Box>(box.geometry).size.isApprox(Vector3(0.001, 0.002, 0.003)));
  EXPECT_TRUE(box.origin.translation().isApprox(Vector3(0.001, 0.002, 0.003)));
  EXPECT_TRUE(box.origin.linear().isApprox(origin.linear()));

  const Shape sphere = scaledShape(shapeAt(Sphere{2.0}, origin), 2.0);
  EXPECT_DOUBLE_EQ(std::get<Sphere>(sphere.geometry).radius, 4.0);

  const Shape cylinder = scaledShape(shapeAt(Cylinder{1.0, 5.0}, origin), 3.0);
  EXPECT_DOUBLE_EQ(std::get<Cylinder>(cylinder.geometry).radius, 3.0);
  EXPECT_DOUBLE_EQ(std::get<Cylinder>(cylinder.geometry).length, 15.0);

  MeshGeometry geometry;
  geometry.scale = Vector3(1, 2, 3);
  geometry.reference = "meshes/a.stl";
  const Shape mesh = scaledShape(shapeAt(geometry, origin), 10.0);
  EXPECT_TRUE(std::get<MeshGeometry>(mesh.geometry).scale.isApprox(Vector3(10, 20, 30)));
  EXPECT_EQ(std::get<MeshGeometry>(mesh.geometry).reference, "meshes/a.stl");
}

TEST(Geometry, ScaledShapeRejectsBadFactor) {
  const Shape box = shapeAt(Box{Vector3(1, 1, 1)}, Pose::Identity());
  for (double factor : {0.0, -1.0, std::nan("")}) {
    try {
      scaledShape(box, factor);
      ADD_FAILURE() << "no error for " << factor;
    } catch (const InputError& error) {
      EXPECT_THAT(std::string(error.what()), HasSubstr("scale factor must be positive"));
    }
  }
}

TEST(Geometry, BoundsOfScaledShapeAreScaled) {
  const Pose origin = poseOf(Vector3(1, 2, 3), Eigen::AngleAxisd(0.4, Vector3::UnitY()));
  const Shape cylinder = shapeAt(Cylinder{0.5, 2.0}, origin);
  const AlignedBox3 before = shapeBounds(cylinder);
  const AlignedBox3 after = shapeBounds(scaledShape(cylinder, 2.5));
  expectBounds(after, 2.5 * before.min(), 2.5 * before.max(), 1e-12);
}

std::string rangeError(const Shape& shape) {
  try {
    requireShapeInRange(shape, "link \"a\" collision 1", SourceLocation{"m.urdf", 4});
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(GeometryRange, AcceptsEveryShapeWithinTheRangeAndZeroSizes) {
  EXPECT_EQ(rangeError(shapeAt(Box{Vector3(kMaxModelLength, kMinModelLength, 0.0)}, Pose::Identity())), "(no error)");
  EXPECT_EQ(rangeError(shapeAt(Sphere{0.0}, Pose::Identity())), "(no error)");
  MeshGeometry mirrored;
  mirrored.scale = Vector3(-1, 0.001, 1000);
  EXPECT_EQ(rangeError(shapeAt(mirrored, poseOf(Vector3(-kMaxModelLength, 0, 0), Eigen::AngleAxisd(1.0, Vector3::UnitY())))),
            "(no error)");
}

TEST(GeometryRange, RefusesEveryDimensionPositionAndScaleOutsideIt) {
  const Pose far = poseOf(Vector3(0, 1.5e4, 0), Eigen::AngleAxisd(0.0, Vector3::UnitZ()));
  EXPECT_EQ(rangeError(shapeAt(Box{Vector3(1, 1e300, 1)}, Pose::Identity())),
            "m.urdf:4: link \"a\" collision 1 box size 1e+300 m is outside [1e-06, 10000] m");
  EXPECT_THAT(rangeError(shapeAt(Box{Vector3(1, -1, 1)}, Pose::Identity())), HasSubstr("box size -1 m is outside"));
  EXPECT_THAT(rangeError(shapeAt(Sphere{1e-7}, Pose::Identity())), HasSubstr("sphere radius 1e-07 m"));
  EXPECT_THAT(rangeError(shapeAt(Cylinder{1e308, 1}, Pose::Identity())), HasSubstr("cylinder radius 1e+308 m"));
  EXPECT_THAT(rangeError(shapeAt(Cylinder{1, 2e4}, Pose::Identity())), HasSubstr("cylinder length 20000 m"));
  EXPECT_THAT(rangeError(shapeAt(Sphere{1}, far)), HasSubstr("origin (0, 15000, 0) m is more than 10000 m"));
  MeshGeometry huge;
  huge.scale = Vector3(1, 1e300, 1);
  EXPECT_THAT(rangeError(shapeAt(huge, Pose::Identity())), HasSubstr("mesh scale 1e+300 is outside"));
  MeshGeometry flat;
  flat.scale = Vector3(1, 0, 1);
  EXPECT_THAT(rangeError(shapeAt(flat, Pose::Identity())), HasSubstr("mesh scale 0 is outside"));
  // A loaded mesh whose scaled vertices reach beyond the range (the tetrahedron spans 1 m).
  auto farMesh = std::make_shared<TriangleMesh>();
  farMesh->vertices = {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 0, 3e5)};
  farMesh->triangles = {{0, 1, 2}};
  MeshGeometry vast;
  vast.mesh = farMesh;
  vast.scale = Vector3(1, 1, 0.1);
  EXPECT_THAT(rangeError(shapeAt(vast, Pose::Identity())), HasSubstr("scaled mesh corner"));
  EXPECT_THAT(rangeError(shapeAt(Box{Vector3::Constant(std::nan(""))}, Pose::Identity())), HasSubstr("box size nan"));
}

}  // namespace
}  // namespace lang2manip
