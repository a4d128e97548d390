#pragma once
/// @file The motions action grounding is made of, for one arm of one robot: transit motions
/// planned with a named OMPL planner, straight Cartesian tool motions (approach, retreat, lift,
/// push) solved by IK step by step, gripper motions, and the exact re-check of any motion
/// segment against the world it happens in.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/core/stop_condition.hpp"
#include "lang2manip/execution/execution_types.hpp"
#include "lang2manip/grounding/gripper_geometry.hpp"
#include "lang2manip/kinematics/ik_solver.hpp"
#include "lang2manip/planning/planning_space.hpp"

namespace lang2manip {

/// The executing arm and what is derived from it once. Immutable after construction.
class ArmContext {
 public:
  /// For `settings.robot` / `settings.manipulator` of `scene`. Throws InputError for an unknown
  /// robot, arm, IK solver or grasp planner, a gripper that does not open, or invalid settings
  /// (an arm without a gripper is accepted: it moves and pushes; picks are refused).
  ArmContext(const Scene& scene, ExecutionSettings settings);

  [[nodiscard]] const std::string& robotName() const noexcept { return robot_; }
  [[nodiscard]] const RobotModel& model() const noexcept { return *model_; }
  [[nodiscard]] const Manipulator& manipulator() const noexcept { return manipulator_; }
  [[nodiscard]] const GripperGeometry& gripper() const noexcept { return *gripper_; }
  [[nodiscard]] const ExecutionSettings& settings() const noexcept { return settings_; }
  [[nodiscard]] const std::shared_ptr<const IkSolver>& ik() const noexcept { return ik_; }
  /// The arm joints of the robot's named configuration "home", when it has one.
  [[nodiscard]] const std::optional<VectorX>& homeArm() const noexcept { return homeArm_; }
  /// `q` with the arm joints set to `arm` (values in manipulator().armJoints order).
  [[nodiscard]] VectorX withArm(VectorX q, const VectorX& arm) const;
  /// Variable indices of the arm joints in the robot's configuration.
  [[nodiscard]] const std::vector<int>& armVariables() const noexcept { return armVariables_; }

  /// An exact checker for `world` that reuses the allowed-collision matrices of the first world.
  [[nodiscard]] std::shared_ptr<const FclCollisionChecker> checkerFor(const Scene& world) const;
  /// A reachability checker (IK + collision) for `world`.
  [[nodiscard]] ReachabilityChecker reachIn(const Scene& world) const;
  /// X_WG: the gripper's grasp frame (GripperGeometry::graspFrame) in the world for configuration
  /// `q` of the robot in `world`.
  [[nodiscard]] Pose toolPose(const Scene& world, const VectorX& q) const;
  /// The gripper gap of configuration `q`.
  [[nodiscard]] double gripperWidth(const VectorX& q) const;
  /// The robot's full configuration space (every variable; the trajectories' joints and limits).
  [[nodiscard]] const PlanningSpace& robotSpace() const noexcept { return *robotSpace_; }

 private:
  std::string robot_;
  RobotModelPtr model_;
  Manipulator manipulator_;
  std::shared_ptr<const GripperGeometry> gripper_;
  ExecutionSettings settings_;
  std::shared_ptr<const IkSolver> ik_;
  std::vector<int> armVariables_;
  std::vector<std::shared_ptr<const AllowedCollisionMatrix>> matrices_;
  std::shared_ptr<const PlanningSpace> robotSpace_;
  std::optional<VectorX> homeArm_;
};

/// The named configuration transits fall back to: "home".
inline constexpr const char* kHomeConfiguration = "home";

/// A motion, or why there is none.
struct MotionResult {
  std::optional<MotionSegment> segment;
  /// "ik" or "motion" on failure, with the reason in words.
  std::string stage;
  std::string reason;
  /// Work done.
  int plannerCalls = 0;
  int plannerSolved = 0;
  int ikCalls = 0;
  long collisionChecks = 0;
  double ikSeconds = 0.0;

