#pragma once
/// @file The space a motion query is planned in: the controlled joints of one or several robots
/// (real joint values), or a Kautham problem's normalized controls with their couplings. A
/// space maps a point x to the world (robot configurations and base poses), checks validity with
/// the collision module, and is an affine image of the trajectory joints (q = offset + J x), which
/// time parameterization uses to respect each joint's limits.

#include <memory>
#include <optional>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "lang2manip/collision/collision_checker.hpp"
#include "lang2manip/core/types.hpp"
#include "lang2manip/model/kautham_problem.hpp"

namespace lang2manip {

/// Per-thread scratch of a space (a collision context and a full configuration).
struct SpaceWorkspace {
  std::unique_ptr<CollisionContext> collision;
  VectorX configuration;
  WorldState world;
};

/// How far planned motions keep from each joint's position limits: planners sample, connect and
/// smooth intermediate states only inside the limits moved inward by it, so no trajectory passes a
/// limit at speed. The start and goals may lie inside the margin (they are states at rest): the
/// box is widened to contain them. Continuous joints and Kautham controls have no margin.
struct PositionMargin {
  /// rad for revolute joints (3 degrees).
  double angular = 0.05;
  /// m for prismatic joints.
  double linear = 0.005;
  /// Neither is more than this fraction of a joint's range.
  static constexpr double kMaxRangeFraction = 0.1;
};

/// Which PositionMargin a coordinate keeps from its limits.
enum class MarginKind { kNone, kAngular, kLinear };

/// A box of a planning space: per coordinate, lower <= x <= upper.
struct StateBounds {
  VectorX lower;
  VectorX upper;
};

/// A bounded subset of R^n with validity, motion checking and the map to joint values.
/// Immutable after construction; the check methods are thread-safe (per-thread workspaces).
class PlanningSpace {
 public:
  virtual ~PlanningSpace() = default;
  PlanningSpace(const PlanningSpace&) = delete;
  PlanningSpace& operator=(const PlanningSpace&) = delete;

  [[nodiscard]] int dimension() const noexcept { return static_cast<int>(dofNames_.size()); }
  /// Name of each coordinate ("panda/panda_joint1", or a Kautham control name).
  [[nodiscard]] const std::vector<std::string>& dofNames() const noexcept { return dofNames_; }
  [[nodiscard]] const VectorX& lower() const noexcept { return lower_; }
  [[nodiscard]] const VectorX& upper() const noexcept { return upper_; }
  [[nodiscard]] const CollisionChecker& checker() const noexcept { return *checker_; }

  /// The joints a trajectory reports ("robot/joint"; base axes as "robot/base_x"...), and the
  /// affine map from x: q = trajectoryOffset() + trajectoryJacobian() * x (before clamping).
  [[nodiscard]] const std::vector<std::string>& trajectoryJointNames() const noexcept {
    return trajectoryJointNames_;
  }
  [[nodiscard]] virtual VectorX trajectoryPositions(const VectorX& x) const = 0;
  [[nodiscard]] const MatrixX& trajectoryJacobian() const noexcept { return jacobian_; }
  /// Velocity and acceleration limits of the trajectory joints.
  [[nodiscard]] const VectorX& jointVelocityLimits() const noexcept { return velocityLimits_; }
  [[nodiscard]] const VectorX& jointAccelerationLimits() const noexcept {
    return accelerationLimits_;
  }
  /// Jerk limits of the trajectory joints, 0 where the model gives none (no default is assumed).
  [[nodiscard]] const VectorX& jointJerkLimits() const noexcept { return jerkLimits_; }

  /// The world at x: every robot's configuration and base pose.
  [[nodiscard]] virtual WorldState worldState(const VectorX& x) const = 0;

  /// The step of tree planners (OMPL's `range`) when the settings do not give one; nullopt keeps
  /// OMPL's default (a fifth of the space's extent).
  [[nodiscard]] virtual std::optional<double> defaultRange() const { return std::nullopt; }

  /// The box intermediate states are planned in (see PositionMargin): lower()/upper() moved inward
  /// by `margin`, widened to contain every point of `restingPoints`.
  [[nodiscard]] StateBounds plannedBounds(const PositionMargin& margin,
                                          const std::vector<VectorX>& restingPoints) const;

  /// Throws InputError (naming `what`) unless x has dimension() finite values within bounds.
  void checkPoint(const VectorX& x, const std::string& what) const;

  /// True when the world at x is collision-free (x within bounds is the caller's duty).
  [[nodiscard]] bool isValid(const double* x) const;
  /// True when every state of the straight segment x0 -> x1 is valid, no trajectory joint moving
  /// more than `resolution` (rad or m) between checked states; both ends are checked.
  [[nodiscard]] bool isMotionValid(const double* x0, const double* x1, double resolution) const;
  /// A diagnostic report at x naming the colliding pairs.
  [[nodiscard]] CollisionReport report(const VectorX& x) const;

  /// How many equal steps the segment x0 -> x1 is checked in so that no trajectory joint moves
  /// more than `resolution` per step; base translations with a range above 5 units (worlds
  /// modelled in centimetres) move at most resolution * range / 5.
  [[nodiscard]] int motionSteps(const double* x0, const double* x1, double resolution) const;
  /// The first invalid state of the segment checked in motionSteps() steps, if any.
  [[nodiscard]] std::optional<VectorX> firstInvalidState(const VectorX& x0, const VectorX& x1,
                                                         double resolution) const;

