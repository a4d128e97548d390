#include "lang2manip/collision/fcl_penetration.hpp"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace lang2manip {
namespace {

/// Contacts asked of FCL for depths and directions (box-box gives several, different depths).
constexpr std::size_t kContacts = 16;
/// Distinct directions probed at most (each up to two narrow-phase calls).
constexpr std::size_t kDirections = 6;
/// Slack of a probe: a translation of exactly the tolerance leaves the bodies touching.
constexpr double kProbeSlack = 1e-9;
constexpr double kDepthResolution = 1e-4;

using Mesh = fcl::BVHModel<fcl::OBBRSSd>;

const Mesh* meshOf(const PlacedFclShape& placed) {
  return dynamic_cast<const Mesh*>(placed.shape->geometry.get());
}

bool overlaps(const PlacedFclShape& a, const Pose& X_WA, const PlacedFclShape& b) {
  const fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::collide(a.shape->geometry.get(), X_WA, b.shape->geometry.get(), *b.pose, request, result);
  return result.isCollision();
}

fcl::CollisionResultd contactsOf(const PlacedFclShape& a, const PlacedFclShape& b, std::size_t count) {
  const fcl::CollisionRequestd request(count, true);
  fcl::CollisionResultd result;
  fcl::collide(a.shape->geometry.get(), *a.pose, b.shape->geometry.get(), *b.pose, request, result);
  return result;
}

/// Unit directions, each kept once up to sign.
class Directions {
 public:
  void add(const Vector3& direction) {
    if (!direction.allFinite() || direction.norm() < 1e-12 || list_.size() == kDirections) return;
    const Vector3 unit = direction.normalized();
    const auto same = [&unit](const Vector3& known) { return std::abs(known.dot(unit)) > 1.0 - 1e-9; };
    if (std::none_of(list_.begin(), list_.end(), same)) list_.push_back(unit);
  }
  [[nodiscard]] const std::vector<Vector3>& list() const { return list_; }

 private:
  std::vector<Vector3> list_;
};

/// World normal of triangle `index` of the mesh of `placed` (zero when out of range).
Vector3 triangleNormal(const PlacedFclShape& placed, const Mesh& mesh, std::intptr_t index) {
  if (index < 0 || index >= mesh.num_tris || !mesh.tri_indices || !mesh.vertices) return Vector3::Zero();
  const fcl::Triangle& triangle = mesh.tri_indices[index];
  const Vector3& p = mesh.vertices[triangle[0]];
  const Vector3 normal = (mesh.vertices[triangle[1]] - p).cross(mesh.vertices[triangle[2]] - p);
  return placed.pose->linear() * normal;
}

bool separatedAlong(const PlacedFclShape& a, const PlacedFclShape& b, const Vector3& direction,
                    double length) {
  for (const double sign : {1.0, -1.0}) {
    Pose X_WA = *a.pose;
    X_WA.translation() += sign * length * direction;
    if (!overlaps(a, X_WA, b)) return true;
  }
  return false;
}

bool separatedAlongAny(const PlacedFclShape& a, const PlacedFclShape& b, const Directions& directions,
                       double length) {
  return std::any_of(directions.list().begin(), directions.list().end(),
                     [&](const Vector3& n) { return separatedAlong(a, b, n, length); });
}

double deepest(const fcl::CollisionResultd& result) {
  double depth = 0.0;
  for (std::size_t c = 0; c < result.numContacts(); ++c) {
    depth = std::max(depth, result.getContact(c).penetration_depth);
  }
  return depth;
}

/// The world axes: where faces meet at zero depth (a robot's base flush on a table) the contact
/// normals FCL reports can be degenerate, and a short translation along an axis still tells.
bool separatedAlongAnAxis(const PlacedFclShape& a, const PlacedFclShape& b, double tolerance) {
  Directions axes;
  axes.add(Vector3::UnitZ());
  axes.add(Vector3::UnitX());
  axes.add(Vector3::UnitY());
  return separatedAlongAny(a, b, axes, tolerance + kProbeSlack);
}

/// Between two meshes FCL's depth means nothing: probe the first contact's normal and the
/// normals of its two triangles (one more full contact query would cost more than it finds),
/// then the world axes.
bool meshesSeparableWithin(const PlacedFclShape& a, const Mesh& meshA, const PlacedFclShape& b,
                           const Mesh& meshB, const fcl::Contactd& first, double tolerance) {
  Directions directions;
  directions.add(first.normal);
  directions.add(triangleNormal(b, meshB, first.b2));
  directions.add(triangleNormal(a, meshA, first.b1));
  return separatedAlongAny(a, b, directions, tolerance + kProbeSlack) || separatedAlongAnAxis(a, b, tolerance);
}

/// One mesh: every reported depth bounds the true one from below.
bool meshShapeSeparableWithin(const PlacedFclShape& a, const PlacedFclShape& b,
                              const fcl::Contactd& first, double tolerance) {
  if (first.penetration_depth > tolerance) return false;
  Directions directions;
  directions.add(first.normal);
  if (separatedAlongAny(a, b, directions, tolerance + kProbeSlack)) return true;
  const fcl::CollisionResultd all = contactsOf(a, b, kContacts);
  if (deepest(all) > tolerance) return false;
  for (std::size_t c = 0; c < all.numContacts(); ++c) directions.add(all.getContact(c).normal);
  return separatedAlongAny(a, b, directions, tolerance + kProbeSlack) || separatedAlongAnAxis(a, b, tolerance);
}

/// Longest distance any translation needs to separate the two (their bounding spheres apart).
double separationBound(const PlacedFclShape& a, const PlacedFclShape& b) {
  return 2.0 * (a.shape->localHalfExtent.norm() + b.shape->localHalfExtent.norm()) + kDepthResolution;
}

}  // namespace

