#include "lang2manip/model/geometry.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <type_traits>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {
namespace {

/// A box centred on `center` with the given half extents.
AlignedBox3 centredBox(const Vector3& center, const Vector3& halfExtents) {
  return AlignedBox3(center - halfExtents, center + halfExtents);
}

AlignedBox3 boxBounds(const Box& box, const Pose& X_FG) {
  // Half extent along each frame axis: sum over the box axes of |R_ij| * half size j.
  const Vector3 halfExtents = X_FG.linear().cwiseAbs() * (0.5 * box.size.cwiseAbs());
  return centredBox(X_FG.translation(), halfExtents);
}

AlignedBox3 sphereBounds(const Sphere& sphere, const Pose& X_FG) {
  return centredBox(X_FG.translation(), Vector3::Constant(std::abs(sphere.radius)));
}

AlignedBox3 cylinderBounds(const Cylinder& cylinder, const Pose& X_FG) {
  // The cylinder is the Minkowski sum of its axis segment and a disc normal to the axis. Along
  // frame axis i the segment reaches |a_i| L/2 and the disc r sqrt(1 - a_i^2).
  const Vector3 axis = X_FG.linear().col(2).normalized();
  const double radius = std::abs(cylinder.radius);
  const double halfLength = 0.5 * std::abs(cylinder.length);
  Vector3 halfExtents;
  for (int i = 0; i < 3; ++i) {
    const double a = axis[i];
    halfExtents[i] = halfLength * std::abs(a) + radius * std::sqrt(std::max(0.0, 1.0 - a * a));
  }
  return centredBox(X_FG.translation(), halfExtents);
}

AlignedBox3 meshBounds(const MeshGeometry& mesh, const Pose& X_FG) {
  AlignedBox3 box;
  if (!mesh.mesh) return box;
  for (const Vector3& vertex : mesh.mesh->vertices) box.extend(X_FG * mesh.scale.cwiseProduct(vertex));
  return box;
}

std::string rangeText() {
  return "[" + numberText(kMinModelLength) + ", " + numberText(kMaxModelLength) + "] m";
}

}  // namespace

std::string dimensionRangeProblem(double value) {
  if (value == 0.0 || (value >= kMinModelLength && value <= kMaxModelLength)) return {};
  return numberText(value) + " m is outside " + rangeText();
}

std::string positionRangeProblem(const Vector3& position) {
  if (position.cwiseAbs().maxCoeff<Eigen::PropagateNaN>() <= kMaxModelLength) return {};
  return "(" + numberText(position.x()) + ", " + numberText(position.y()) + ", " +
         numberText(position.z()) + ") m is more than " + numberText(kMaxModelLength) +
         " m from the origin";
}

void requireDimensionInRange(double value, std::string_view what, const SourceLocation& where) {
  const std::string problem = dimensionRangeProblem(value);
  if (!problem.empty()) throw InputError(where, std::string(what) + " " + problem);
}

void requirePositionInRange(const Vector3& position, std::string_view what, const SourceLocation& where) {
  const std::string problem = positionRangeProblem(position);
  if (!problem.empty()) throw InputError(where, std::string(what) + " " + problem);
}

void requireShapeInRange(const Shape& shape, std::string_view what, const SourceLocation& where) {
  const std::string name(what);
  requirePositionInRange(shape.origin.translation(), name + " origin", where);
  if (const auto* box = std::get_if<Box>(&shape.geometry)) {
    for (int i = 0; i < 3; ++i) requireDimensionInRange(box->size[i], name + " box size", where);
  } else if (const auto* sphere = std::get_if<Sphere>(&shape.geometry)) {
    requireDimensionInRange(sphere->radius, name + " sphere radius", where);
  } else if (const auto* cylinder = std::get_if<Cylinder>(&shape.geometry)) {
    requireDimensionInRange(cylinder->radius, name + " cylinder radius", where);
    requireDimensionInRange(cylinder->length, name + " cylinder length", where);
  } else {
    const auto& mesh = std::get<MeshGeometry>(shape.geometry);
    for (int i = 0; i < 3; ++i) {
      // A mirroring (negative) scale is allowed; its magnitude is a length factor.
      if (!(std::abs(mesh.scale[i]) >= kMinModelLength && std::abs(mesh.scale[i]) <= kMaxModelLength)) {
        throw InputError(where, name + " mesh scale " + numberText(mesh.scale[i]) + " is outside +-" +
                                    rangeText());
      }
    }
    const AlignedBox3 bounds = shapeBounds(Shape{shape.geometry, Pose::Identity(), {}, {}});
    if (!bounds.isEmpty()) {
      requirePositionInRange(bounds.min(), name + " scaled mesh corner", where);
      requirePositionInRange(bounds.max(), name + " scaled mesh corner", where);
    }
  }
}

AlignedBox3 shapeBounds(const Shape& shape) {
  const Pose& X_FG = shape.origin;
  return std::visit(
      [&X_FG](const auto& geometry) -> AlignedBox3 {
        using T = std::decay_t<decltype(geometry)>;
        if constexpr (std::is_same_v<T, Box>) return boxBounds(geometry, X_FG);
        if constexpr (std::is_same_v<T, Sphere>) return sphereBounds(geometry, X_FG);
        if constexpr (std::is_same_v<T, Cylinder>) return cylinderBounds(geometry, X_FG);
        if constexpr (std::is_same_v<T, MeshGeometry>) return meshBounds(geometry, X_FG);
      },
      shape.geometry);
}

std::string geometryKindName(const Geometry& geometry) {
  return std::visit(
      [](const auto& g) -> std::string {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, Box>) return "box";
        if constexpr (std::is_same_v<T, Sphere>) return "sphere";
        if constexpr (std::is_same_v<T, Cylinder>) return "cylinder";
        if constexpr (std::is_same_v<T, MeshGeometry>) return "mesh";
      },
      geometry);
}

Shape scaledShape(const Shape& shape, double factor) {
  if (!std::isfinite(factor) || factor <= 0.0) {
    throw InputError("scale factor must be positive and finite, got " + std::to_string(factor));
  }
  Shape scaled = shape;
  scaled.origin.translation() *= factor;
  std::visit(
      [factor](auto& g) {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, Box>) g.size *= factor;
        if constexpr (std::is_same_v<T, Sphere>) g.radius *= factor;
        if constexpr (std::is_same_v<T, Cylinder>) {
          g.radius *= factor;
          g.length *= factor;
        }
        if constexpr (std::is_same_v<T, MeshGeometry>) g.scale *= factor;
      },
      scaled.geometry);
  return scaled;
}

}  // namespace lang2manip