 protected:
  explicit PlanningSpace(std::shared_ptr<const CollisionChecker> checker);

  /// Set by subclasses in their constructor.
  std::vector<std::string> dofNames_;
  VectorX lower_;
  VectorX upper_;
  std::vector<std::string> trajectoryJointNames_;
  MatrixX jacobian_;
  VectorX velocityLimits_;
  VectorX accelerationLimits_;
  VectorX jerkLimits_;
  /// Per trajectory joint: how many times `resolution` it may move per checked step.
  VectorX stepScale_;
  /// Per coordinate, which PositionMargin applies; empty: none (set by subclasses).
  std::vector<MarginKind> marginKinds_;

  [[nodiscard]] SpaceWorkspace& workspace() const;
  [[nodiscard]] virtual bool isValidIn(const double* x, SpaceWorkspace& workspace) const = 0;
  /// A faster exact motion check when the subclass has one; nullopt to use interpolation.
  [[nodiscard]] virtual std::optional<bool> fastMotionCheck(const double* x0, const double* x1,
                                                            double resolution,
                                                            SpaceWorkspace& workspace) const;

 private:
  std::shared_ptr<const CollisionChecker> checker_;
  mutable std::mutex workspacesMutex_;
  mutable std::unordered_map<std::thread::id, std::unique_ptr<SpaceWorkspace>> workspaces_;
};

/// The limits trajectories are timed with where a robot model gives none. A joint's velocity
/// limit is its model's when positive, else kDefaultJointVelocityLimit (robot_model.hpp; the URDF
/// reader warns once per model). Its acceleration limit is its model's when known (a joint
/// limits file gave one, see joint_limits_reader.hpp), else accelerationPerVelocity times the
/// velocity limit.
struct JointLimitDefaults {
  /// Per second: an acceleration limit of 2 x the velocity limit reaches full speed in 0.5 s.
  double accelerationPerVelocity = 2.0;
  /// Velocity and acceleration limits of base axes (m/s, m/s^2; unit-cube rotation units/s).
  double baseVelocity = 0.5;
  double baseAcceleration = 1.0;

  /// The velocity limit of variable `variable` of `model` (see the struct comment).
  [[nodiscard]] double velocityLimit(const RobotModel& model, int variable) const;
  /// The acceleration limit of variable `variable` of `model` (see the struct comment).
  [[nodiscard]] double accelerationLimit(const RobotModel& model, int variable) const;
};

/// The controlled joints of one or several robots. Each robot's other variables stay at their
/// scene values. One robot: validity is the checker's fast single-robot check.
class JointPlanningSpace final : public PlanningSpace {
 public:
  /// Plans `variables[i]` (variable names) of robot `robots[i]`; an empty list means every
  /// variable of that robot. The joints' velocity and acceleration limits are the models' where
  /// known, else `defaults`'. Throws InputError for unknown robots or joints (listing the valid
  /// names) or a joint with an empty range.
  JointPlanningSpace(std::shared_ptr<const CollisionChecker> checker,
                     const std::vector<std::string>& robots,
                     const std::vector<std::vector<std::string>>& variables = {},
                     const JointLimitDefaults& defaults = {});

  [[nodiscard]] VectorX trajectoryPositions(const VectorX& x) const override;
  [[nodiscard]] WorldState worldState(const VectorX& x) const override;
  /// 0.5 (rad): on the MotionBenchMaker Panda problems RRTConnect solves 574 of 575 in 10 s with
  /// it, 565 with OMPL's default of about 2.4 (a fifth of the 7-DOF extent).
  [[nodiscard]] std::optional<double> defaultRange() const override { return 0.5; }
  /// x for a world where the robots are at `configurations` (one per planned robot, full size).
  [[nodiscard]] VectorX pointFromConfigurations(const std::vector<VectorX>& configurations) const;

 private:
  struct PlannedVariable {
    int robot;     // index in the scene
    int variable;  // index in the robot's configuration
  };
  [[nodiscard]] bool isValidIn(const double* x, SpaceWorkspace& workspace) const override;
  [[nodiscard]] std::optional<bool> fastMotionCheck(const double* x0, const double* x1,
                                                    double resolution,
                                                    SpaceWorkspace& workspace) const override;
  void fillWorld(const double* x, WorldState& world) const;

  std::vector<int> robots_;
  std::vector<PlannedVariable> planned_;
  WorldState sceneWorld_;
};

/// A Kautham problem's robot controls in [0,1]^k, mapped through its couplings to the joints and
/// base poses of every robot (kautham-format.md).
class KauthamControlSpace final : public PlanningSpace {
 public:
  /// `problem` must outlive the space; `checker` is built on the query's scene.
  KauthamControlSpace(std::shared_ptr<const CollisionChecker> checker,
                      const KauthamProblem& problem, const JointLimitDefaults& defaults = {});

  [[nodiscard]] VectorX trajectoryPositions(const VectorX& x) const override;
  [[nodiscard]] WorldState worldState(const VectorX& x) const override;

 private:
  [[nodiscard]] bool isValidIn(const double* x, SpaceWorkspace& workspace) const override;
  void buildTrajectoryMap(const JointLimitDefaults& defaults);

  const KauthamProblem& problem_;
  VectorX trajectoryOffset_;
  VectorX trajectoryLow_;
  VectorX trajectoryHigh_;
};

}  // namespace lang2manip
