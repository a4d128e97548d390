#pragma once
/// @file Collision and visual geometry: primitives and meshes, with a pose in their frame.

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/types.hpp"
#include "lang2manip/model/triangle_mesh.hpp"

namespace lang2manip {

/// A box centred on its frame; `size` is the full extent along x, y, z.
struct Box {
  Vector3 size = Vector3::Zero();
};
/// A sphere centred on its frame.
struct Sphere {
  double radius = 0.0;
};
/// A cylinder centred on its frame, axis along z.
struct Cylinder {
  double radius = 0.0;
  double length = 0.0;
};
/// A mesh with a per-axis scale applied to its vertices.
struct MeshGeometry {
  std::shared_ptr<const TriangleMesh> mesh;
  Vector3 scale = Vector3::Ones();
  /// The reference as written in the model file (e.g. "package://x/y.stl", "meshes/a.dae").
  std::string reference;
};

using Geometry = std::variant<Box, Sphere, Cylinder, MeshGeometry>;

/// RGBA colour and optional texture of a visual.
struct Material {
  std::string name;
  Vector4 rgba = Vector4(0.7, 0.7, 0.7, 1.0);
  std::string texture;
};

/// A geometry placed in a link or object frame.
struct Shape {
  Geometry geometry;
  /// Pose of the geometry in the frame it belongs to.
  Pose origin = Pose::Identity();
  std::optional<Material> material;
  /// The name given in the model file, if any.
  std::string name;
};

/// The lengths (m) a model may hold. Every non-zero dimension (box size, radius, cylinder length,
/// mesh scale and scaled mesh extent) lies in [kMinModelLength, kMaxModelLength] and every
/// position coordinate within +-kMaxModelLength: beyond them FCL's arithmetic loses collisions
/// (a 1e300 m box is reported free). A zero dimension is a shape with no volume (never collides).
inline constexpr double kMinModelLength = 1e-6;
inline constexpr double kMaxModelLength = 1e4;

/// "<value> m is outside [1e-06, 10000] m" unless `value` is 0 or within the range (then empty).
std::string dimensionRangeProblem(double value);

/// "(x, y, z) m is more than 10000 m from the origin", or empty within the range.
std::string positionRangeProblem(const Vector3& position);

/// Throws InputError "<where>: <what> <value> m is outside [1e-06, 10000] m" unless `value` is 0
/// or within [kMinModelLength, kMaxModelLength] (negative values are refused too).
void requireDimensionInRange(double value, std::string_view what, const SourceLocation& where);

/// Throws InputError unless every coordinate of `position` lies within +-kMaxModelLength.
void requirePositionInRange(const Vector3& position, std::string_view what, const SourceLocation& where);

/// Checks every dimension of `shape`, its origin and, for a loaded mesh, its scaled extent.
void requireShapeInRange(const Shape& shape, std::string_view what, const SourceLocation& where);

/// Bounds of `shape` in the frame it belongs to (origin applied): exact for boxes, spheres and
/// cylinders in any orientation; for meshes, the bounds of the scaled, placed vertices (an empty
/// box when the mesh is not loaded or has no vertices).
AlignedBox3 shapeBounds(const Shape& shape);

/// "box", "sphere", "cylinder" or "mesh".
std::string geometryKindName(const Geometry& geometry);

/// Returns `shape` with every length multiplied by `factor` (origin translation included; a
/// mesh's scale is multiplied). Throws InputError unless `factor` is positive and finite.
Shape scaledShape(const Shape& shape, double factor);

}  // namespace lang2manip
