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

/// How the motions of an action are timed.
enum class TrajectoryTiming {
  /// One time-optimal trajectory per run of arm motions (transits and Cartesian moves joined,
  /// corners blended): stops only where the gripper acts, a push starts or ends, or a corner
  /// cannot be blended.
  kTimeOptimal,
  /// A trapezoid from rest to rest between every two waypoints (the older, slower timing).
  kRestToRest,
};

/// "time-optimal", "rest-to-rest".
std::string trajectoryTimingName(TrajectoryTiming timing);
/// The timing named `name`; throws InputError listing the names otherwise.
TrajectoryTiming trajectoryTimingNamed(const std::string& name);

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
  /// How each action's motions become a trajectory (see motion_timing.hpp).
  TrajectoryTiming timing = TrajectoryTiming::kTimeOptimal;
  /// Fractions of every joint's velocity and acceleration limits the trajectories use, in (0, 1]
  /// (MoveIt's velocity and acceleration scaling factors).
  double velocityScaling = 1.0;
  double accelerationScaling = 1.0;
  /// How far planned transits keep from the arm's position limits (see PositionMargin).
  PositionMargin positionMargin;
  /// Time-optimal timing: the largest distance (rad, Euclidean in joint space) between a corner
  /// of a motion and the arc that replaces it. Arcs that would collide, or take the tool further
  /// than cartesianDeviation (m) from a Cartesian move's straight line, are made smaller, down to
  /// a stop at that corner. Where a transit joins a Cartesian move, the tool may leave the line
  /// within one cartesianStep of the junction (a blend zone).
  double blendDeviation = 0.1;
  double cartesianDeviation = 0.001;
  /// Time-optimal timing: jerk-limit every run of a robot whose model gives jerk limits
  /// (joint_limits.yaml max_jerk), see planning/jerk_limiting.hpp.
  bool limitJerk = true;
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
  /// Transit: the planner's path length and the length after simplification (joint space,
  /// Euclidean; 0 for other motions).
  double plannedLength = 0.0;
  double simplifiedLength = 0.0;
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

/// Consecutive segments of an action timed as one motion from rest to rest (motion_timing.hpp).
struct TimedRun {
  /// Segments [firstSegment, endSegment) of the action.
  std::size_t firstSegment = 0;
  std::size_t endSegment = 0;
  /// The blend bound at each waypoint of the run (runWaypoints()): 0 leaves a sharp corner where
  /// the trajectory stops; the first and last entries are unused.
  std::vector<double> cornerDeviations;
};

/// How an action's trajectory came out.
struct TrajectoryQuality {
  /// Where the arm is at rest inside a run: corners left sharp (reversals, blends refused).
  int stopsInsideRuns = 0;
  /// Corners blended, and those whose first blend had to be made smaller.
  int blendedCorners = 0;
  int reducedBlends = 0;
  /// Runs whose time-optimal trajectory broke a limit on its samples and were timed rest to
  /// rest instead (a numerical failure, reported rather than hidden).
  int restToRestFallbacks = 0;
  /// Runs made jerk-limited (joints with a jerk limit in the robot model), and how many of them
  /// needed a lower acceleration to keep within kJerkFilterDeviation of their path.
  int jerkLimitedRuns = 0;
  int jerkReducedRuns = 0;
  /// Length of the path the trajectory follows (joint space, Euclidean; blends included).
  double pathLength = 0.0;
  /// Seconds spent timing (blend checks and parameterization).
  double seconds = 0.0;

  TrajectoryQuality& operator+=(const TrajectoryQuality& other);
};

struct ActionExecution {
  std::size_t index = 0;
  SymbolicAction action;
  ActionStatus status = ActionStatus::kNotRun;
  /// On failure: the stage ("grasp", "placement", "ik", "motion", "push", "precondition") and
  /// why, naming the object.
  std::string stage;
  std::string reason;
  /// On failure: the objects standing where the action needed room (a placement's blockers).
  std::vector<std::string> blockingObjects;
  /// On failure: the gripper cannot hold the object in any direction (GroundingFailure).
  bool objectUngraspable = false;
  /// What was chosen: "top, closing 90 deg ...", "in holder at ...", "home".
  std::string choice;
  std::vector<MotionSegment> segments;
  /// The action's motion, time from the start of the action (empty unless it succeeded).
  JointTrajectory trajectory;
  /// When each of `segments` ends in `trajectory` (seconds from the start of the action): which
  /// world (attachments) holds at each moment of the motion. Exact at run ends (rest); inside a
  /// run, the trajectory point nearest the segment's last waypoint.
  std::vector<double> segmentEndTimes;
  /// How the segments were joined and blended (time-optimal timing; empty otherwise).
  std::vector<TimedRun> runs;
  TrajectoryQuality quality;
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
