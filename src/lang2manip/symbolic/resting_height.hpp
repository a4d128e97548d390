#pragma once
/// @file Where a body rests: the height of the surface a support offers under a point, from the
/// support's bounds when its top is there, else from its collision geometry (a counter inside a
/// kitchen mesh whose bounds reach the cabinets above it, a shelf inside a bookcase).

#include <optional>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// The height (world z) of the surface of `support` under `bottom` (a body's bottom centre, world
/// frame) within `tolerance` of bottom.z(), or nullopt when it offers none there:
/// - the top of its world bounds when they contain bottom's x, y and that top is within tolerance;
/// - otherwise, when its bounds contain bottom's x, y and reach higher (the support has parts
///   above the body, such as the cabinets over a counter), the highest point of its collision
///   geometry in a 1 cm column about bottom's x, y between bottom.z() - tolerance and
///   bottom.z() + tolerance, when it has none at the window's top (the body is not inside it). A
///   container's cavity is no surface (what stands there is in it).
std::optional<double> restingHeight(const SceneObject& support, const Vector3& bottom, double tolerance);

}  // namespace lang2manip
