#pragma once
/// @file Collision and visual geometry: primitives and meshes, with a pose in their frame.

#include <memory>
#include <optional>
#include <string>
#include <variant>

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
