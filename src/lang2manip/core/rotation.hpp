#pragma once
/// @file Orientation conversions. lang2manip's own API uses quaternions; the readers convert the
/// conventions of the files they read (URDF roll-pitch-yaw, Kautham axis-angle, MoveIt xyzw).

#include <optional>
#include <vector>

#include "lang2manip/core/types.hpp"

namespace lang2manip {

/// URDF convention: R = Rz(yaw) * Ry(pitch) * Rx(roll).
Quaternion quaternionFromRpy(double roll, double pitch, double yaw);

/// Roll, pitch, yaw of `q` in the URDF convention (inverse of quaternionFromRpy).
Vector3 rpyFromQuaternion(const Quaternion& q);

/// Kautham's Home convention (SE3Conf::fromAxisToQuaternion): q = (cos(angle/2), axis *
/// sin(angle/2)) normalized as a quaternion. The axis is NOT normalized first, so for a non-unit
/// axis the rotation angle differs from `angle`; for a unit axis it is the usual axis-angle
/// rotation. An all-zero axis means the identity whatever the angle (Kautham's UR5 demo).
Quaternion quaternionFromKauthamAxisAngle(const Vector3& axis, double angle);

/// Axis (unit, or +z for the identity) and angle in [0, pi] of `q`.
void axisAngleFromQuaternion(const Quaternion& q, Vector3& axis, double& angle);

/// The unit quaternion of (w, x, y, z) as a direction, computed without overflow or underflow (a
/// quaternion of 1e300 components is that rotation, not a zero one); nullopt when a component is
/// not finite or all are zero, which no rotation is.
std::optional<Quaternion> unitQuaternion(double w, double x, double y, double z);

/// A pose from a translation and a rotation.
Pose makePose(const Vector3& translation, const Quaternion& rotation);

/// Kautham's uniform-quaternion map from (X1, X2, X3) in [0,1]^3 to a rotation
/// (X1 = X2 = X3 = 0 is the identity; with X1 = X2 = 0, X3 is a yaw of 2*pi*X3).
Quaternion quaternionFromKauthamUnitCube(double x1, double x2, double x3);

/// A pose from Kautham's seven numbers: x y z, then an axis (ax ay az) and an angle in radians.
/// Throws InputError unless there are seven finite values, and for the zero axis with a non-zero
/// angle (a problem file's <Home> takes that as no rotation, as Kautham does, with a warning).
Pose kauthamPose(const std::vector<double>& values);

}  // namespace lang2manip
