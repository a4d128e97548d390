#pragma once
/// @file Which way an object points and which turns leave it looking the same: the yaw of its
/// long horizontal side, the symmetry of its collision shapes about the vertical, and the turn
/// between two orientations. Shared by the offline planner (turning, pointing an object at
/// another), plan validation (refusing a turn that changes nothing) and the goal checker.

#include <optional>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// A turn of this size (rad) or less counts as "the same orientation" in goal checks: 10 deg.
inline constexpr double kTurnTolerance = 0.1745;

/// The yaw about the world vertical (world frame, in [0, pi)) of the longest horizontal edge of
/// `object`'s bounding box in its own frame, with the object at orientation `rotation`; nullopt
/// when no box axis lies within 10 deg of horizontal or its two horizontal sides are within
/// 15 % of each other (a square or round footprint has no long side to point with).
std::optional<double> longSideYaw(const SceneObject& object, const Matrix3& rotation);

/// The smallest turn about the vertical (through the centre of its collision bounds) that maps
/// `object`'s collision shapes at its current orientation onto themselves: 0 when every turn
/// does (a standing cylinder, a sphere), pi/2 or pi, and 2 pi when none is known. Boxes,
/// cylinders and spheres are compared shape by shape; a mesh matches nothing, so an object with
/// one is never called symmetric.
double turnSymmetry(const SceneObject& object);

/// `angle` reduced modulo `period` into (-period/2, period/2]; 0 when period is 0 (every angle is
/// equivalent). A period of 2 pi wraps the angle into (-pi, pi].
double reducedAngle(double angle, double period);

/// The rotation from `from` to `to` (both world orientations) split into its yaw about the world
/// vertical (rad, counter-clockwise seen from above) and what is left, a tilt (rad).
struct TurnBetween {
  double yaw = 0.0;
  double tilt = 0.0;
};
TurnBetween turnBetween(const Matrix3& from, const Matrix3& to);

/// The rotation by `yaw` about the vertical axis.
Matrix3 verticalTurn(double yaw);

/// "90 deg" for pi/2 (whole degrees).
std::string degreesText(double radians);

}  // namespace lang2manip
