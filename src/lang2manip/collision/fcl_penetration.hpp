#pragma once
/// @file How deeply two overlapping FCL geometries penetrate: the contact-tolerance test of
/// the checkers (may a short translation separate them?) and a depth estimate for reports.
/// FCL's own depth is exact for primitive pairs and a lower bound when one side is a mesh (a
/// per-triangle depth), but between two meshes it depends on the triangles' winding (an
/// inward-wound box resting 2 mm deep reads 0.3 m), so mesh pairs are probed by translation.

#include <fcl/narrowphase/contact.h>

#include "lang2manip/collision/fcl_geometry.hpp"

namespace lang2manip {

/// One geometry placed in the world.
struct PlacedFclShape {
  const FclShape* shape = nullptr;
  /// X_WG.
  const Pose* pose = nullptr;
};

/// True when `a` and `b`, which FCL found overlapping with `firstContact` (asked with
/// enable_contact), can be separated by translating `a` by at most `tolerance` metres along
/// a direction the contacts suggest (contact normals and, between meshes, the normals of the
/// touching triangles; both ways): they rest on each other rather than collide. False when
/// `tolerance` is 0 or a reported depth that bounds the true one from below exceeds it.
/// Conservative: a separating translation the contacts do not suggest is not found.
[[nodiscard]] bool separableWithin(const PlacedFclShape& a, const PlacedFclShape& b,
                                   const fcl::Contactd& firstContact, double tolerance);

/// The same when the caller has no contact at hand (asks FCL for one first; true when they do
/// not overlap at all).
[[nodiscard]] bool separableWithin(const PlacedFclShape& a, const PlacedFclShape& b, double tolerance);

/// The penetration depth of `a` and `b` (m; 0 when they do not overlap): FCL's depth for
/// primitive pairs and its lower bound for mesh–primitive pairs; for two meshes, the shortest
/// translation along the contact normals that separates them (bisected to 0.1 mm; the size of
/// both geometries together when no contact normal separates them).
[[nodiscard]] double penetrationDepth(const PlacedFclShape& a, const PlacedFclShape& b);

}  // namespace lang2manip
