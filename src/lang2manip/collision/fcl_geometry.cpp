#include "lang2manip/collision/fcl_geometry.hpp"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "lang2manip/collision/fcl_mesh_cache.hpp"

namespace lang2manip {
namespace {

/// How far (m) a capsule's end sphere may be from the cylinder's end, and how much the radii
/// may differ, for a triple to merge (the URDFs write 10 significant digits).
constexpr double kCapsuleTolerance = 1e-4;

struct CapsuleParts {
  const Shape* cylinder = nullptr;
  const Shape* endA = nullptr;
  const Shape* endB = nullptr;
};

/// "capsule3_a" -> ("capsule3", "a"); nullopt for other names.
std::optional<std::pair<std::string, std::string>> capsulePart(const std::string& name) {
  if (name.rfind("capsule", 0) != 0) return std::nullopt;
  const std::size_t underscore = name.rfind('_');
  if (underscore == std::string::npos || underscore <= 7) return std::nullopt;
  for (std::size_t i = 7; i < underscore; ++i) {
    if (name[i] < '0' || name[i] > '9') return std::nullopt;
  }
  std::string part = name.substr(underscore + 1);
  if (part != "cylinder" && part != "a" && part != "b") return std::nullopt;
  return std::make_pair(name.substr(0, underscore), part);
}

/// The capsule (radius, length) a triple stands for, or nullopt when the parts do not fit.
std::optional<std::pair<double, double>> capsuleOf(const CapsuleParts& parts) {
  if (!parts.cylinder || !parts.endA || !parts.endB) return std::nullopt;
  const auto* cylinder = std::get_if<Cylinder>(&parts.cylinder->geometry);
  const auto* a = std::get_if<Sphere>(&parts.endA->geometry);
  const auto* b = std::get_if<Sphere>(&parts.endB->geometry);
  if (!cylinder || !a || !b) return std::nullopt;
  if (std::abs(a->radius - cylinder->radius) > kCapsuleTolerance ||
      std::abs(b->radius - cylinder->radius) > kCapsuleTolerance) {
    return std::nullopt;
  }
  const Pose& X_FC = parts.cylinder->origin;
  const Vector3 top = X_FC * Vector3(0, 0, cylinder->length / 2);
  const Vector3 bottom = X_FC * Vector3(0, 0, -cylinder->length / 2);
  const Vector3 pa = parts.endA->origin.translation();
  const Vector3 pb = parts.endB->origin.translation();
  const bool fits = ((pa - top).norm() < kCapsuleTolerance && (pb - bottom).norm() < kCapsuleTolerance) ||
                    ((pa - bottom).norm() < kCapsuleTolerance && (pb - top).norm() < kCapsuleTolerance);
  if (!fits) return std::nullopt;
  return std::make_pair(cylinder->radius, cylinder->length);
}

std::map<std::string, CapsuleParts> capsuleTriples(const std::vector<Shape>& shapes) {
  std::map<std::string, CapsuleParts> triples;
  for (const Shape& shape : shapes) {
    const auto part = capsulePart(shape.name);
    if (!part) continue;
    CapsuleParts& parts = triples[part->first];
    if (part->second == "cylinder") parts.cylinder = &shape;
    if (part->second == "a") parts.endA = &shape;
    if (part->second == "b") parts.endB = &shape;
  }
  return triples;
}

FclShape placed(std::shared_ptr<const fcl::CollisionGeometryd> geometry, const Pose& origin) {
  FclShape shape;
  shape.origin = origin;
  shape.localCenter = geometry->aabb_local.center();
  shape.localHalfExtent = (geometry->aabb_local.max_ - geometry->aabb_local.min_) / 2;
  shape.geometry = std::move(geometry);
  return shape;
}

template <typename T, typename... Args>
std::shared_ptr<const fcl::CollisionGeometryd> makeShape(Args... args) {
  auto shape = std::make_shared<T>(args...);
  shape->computeLocalAABB();
  return shape;
}

}  // namespace

std::shared_ptr<const fcl::CollisionGeometryd> FclGeometryBuilder::primitive(const Geometry& geometry) {
  if (const auto* box = std::get_if<Box>(&geometry)) {
    if (!(box->size.minCoeff() > 0.0)) return nullptr;
    return makeShape<fcl::Boxd>(box->size.x(), box->size.y(), box->size.z());
  }
  if (const auto* sphere = std::get_if<Sphere>(&geometry)) {
    if (!(sphere->radius > 0.0)) return nullptr;
    return makeShape<fcl::Sphered>(sphere->radius);
  }
  if (const auto* cylinder = std::get_if<Cylinder>(&geometry)) {
    if (!(cylinder->radius > 0.0) || !(cylinder->length > 0.0)) return nullptr;
    return makeShape<fcl::Cylinderd>(cylinder->radius, cylinder->length);
  }
  return mesh(std::get<MeshGeometry>(geometry));
}

std::shared_ptr<const fcl::CollisionGeometryd> FclGeometryBuilder::mesh(const MeshGeometry& geometry) {
  auto model = sharedMeshBvh(geometry);
  if (model) meshes_.emplace(MeshKey{geometry.mesh.get(), geometry.scale.x(), geometry.scale.y(), geometry.scale.z()}, model);
  return model;
}

std::vector<FclShape> FclGeometryBuilder::build(const std::vector<Shape>& shapes) {
  std::vector<FclShape> result;
  std::vector<const Shape*> merged;
  for (const auto& [name, parts] : capsuleTriples(shapes)) {
    const auto capsule = capsuleOf(parts);
    if (!capsule) continue;
    result.push_back(placed(makeShape<fcl::Capsuled>(capsule->first, capsule->second),
                            parts.cylinder->origin));
    merged.insert(merged.end(), {parts.cylinder, parts.endA, parts.endB});
  }
  for (const Shape& shape : shapes) {
    if (std::find(merged.begin(), merged.end(), &shape) != merged.end()) continue;
    auto geometry = primitive(shape.geometry);
    if (!geometry) {
      ++skipped_;
      continue;
    }
    result.push_back(placed(std::move(geometry), shape.origin));
  }
  return result;
}

}  // namespace lang2manip
