#pragma once
/// @file The immutable tables behind FclCollisionChecker: every geometry of the world with the
/// body it belongs to, the allowed-collision matrix of each robot, and the geometry pairs each
/// kind of check visits. Built once from a Scene; read-only afterwards (thread-safe).

#include <memory>
#include <string>
#include <vector>

#include "lang2manip/collision/allowed_collision_matrix.hpp"
#include "lang2manip/collision/fcl_geometry.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// A rigid body: a robot link, an attached object (moves with its link) or a fixed object.
struct FclBody {
  /// "robot/link" or the object's name.
  std::string name;
  /// Robot it moves with (-1 for a fixed object) and the link that carries it.
  int robot = -1;
  int link = -1;
  bool attached = false;
};

/// One geometry of a body. For robot bodies (links and attached objects) `origin` is X_LG in
/// the carrying link; for fixed objects it is X_WG.
struct FclGeometryEntry {
  FclShape shape;
  int body = -1;
};

/// A pair of geometry indices to check.
struct FclGeometryPair {
  int first = -1;
  int second = -1;
  /// The pair may touch without colliding (the scene's contact tolerance applies): `second` is a
  /// fixed object the robot rests on, or both are of one robot (links whose faces meet at zero
  /// or tiny depth, as a vendor's fingers do, touch; the ACM handles what always overlaps).
  /// Robot–robot pairs are strict.
  bool mayRest = false;
};

struct FclWorldTables {
  std::vector<FclBody> bodies;
  std::vector<FclGeometryEntry> geometries;
  /// Geometry indices that move with each robot (its links and attached objects).
  std::vector<std::vector<int>> robotGeometries;
  /// Per robot: self pairs (after the ACM and attachment exclusions), then pairs against every
  /// geometry that does not move with it (objects, other robots at their scene state).
  std::vector<std::vector<FclGeometryPair>> robotPairs;
  /// Every pair checked when all robots move (self, robot-robot, robot-object).
  std::vector<FclGeometryPair> worldPairs;
  /// The allowed-collision matrix of each robot.
  std::vector<std::shared_ptr<const AllowedCollisionMatrix>> allowedCollisions;
  /// Shapes that could not be converted (empty meshes, zero-size primitives).
  int skippedShapes = 0;
};

struct FclCheckerSettings;

/// Builds the tables for `scene`. Throws InputError for an attachment naming an unknown link or
/// precomputed matrices that do not fit the scene's robots.
FclWorldTables buildFclWorld(const Scene& scene, const FclCheckerSettings& settings);

}  // namespace lang2manip