  [[nodiscard]] bool ok() const noexcept { return segment.has_value(); }
};

/// Plans the arm (or `joints` when given) from `start` to any of `goals` (full configurations;
/// the gripper and every other joint keep start's values) in `world` with `planner` (empty = the settings' default), within
/// the settings' time limit or until `stop`. The path is simplified and re-verified by the motion
/// planner. A start or goal in collision is a failure naming the colliding pair, not an error.
/// When no path is found and the robot has a "home" configuration, plans start -> home -> goal
/// (a known free configuration often joins IK branches a direct query does not); not when
/// `joints` are given.
MotionResult planTransit(const ArmContext& arm, const Scene& world, const VectorX& start,
                         const std::vector<VectorX>& goals, const std::string& planner,
                         const std::string& label, const StopCondition& stop,
                         const std::vector<std::string>& joints = {});

/// What a Cartesian motion may touch and carry (see MotionSegment).
struct CartesianAllowance {
  std::vector<std::pair<std::string, std::string>> allowedContacts;
  /// Push: the object carried from `carriedStart` by `carriedDisplacement` (see MotionSegment).
  std::string carried;
  Pose carriedStart = Pose::Identity();
  Vector3 carriedDisplacement = Vector3::Zero();
};

/// The pairs (object, robot/finger link) of every finger of the arm's gripper.
std::vector<std::pair<std::string, std::string>> fingerContacts(const ArmContext& arm, const std::string& object);
/// A Cartesian motion during which the fingers may touch `object`.
CartesianAllowance fingersMayTouch(const ArmContext& arm, const std::string& object);

/// Moves the tool frame in a straight line (position interpolated, orientation slerped) from
/// its pose at `start` to `X_WG_goal`, with IK at every step seeded by the previous solution;
/// fails on an IK failure, a joint jump above settings.maxJointStep, or a collision found at
/// the verification resolution. The gripper joints keep start's values.
MotionResult planCartesian(const ArmContext& arm, const Scene& world, const VectorX& start,
                           const Pose& X_WG_goal, const std::string& label,
                           const CartesianAllowance& allowance = {});

/// Opens or closes the gripper from `start` to a finger gap of `width` (one straight segment).
MotionSegment gripperMotion(const ArmContext& arm, const Scene& world, const VectorX& start, double width,
                            const std::string& label,
                            std::vector<std::pair<std::string, std::string>> allowedContacts = {});

/// Closes the gripper from `start` onto `object` and stops where the fingers first touch it: the
/// travel is searched (bisection on the finger geometry against the object's, to 1/4096 of the
/// travel) for the last position without contact, which is what the segment ends at. Fails with
/// stage "grasp" when the fingers close fully without touching `object`.
MotionResult closeGripperOn(const ArmContext& arm, const Scene& world, const VectorX& start, const std::string& object,
                            const std::string& label);

/// The outcome of checkSegment().
struct SegmentCheck {
  /// Empty when the segment is collision-free; otherwise names the waypoint and the pair.
  std::string collision;
  /// Robot states checked.
  long checks = 0;
};

/// Checks configurations of the arm's robot against one segment's world and allowed contacts
/// (the robot's part of checkSegment: a carried object is left out), with one checker for all.
class SegmentStateChecker {
 public:
  SegmentStateChecker(const ArmContext& arm, const MotionSegment& segment);
  /// Empty when the robot at `q` touches nothing, or only what the segment allows; otherwise
  /// the contacts ("a - b, c - d").
  [[nodiscard]] std::string forbiddenContacts(const VectorX& q);
  /// Configurations checked so far.
  [[nodiscard]] long checks() const noexcept { return checks_; }

 private:
  const MotionSegment* segment_;
  std::shared_ptr<const FclCollisionChecker> checker_;
  int robot_ = 0;
  std::unique_ptr<CollisionContext> context_;
  long checks_ = 0;
};

/// Empty when a push segment's carried object sweeps free of the other objects (or nothing is
/// carried); otherwise says what it would hit and where.
std::string carriedSweepCollision(const MotionSegment& segment);

/// Checks `segment` in its world at `resolution` (but for its allowed contacts; a carried
/// object's sweep is checked against the other objects).
SegmentCheck checkSegment(const ArmContext& arm, const MotionSegment& segment, double resolution);

}  // namespace lang2manip
