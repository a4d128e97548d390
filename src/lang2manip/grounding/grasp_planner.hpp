#pragma once
/// @file Grasp planning behind one interface (the paper's plugin point) and a registry of
/// planners by name. A grasp planner turns "grasp object o from direction d" into ranked grasp
/// candidates, each with its tool poses (pre-grasp, grasp, post-grasp lift), the gripper opening
/// and collision-free IK solutions, or a failure that names the object and the reason.
///
/// Frames: X_WG is the tool frame (TCP, see GripperGeometry) in the world; X_OG the tool frame in
/// the object frame, constant while the object is held: after the pick, the object's pose is
/// X_WO = X_WG * X_OG^-1, and placing it at X_WO_target needs X_WG = X_WO_target * X_OG.
///
/// Intended use by action grounding (pick): plan(), then for the first candidate whose motion
/// planning succeeds: move to preGraspPose (preGraspSolutions), Cartesian approach to graspPose
/// (graspSolutions; the gripper open at `opening`), close to gripperClosedWidth, attach the
/// object to the tool frame with linkToObject = X_OG^-1, Cartesian lift to postGraspPose.

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>
#include <cmath>

#include "lang2manip/core/types.hpp"
#include "lang2manip/grounding/reachability.hpp"
#include "lang2manip/symbolic/action.hpp"

namespace lang2manip {

/// Tuning of grasp planning (all lengths in metres).
struct GraspSettings {
  /// Pre-grasp: the TCP retreated from the grasp pose by this along the approach axis.
  double approachDistance = 0.10;
  /// Post-grasp: the TCP lifted by this along the world +z after closing.
  double liftDistance = 0.10;
  /// Free space wanted on each side of the object when the gripper opens for it.
  double openingMargin = 0.01;
  /// Clearance kept between the fingers and the object's support, and between the object and
  /// the part of the gripper behind the fingers.
  double supportClearance = 0.001;
  /// The fingertips must reach at least this far below the object's top (the fingers must hold
  /// something; the TCP may stay above the top when the fingers reach beyond it).
  double minimumEngagement = 0.002;
  /// Closing directions tried around a top approach (evenly spaced over a full turn).
  int topYawSteps = 8;
  /// Approaches within this angle of the robot's +x (front) or +-y (side) axes, radians.
  double sectorHalfAngle = M_PI / 4.0;
  /// Front and side approaches are tilted down from the horizontal by each of these angles
  /// (radians; 0 = level), so that low objects can be taken from the side.
  std::vector<double> approachPitches = {0.0, M_PI / 6.0, M_PI / 3.0};
  /// When no grasp of the first search is collision-free and reachable, a widened search: top
  /// approaches tilted by each of these angles (radians) both ways about the closing axis and
  /// about the object's axis between the fingers, at twice the closing directions.
  std::vector<double> widenedTopTilts = {M_PI / 9.0, 2.0 * M_PI / 9.0};
  /// Best candidates kept and fully checked (IK for grasp and pre-grasp, clearance).
  int maxCandidates = 6;
  /// Stop after this many reachability checks (bounds the time spent on unreachable objects).
  int maxReachChecks = 60;
};

/// Why grasp planning failed.
enum class GraspFailure { kNone, kNotGraspable, kTooWide, kNoCandidate, kUnreachable, kInCollision };

/// "none", "not graspable", "too wide", "no candidate", "unreachable", "in collision".
std::string graspFailureName(GraspFailure failure);

/// One grasp, ready for motion planning.
struct GraspCandidate {
  std::string object;
  /// top, side or front (never auto).
  GraspDirection direction = GraspDirection::kTop;
  /// Human-readable: "top, closing 90 deg, at +0.045 m along the object".
  std::string label;
  /// X_WG at the grasp, before the approach (pre-grasp) and after the lift (post-grasp).
  Pose graspPose = Pose::Identity();
  Pose preGraspPose = Pose::Identity();
  Pose postGraspPose = Pose::Identity();
  /// X_OG: the tool frame in the object frame (constant while the object is held).
  Pose objectToGripper = Pose::Identity();
  /// Unit approach direction in the world (the TCP moves along it into the object).
  Vector3 approachDirection = Vector3::UnitZ();
  /// The object's width between the fingers, and the gripper gap used to approach it.
  double objectWidth = 0.0;
  double opening = 0.0;
  /// Collision-free full configurations (gripper at `opening`) at the grasp and pre-grasp
  /// poses, and IK solutions at the post-grasp pose (empty when none was found).
  std::vector<VectorX> graspSolutions;
  std::vector<VectorX> preGraspSolutions;
  std::vector<VectorX> postGraspSolutions;
  /// Smallest distance from the robot at graspSolutions[0] to the world other than the object.
  double clearance = 0.0;
  /// Higher is better; candidates come sorted by it.
  double score = 0.0;
};

/// A candidate that was dropped, and why.
struct GraspRejection {
  std::string label;
  GraspFailure failure = GraspFailure::kNone;
  std::string reason;
};

/// The result of GraspPlanner::plan().
struct GraspPlan {
  /// Ranked, best first; empty on failure.
  std::vector<GraspCandidate> candidates;
  GraspFailure failure = GraspFailure::kNone;
  /// On failure: names the object and says why ("marker: no top grasp is reachable: ...").
  std::string reason;
  /// Every candidate dropped on the way, in the order it was considered.
  std::vector<GraspRejection> rejections;
  /// The largest tilt of the widened search (radians) when it ran; 0 when the first search found
  /// candidates.
  double widenedTilt = 0.0;
  [[nodiscard]] bool success() const { return !candidates.empty(); }
};

/// A grasp query: the world, robot and IK come with the ReachabilityChecker.
struct GraspRequest {
  std::string object;
  GraspDirection direction = GraspDirection::kAuto;
  /// Start of the IK searches (full configuration); empty = the robot's current configuration.
  VectorX seed;
  GraspSettings settings;
};

/// The interface. Implementations are stateless between calls.
class GraspPlanner {
 public:
  virtual ~GraspPlanner() = default;
  /// The registry name.
  [[nodiscard]] virtual std::string name() const = 0;
  /// Plans grasps of `request.object` in `reach`'s world for its robot. Throws InputError for an
  /// unknown object (listing the objects) or invalid settings; every geometric or kinematic
  /// failure comes back in the GraspPlan.
  [[nodiscard]] virtual GraspPlan plan(const ReachabilityChecker& reach, const GraspRequest& request) const = 0;
};

/// An entry of the grasp planner registry.
struct GraspPlannerEntry {
  std::string_view name;
  std::string_view description;
  std::unique_ptr<GraspPlanner> (*make)();
};

/// Every registered grasp planner, the default first.
std::span<const GraspPlannerEntry> graspPlannerRegistry();
/// Their names, the default first.
std::vector<std::string> graspPlannerNames();
/// "heuristic".
std::string defaultGraspPlannerName();
/// A planner by name; throws InputError listing the names when unknown.
std::unique_ptr<GraspPlanner> makeGraspPlanner(const std::string& name);

/// Throws InputError naming the field unless every length is finite and >= 0 and the counts
/// are positive.
void checkGraspSettings(const GraspSettings& settings);

}  // namespace lang2manip
