#pragma once
/// @file Can the robot put its tool frame at a pose without collision? IK (several solutions)
/// followed by an exact collision check with the gripper at a given opening; shared by grasp and
/// placement planning (and meant for action grounding: approach, retreat and push poses).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lang2manip/collision/collision_checker.hpp"
#include "lang2manip/grounding/gripper_geometry.hpp"
#include "lang2manip/kinematics/ik_solver.hpp"

namespace lang2manip {

/// Tuning of ReachabilityChecker.
struct ReachSettings {
  /// IK time budget per pose (s) and number of distinct IK solutions asked for.
  double ikTimeoutSeconds = 0.05;
  int ikSolutions = 3;
  /// Seed of the IK solver's random restarts.
  std::uint64_t seed = 1;
};

/// Why a pose is not reachable.
enum class ReachFailure { kNone, kOutOfReach, kNoIk, kInCollision };

/// "none", "out of reach", "no IK solution", "in collision".
std::string reachFailureName(ReachFailure failure);

struct ReachResult {
  ReachFailure failure = ReachFailure::kNone;
  /// Collision-free full robot configurations (gripper joints at the requested opening), nearest
  /// to the seed first. Non-empty exactly when failure == kNone.
  std::vector<VectorX> solutions;
  /// For people: "no IK solution (timeout: ...)", "in collision: panda/panda_hand - holder".
  std::string reason;
  [[nodiscard]] bool reachable() const { return failure == ReachFailure::kNone; }
};

/// Work counters (for reports and benchmarks).
struct ReachStatistics {
  int ikCalls = 0;
  int collisionChecks = 0;
};

/// See the file comment. Built for one world (the collision checker's scene), one robot and one
/// of its manipulators. Not thread-safe (it keeps a collision context and counters): give each
/// thread its own (copies share the immutable checker and solver).
class ReachabilityChecker {
 public:
  /// Throws InputError for a null checker or solver, an unknown robot (empty = the first robot
  /// of the checker's scene) or an unknown manipulator. `gripper` is the manipulator's
  /// describeGripper() when the caller has it already (null = described here).
  ReachabilityChecker(std::shared_ptr<const CollisionChecker> checker, std::shared_ptr<const IkSolver> ik,
                      const std::string& robot = {}, const std::string& manipulator = {},
                      ReachSettings settings = {}, std::shared_ptr<const GripperGeometry> gripper = nullptr);

  [[nodiscard]] const Scene& scene() const { return checker_->scene(); }
  [[nodiscard]] const SceneRobot& robot() const;
  [[nodiscard]] const RobotModel& model() const { return *robot().model; }
  [[nodiscard]] const GripperGeometry& gripper() const { return *gripper_; }
  [[nodiscard]] const ReachSettings& settings() const { return settings_; }
  [[nodiscard]] const CollisionChecker& checker() const { return *checker_; }
  [[nodiscard]] const ReachStatistics& statistics() const { return statistics_; }
  /// The robot's current configuration in the scene (the default IK seed).
  [[nodiscard]] const VectorX& currentConfiguration() const { return robot().configuration; }
  /// X_W(chain base): the frame IK targets are expressed in.
  [[nodiscard]] const Pose& chainBase() const { return chainBase_; }

  /// Collision-free IK solutions putting the tool frame at `X_WG` (world), searched from `seed`
  /// (full configuration; empty = the current one), with the gripper at `opening` (m). Contacts
  /// between object `touchable` (may be empty) and the finger links are allowed (a grasped
  /// object); every other contact makes a solution invalid.
  [[nodiscard]] ReachResult reach(const Pose& X_WG, const VectorX& seed, double opening,
                                  const std::string& touchable = {}) const;

  /// True when the arm has fewer than six joints: it cannot choose every turn of the hand about
  /// the approach axis, and grasps and placements take the turn it reaches (turnedToReach()).
  [[nodiscard]] bool turnIsConstrained() const { return armJoints_ < 6; }

  /// `X_WG` turned about its approach axis (the grasp frame's +z, through its origin) to the turn
  /// the arm reaches it with (IK for the position and the approach axis alone, searched from
  /// `seed`), or nullopt when the arm reaches no turn of it. For arms of fewer than six joints,
  /// whose hand turns with where it is; the caller checks that the turned pose still does.
  [[nodiscard]] std::optional<Pose> turnedToReach(const Pose& X_WG, const VectorX& seed) const;

  /// Why no grasp can reach object `object` of the scene: the nearest point of its bounds lies
  /// farther from the arm's base than the chain reaches plus the gripper's length ("marker is
  /// 0.52 m from the arm base of px100 (link base_link), beyond its reach of 0.43 m: move ...").
  /// Empty when some part of it is within reach.
  [[nodiscard]] std::string beyondReach(const std::string& object) const;

  /// Smallest distance (m) between the robot at `q` and the rest of the world; negative when in
  /// collision.
  [[nodiscard]] double clearance(const VectorX& q) const;

  /// The same robot, solver and settings in a variation of this world (an object moved,
  /// attached, removed or disabled). Builds an exact checker for `scene`, reusing this one's
  /// allowed-collision matrices when it is an FclCollisionChecker.
  [[nodiscard]] ReachabilityChecker withScene(Scene scene) const;

 private:
  [[nodiscard]] bool allowedContact(const CollisionContact& contact, const std::string& touchable) const;
  [[nodiscard]] std::string collisionReason(const VectorX& q, const std::string& touchable) const;
  [[nodiscard]] bool isFree(const VectorX& q, const std::string& touchable) const;

  std::shared_ptr<const CollisionChecker> checker_;
  std::shared_ptr<const IkSolver> ik_;
  std::string robotName_;
  int robotIndex_ = 0;
  std::shared_ptr<const GripperGeometry> gripper_;
  ReachSettings settings_;
  Pose chainBase_ = Pose::Identity();
  double chainReach_ = 0.0;
  std::string chainBaseLink_;
  std::size_t armJoints_ = 0;
  std::string toolFrame_;
  std::shared_ptr<CollisionContext> context_;
  mutable ReachStatistics statistics_;
};

}  // namespace lang2manip
