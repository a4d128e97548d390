#pragma once
/// @file What executing a symbolic plan takes (settings) and gives (per action a status, a reason,
/// the motions and the trajectory; the final world; timings and counters).

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lang2manip/grounding/grasp_planner.hpp"
#include "lang2manip/grounding/placement.hpp"
#include "lang2manip/grounding/reachability.hpp"
#include "lang2manip/model/scene.hpp"
#include "lang2manip/planning/motion_planner.hpp"
#include "lang2manip/planning/trajectory.hpp"
#include "lang2manip/symbolic/action.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip {

/// Tuning of plan execution (lengths in metres, angles in radians, times in seconds).
struct ExecutionSettings {
  /// The robot and arm that execute the plan; empty = the scene's first robot, its first arm.
  std::string robot;
  std::string manipulator;
  /// Motion planner of actions that name none (any registered name or alias).
  std::string defaultPlanner = "RRTConnect";
  /// Grasp planner (registry name) and IK solver (registry name).
  std::string graspPlanner = "heuristic";
  std::string ikSolver = "dls";
  /// Time limit of one motion query.
  double planningTimeSeconds = 5.0;
  /// Grasp candidates and placement candidates tried in motion planning, best first.
  int maxGraspAttempts = 4;
  int maxPlacementAttempts = 3;
  /// Cartesian segments: largest tool step between IK solutions, largest tool rotation per
  /// step, and the largest joint change per step (a larger one is a discontinuity).
  double cartesianStep = 0.01;
  double cartesianAngleStep = 0.05;
  double maxJointStep = 0.3;
  /// Joint step at which every motion is re-verified (rad or m).
  double verificationResolution = 0.002;
  /// Push: the tool comes down onto the contact pose from this high, stands this far from the
  /// object's face, and rises this far after the push.
  double pushApproachHeight = 0.08;
  double pushStandoff = 0.01;
  double pushRetreat = 0.08;
  /// Fraction of the velocity and acceleration limits the trajectories use.
  double speedScale = 0.5;
  /// Seed of the planners, IK restarts and placement samples.
  std::uint64_t seed = 1;
  /// Keep each transit planner's exploration graph (at most this many edges per query; 0: none).
  std::size_t recordTreeEdges = 0;
  GraspSettings grasp;
  PlacementSettings placement;
  /// IK for grasps, placements and goal poses: more solutions than the grounding modules'
  /// default, so that arms with many IK branches (UR5) find a collision-free one.
  ReachSettings reach = {0.005, 3, 1};
};

/// Throws InputError naming the field for a non-positive time or step, counts < 1, or a speed
/// scale outside (0, 1]; the grasp and placement settings are checked by their modules.
void checkExecutionSettings(const ExecutionSettings& settings);

/// What the gripper does to an object at the end of a motion (a moment worth showing).
enum class GripperEvent { kNone, kGrasp, kRelease };

/// One motion of the robot, replayable for verification: the robot's full configurations along
/// it (straight joint-space segments between them), and the world it moves in.
struct MotionSegment {
  /// "transit to pre-grasp", "approach", "close gripper", "lift", "push", ...
  std::string label;
  std::vector<VectorX> waypoints;
  /// The world during the motion (objects, attachments); the robot's own configuration in it is
  /// irrelevant.
  Scene world;
  /// Body pairs that may touch during this motion (names as in CollisionContact): the finger
  /// links and the object grasped or released, a lifted object and the support it leaves.
  std::vector<std::pair<std::string, std::string>> allowedContacts;
  /// Push: the object carried with the contact. It is left out of the robot's check and its own
  /// sweep from `carriedStart` by `carriedDisplacement` is checked against the other objects.
  std::string carried;
  Pose carriedStart = Pose::Identity();
  Vector3 carriedDisplacement = Vector3::Zero();
  /// Motion planner that produced it (empty for Cartesian and gripper motions).
  std::string planner;
  /// A gripper motion that closes on an object (kGrasp) or lets it go (kRelease).
  GripperEvent gripperEvent = GripperEvent::kNone;
  /// The planner's exploration graph when recorded (ExecutionSettings::recordTreeEdges), its
  /// vertices as full robot configurations.
  ExplorationTree tree;
};

/// Work counters, summed over actions and attempts.
struct ExecutionCounters {
  /// Motion planner queries, and those that found a verified path.
  int plannerCalls = 0;
  int plannerSolved = 0;
  int ikCalls = 0;
  long collisionChecks = 0;
  int graspPlans = 0;
  int placementPlans = 0;

  ExecutionCounters& operator+=(const ExecutionCounters& other);
};

/// Seconds per stage.
struct StageTimes {
  double grasp = 0.0;
  double placement = 0.0;
  double ik = 0.0;
  double motion = 0.0;

  StageTimes& operator+=(const StageTimes& other);
};

enum class ActionStatus { kSucceeded, kFailed, kNotRun };

/// "succeeded", "failed", "not run".
std::string actionStatusName(ActionStatus status);

struct ActionExecution {
  std::size_t index = 0;
  SymbolicAction action;
  ActionStatus status = ActionStatus::kNotRun;
  /// On failure: the stage ("grasp", "placement", "ik", "motion", "push", "precondition") and
  /// why, naming the object.
  std::string stage;
  std::string reason;
  /// What was chosen: "top, closing 90 deg ...", "in holder at ...", "home".
  std::string choice;
  std::vector<MotionSegment> segments;
  /// The action's motion, time from the start of the action (empty unless it succeeded).
  JointTrajectory trajectory;
  /// When each of `segments` ends in `trajectory` (seconds from the start of the action): which
  /// world (attachments) holds at each moment of the motion.
  std::vector<double> segmentEndTimes;
  StageTimes times;
};

/// The outcome of one execution of a plan.
struct ExecutionRecord {
  /// One entry per action of the plan, in order; those after a failure are kNotRun.
  std::vector<ActionExecution> actions;
  /// The world after the last action that succeeded.
  Scene finalScene;
  std::optional<GroundingFailure> failure;
  StageTimes times;
  ExecutionCounters counters;

  [[nodiscard]] bool succeeded() const noexcept { return !failure.has_value(); }
};

}  // namespace lang2manip
