#pragma once
/// @file Geometric spatial relations in the robot's base frame (x front, y left, z up), shared
/// by the observation text and the geometric goal check so that both say the same; and the
/// check of goals against a Scene.

#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/symbolic/action.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"

namespace lang2manip {

class Scene;

/// Thresholds of the geometric relations.
struct SpatialOptions {
  /// An offset along an axis counts as left/right/front/behind beyond this, metres.
  double directionMargin = 0.02;
  /// Objects whose bounding boxes are closer than this are "near" (and "next_to"), metres.
  double nearDistance = 0.10;
  /// How far an explicit distance or displacement may be off, metres.
  double distanceTolerance = 0.02;
  /// The gap between two objects' boxes meant by "a little" and "a lot" before a side relation
  /// ("a little to the left of the bowl"), metres.
  double littleGap = 0.04;
  double lotGap = 0.18;
};

/// The spatial conventions in words, with the numbers of `spatial` and `tolerances`: which way
/// front and left are, what each relation means in metres, which way a turn goes and how close
/// a goal must be met. Stated in the observation and the system prompt; the offline planner, the
/// plan validator and the goal checker use the same options.
std::string spatialConventions(const SpatialOptions& spatial = {}, const SymbolicStateTolerances& tolerances = {});

/// X_WB of `robot` (the scene's first robot when empty; identity for a scene without robots).
/// Throws InputError for an unknown robot name.
Pose robotBaseFrame(const Scene& scene, const std::string& robot);

/// The smallest distance between two boxes (0 when they overlap).
double boxGap(const AlignedBox3& a, const AlignedBox3& b);

/// left_of / right_of / in_front_of / behind for `offset` = position of A minus position of B
/// in the base frame: A is left_of B when offset.y > margin, in_front_of when offset.x > margin.
std::vector<SpatialRelation> directionalRelations(const Vector3& offset, double margin);

/// Options of checkGoalInScene().
struct GoalCheckOptions {
  /// The robot whose base frame and gripper are meant (first robot when empty).
  std::string robot;
  /// Its arm that acted: regions are of the part of a top it reaches (every arm when empty).
  std::string arm;
  /// The scene before execution; needed for displacement goals.
  const Scene* initialScene = nullptr;
  SpatialOptions spatial;
  SymbolicStateTolerances tolerances;
};

struct GoalCheck {
  bool holds = false;
  /// Why, in words: "marker is 0.120 m left of eraser", "eraser is not in holder (on desk)".
  std::string explanation;
};

/// Whether `goal` holds in `scene`: in/on/holding/at-configuration from observeSymbolicState();
/// side relations from the bounding-box centres in the robot base frame (with an explicit
/// distance, the whole offset: along that side it matches the distance and across it is 0, each
/// within distanceTolerance); next_to when the boxes
/// are within nearDistance (or the explicit distance); displaced by comparing with
/// options.initialScene; at_position when the object frame's origin is within distanceTolerance
/// of the position (x, y in the base frame); turned when the turn about the vertical from
/// options.initialScene matches up to the object's symmetry (turnSymmetry()) within
/// kTurnTolerance, without tilt, the origin staying within distanceTolerance; facing when the
/// long side's line points at the target's centre within kTurnTolerance; on with a region when the
/// object's centre is also within that region of the target's reachable top (surface_region.hpp),
/// up to half distanceTolerance; arranged as checkArranged() measures it. Throws InputError for
/// unknown objects, or a displacement or turn goal without an initial scene.
GoalCheck checkGoalInScene(const Scene& scene, const Goal& goal, const GoalCheckOptions& options = {});

}  // namespace lang2manip
