#pragma once
/// @file Placement: where to put an object for each relation of the plan grammar (in, on,
/// left_of, right_of, in_front_of, behind, next_to) or at an explicit pose, as candidate object
/// poses that are collision-free against the other objects, resting on a support and reachable
/// by the robot holding the object (IK for X_WG = X_WO_target * X_OG, the robot and the held
/// object collision-free).
///
/// Intended use by action grounding (place): plan() with the grasp the object is held by (or,
/// before picking, every grasp candidate's objectToGripper, to choose a pick that allows the
/// place); then for the first candidate whose motion planning succeeds: transport to
/// prePlacePose (prePlaceSolutions), Cartesian descent to placePose (placeSolutions), open the
/// gripper to releaseOpening, detach the object at objectPose, Cartesian retreat to retreatPose.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/grounding/reachability.hpp"
#include "lang2manip/symbolic/action.hpp"

namespace lang2manip {

/// Tuning of placement (lengths in metres).
struct PlacementSettings {
  /// The object is released this far above its support (or the cavity floor).
  double releaseGap = 0.003;
  /// Gap between the bounding boxes for left_of / right_of / in_front_of / behind without an
  /// explicit distance, and for next_to without one.
  double sideGap = 0.05;
  double nextToGap = 0.03;
  /// Clearance kept from a container's walls and from a surface's edges.
  double wallMargin = 0.002;
  double edgeMargin = 0.02;
  /// Positions per axis on the grid inside a cavity.
  int cavityGrid = 3;
  /// Random positions tried on a surface (seeded; nearest to the object's current place first).
  int surfaceSamples = 30;
  /// Shifts across the direction of a side relation (left_of, ...), tried in this order.
  std::vector<double> lateralShifts = {0.0, 0.04, -0.04, 0.08, -0.08};
  /// Inside a container the object may be released above its resting pose and drop straight
  /// down onto the cavity floor: release heights above the resting pose tried in order.
  std::vector<double> dropHeights = {0.0, 0.03, 0.06, 0.09};
  /// Last, the object is released with its bottom this far above the container's rim (the
  /// hand then stays out of the opening); the heights above that are not tried.
  double rimClearance = 0.01;
  /// Pre-place: the object held this far above its target pose.
  double approachHeight = 0.10;
  /// After release, the tool frame retreats this far back along the approach axis.
  double retreatDistance = 0.10;
  /// An explicit pose within this height of a support's top is set onto it.
  double supportTolerance = 0.015;
  /// Extra opening beyond the object's width when releasing it.
  double releaseMargin = 0.01;
  /// Stop once this many reachable candidates are found, or after this many reach checks.
  int maxCandidates = 3;
  int maxReachChecks = 40;
  /// Seed of the surface samples.
  std::uint64_t seed = 1;
};

/// Where to place: a relation to a target object, or an explicit pose.
struct PlacementTarget {
  std::optional<SpatialRelation> relation;
  std::string target;
  /// For left_of / right_of / in_front_of / behind: the centre-to-centre offset along that side;
  /// for next_to: the gap between the bounding boxes (as the goal check measures them).
  std::optional<double> distance;
  /// Explicit position of the object's frame in the robot base frame, and optionally its
  /// orientation (base frame; default: the object's current world orientation, then the same
  /// turned about the vertical by 90, 180 and 270 degrees).
  std::optional<Vector3> position;
  std::optional<Quaternion> orientation;
  /// For on: the region of the target's reachable top the object's centre goes in.
  std::optional<SurfaceRegion> region{};
};

/// The target of a place action's parameters (relation + target + distance, or position +
/// orientation).
PlacementTarget placementTargetFromParams(const ActionParams& params);

/// "in holder", "left_of eraser (0.100 m)", "at (0.4, 0.1, 0.0)".
std::string describePlacementTarget(const PlacementTarget& target);

enum class PlacementFailure { kNone, kBadTarget, kTooLarge, kNoSupport, kBlocked, kUnreachable };

/// "none", "bad target", "too large", "no support", "blocked", "unreachable".
std::string placementFailureName(PlacementFailure failure);

struct PlacementRequest {
  std::string object;
  PlacementTarget target;
  /// Candidate grasps X_OG of the object; empty = the grasp it is held by in the scene.
  std::vector<Pose> grasps;
  /// Start of the IK searches; empty = the robot's current configuration.
  VectorX seed;
  /// Objects the plan puts at the same target after this one (several objects into one
  /// container): candidates that leave each of them a free position there come first.
  std::vector<std::string> placedAfter;
  PlacementSettings settings;
};

struct PlacementCandidate {
  std::string object;
  /// What the object rests on (the container for "in").
  std::string support;
  std::string label;
  /// X_WO: where the object is released (releaseGap above its support, dropHeight not counted),
  /// and where it comes to rest after the release: on its support, straight below.
  Pose objectPose = Pose::Identity();
  Pose restingPose = Pose::Identity();
  /// Index into the request's grasps (0 for the held grasp) and that grasp X_OG.
  std::size_t graspIndex = 0;
  Pose objectToGripper = Pose::Identity();
  /// How far above objectPose the object is released (> 0 only inside a container: it drops).
  double dropHeight = 0.0;
  /// Tool poses X_WG: release, before the descent (object approachHeight above), after the
  /// retreat.
  Pose placePose = Pose::Identity();
  Pose prePlacePose = Pose::Identity();
  Pose retreatPose = Pose::Identity();
  /// Gripper gap holding the object, and when releasing it.
  double heldWidth = 0.0;
  double releaseOpening = 0.0;
  /// Collision-free configurations (robot holding the object) at placePose (gripper opened to
  /// releaseOpening) and prePlacePose (gripper at heldWidth).
  std::vector<VectorX> placeSolutions;
  std::vector<VectorX> prePlaceSolutions;
  /// Higher is better (earlier in the preference order of the relation, more IK solutions).
  double score = 0.0;
};

struct PlacementRejection {
  std::string label;
  PlacementFailure failure = PlacementFailure::kNone;
  std::string reason;
  /// The objects standing where the pose would put the object (kBlocked).
  std::vector<std::string> blockers;
};

struct PlacementPlan {
  std::vector<PlacementCandidate> candidates;
  PlacementFailure failure = PlacementFailure::kNone;
  /// On failure, names the object, the target and the reason.
  std::string reason;
  /// On a kBlocked failure (no pose free of other objects): every object that blocked one, in
  /// the order first met.
  std::vector<std::string> blockers;
  std::vector<PlacementRejection> rejections;
  [[nodiscard]] bool success() const { return !candidates.empty(); }
};

/// Throws InputError naming the field for non-finite or negative lengths and counts < 1.
void checkPlacementSettings(const PlacementSettings& settings);

/// Plans placements of `request.object` in `reach`'s world for its robot (see the file
/// comment). Throws InputError for an unknown object or target (listing the objects), an object
/// that is neither held nor given grasps, and invalid settings; every geometric or kinematic
/// failure comes back in the PlacementPlan.
PlacementPlan planPlacement(const ReachabilityChecker& reach, const PlacementRequest& request);

}  // namespace lang2manip
