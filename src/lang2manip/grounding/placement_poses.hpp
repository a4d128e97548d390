#pragma once
/// @file Candidate object poses for each placement relation, from geometry alone (before
/// collision and reachability checks), in order of preference.

#include <string>
#include <vector>

#include "lang2manip/grounding/placement.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {

struct PoseCandidate {
  /// X_WO, the object released releaseGap above its support.
  Pose pose = Pose::Identity();
  std::string support;
  std::string label;
};

struct PoseSampling {
  std::vector<PoseCandidate> poses;
  /// When `poses` is empty: why (kBadTarget, kTooLarge, kNoSupport).
  PlacementFailure failure = PlacementFailure::kNone;
  std::string reason;
};

/// What the samplers need about the world.
struct PoseSamplingInput {
  const Scene* scene = nullptr;
  const SceneObject* object = nullptr;
  /// The object's current world orientation (its resting orientations derive from it).
  Quaternion orientation = Quaternion::Identity();
  /// Its current world position (surface samples near it come first) and the robot base X_WB.
  Vector3 position = Vector3::Zero();
  Pose robotBase = Pose::Identity();
  /// The robot placing it: regions are of the part of a top it reaches.
  std::string robot{};
  /// Its arm (every arm when empty).
  std::string arm{};
  /// In a container: positions that leave the most room for more objects like it come first
  /// (nothing is known of what follows); false keeps the middle first (what follows is known and
  /// the planner leaves room for it).
  bool packForMore = true;
};

/// Candidate poses for `target`:
/// - in: the container's cavity (its role must be container); every resting orientation whose
///   footprint fits the cavity and whose centre stays below the rim, on a grid of positions on
///   the cavity floor, the centre first;
/// - on: the top of the target, seeded random positions within its footprint (nearest to the
///   object's current position first), in the object's current orientation and its yaws; with a
///   region, positions within it (regionCentres(), base frame), nearest to the region's outer
///   point first (a corner's corner, an edge's midpoint, the centre);
/// - left_of / right_of / in_front_of / behind: beside the target along that robot-base axis,
///   at the given centre offset or with sideGap between the boxes, shifted sideways by
///   lateralShifts (none with a distance: it is the whole offset), on the target's support;
/// - next_to: all four sides with the given or the nextToGap gap;
/// - explicit position: that pose, set onto the support under it.
PoseSampling samplePlacementPoses(const PoseSamplingInput& input, const PlacementTarget& target,
                                  const PlacementSettings& settings);

}  // namespace lang2manip
