#pragma once
/// @file Geometric queries on scene objects shared by grasp and placement planning: extents along
/// a direction from the object's shape, bounds at a hypothetical pose, resting orientations and
/// the support under a point.

#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// Half the object's extent along the world direction `direction` (unit) with the object at
/// `X_WO`, measured from objectCentre(). Exact for an object made of one box, sphere or
/// cylinder; other objects (several shapes, meshes) use their local bounding box.
double halfExtentAlong(const SceneObject& object, const Pose& X_WO, const Vector3& direction);

/// The centre of the object's local bounding box, in the world, with the object at `X_WO`.
Vector3 objectCentre(const SceneObject& object, const Pose& X_WO);

/// World axis-aligned bounds of the object's collision geometry with the object at `X_WO`.
AlignedBox3 boundsAtPose(const SceneObject& object, const Pose& X_WO);

/// Bounds of `box` (in frame F) in frame W, for X_WF = `X`.
AlignedBox3 transformedBox(const AlignedBox3& box, const Pose& X);

/// World orientations an object can rest in: first `current` turned about the world z axis by
/// 0, 90, 180 and 270 degrees, then each other object axis (+-x, +-y, -z of `current`) turned to
/// point up, each with the same four yaws. No duplicates.
std::vector<Quaternion> restingOrientations(const Quaternion& current);

/// The object that a body standing at world point `point` (its bottom centre) would rest on:
/// the one, other than those in `exclude` and held ones, whose surface under the point is
/// highest among those within `tolerance` of point.z() (restingHeight(): its top, or a surface
/// inside its bounds such as a counter under cabinets). nullptr when there is none.
const SceneObject* supportUnder(const Scene& scene, const Vector3& point, double tolerance,
                                const std::vector<std::string>& exclude);

/// The object a body of world bounds `bounds` rests on: supportUnder() its bottom centre, else
/// the one of the objects it bridges (see bridgedSupport(), the top of a pyramid), other than
/// those in `exclude` and held ones. nullptr when there is none.
const SceneObject* supportUnderBody(const Scene& scene, const AlignedBox3& bounds, double tolerance,
                                    const std::vector<std::string>& exclude);

/// The object `object` currently rests on (see supportUnderBody()), from its world bounds.
const SceneObject* currentSupport(const Scene& scene, const SceneObject& object, double tolerance);

/// The height (world z) of `support`'s surface under `bottom` (a body's bottom centre): its
/// restingHeight() within `tolerance`, else the top of its bounds (a body bridging two supports,
/// or one about to be set down on it).
double surfaceUnder(const SceneObject& support, const Vector3& bottom, double tolerance);

/// How far an object's bottom may be from its support's top (m) for it to rest there.
inline constexpr double kSupportTolerance = 0.015;

/// Throws InputError "<settings> settings: <field> must be a finite length >= 0 (got ...)".
void requireSettingLength(double value, const char* settings, const char* field);

/// Throws InputError "<settings> settings: <field> must be >= 1 (got ...)".
void requireSettingCount(int value, const char* settings, const char* field);

/// The pose of object `name` in the world, following its attachment when it is held.
Pose currentObjectPose(const Scene& scene, const std::string& name);

}  // namespace lang2manip