bool separableWithin(const PlacedFclShape& a, const PlacedFclShape& b, const fcl::Contactd& firstContact,
                     double tolerance) {
  if (!(tolerance > 0.0)) return false;
  const Mesh* meshA = meshOf(a);
  const Mesh* meshB = meshOf(b);
  if (meshA && meshB) return meshesSeparableWithin(a, *meshA, b, *meshB, firstContact, tolerance);
  if (meshA || meshB) return meshShapeSeparableWithin(a, b, firstContact, tolerance);
  return deepest(contactsOf(a, b, kContacts)) <= tolerance;
}

bool separableWithin(const PlacedFclShape& a, const PlacedFclShape& b, double tolerance) {
  const fcl::CollisionResultd result = contactsOf(a, b, 1);
  if (!result.isCollision()) return true;
  if (result.numContacts() == 0) return false;
  return separableWithin(a, b, result.getContact(0), tolerance);
}

double penetrationDepth(const PlacedFclShape& a, const PlacedFclShape& b) {
  const fcl::CollisionResultd result = contactsOf(a, b, kContacts);
  if (!result.isCollision()) return 0.0;
  const Mesh* meshA = meshOf(a);
  const Mesh* meshB = meshOf(b);
  if (!meshA || !meshB) return deepest(result);
  Directions directions;
  for (std::size_t c = 0; c < result.numContacts(); ++c) {
    const fcl::Contactd& contact = result.getContact(c);
    directions.add(contact.normal);
    directions.add(triangleNormal(b, *meshB, contact.b2));
    directions.add(triangleNormal(a, *meshA, contact.b1));
  }
  double best = separationBound(a, b);
  for (const Vector3& n : directions.list()) {
    if (!separatedAlong(a, b, n, best)) continue;
    double inside = 0.0;
    double outside = best;
    while (outside - inside > kDepthResolution) {
      const double middle = 0.5 * (inside + outside);
      (separatedAlong(a, b, n, middle) ? outside : inside) = middle;
    }
    best = outside;
  }
  return best;
}

}  // namespace lang2manip
