#pragma once
/// @file The collision-checking interface shared by every backend (exact FCL today, a vectorized
/// sphere backend later): is a state valid, is a motion valid, a batch of states in one call,
/// and a diagnostic report naming the colliding pairs with penetration depths and distances.

#include <memory>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// Per-thread scratch memory of a checker (poses of every geometry, FK workspaces, narrow-phase
/// results). Made by CollisionChecker::makeContext() and only usable with the checker that made
/// it. Not thread-safe: give each thread its own, as with Drake's per-thread contexts.
class CollisionContext {
 public:
  virtual ~CollisionContext() = default;
  CollisionContext() = default;
  CollisionContext(const CollisionContext&) = delete;
  CollisionContext& operator=(const CollisionContext&) = delete;

  /// The checker that made this context (to detect a context given to another checker).
  [[nodiscard]] const void* owner() const noexcept { return owner_; }

 protected:
  explicit CollisionContext(const void* owner) : owner_(owner) {}

 private:
  const void* owner_ = nullptr;
};

/// A pair of bodies in contact. Bodies are named "robot/link" for robot links and by the object
/// name for objects (attached objects too).
struct CollisionContact {
  std::string first;
  std::string second;
  /// Largest penetration depth over the geometries of the two bodies (m; 0 when touching or
  /// when the backend cannot tell).
  double penetrationDepth = 0.0;
};

/// What a report should compute beyond validity.
struct CollisionRequest {
  /// Compute the smallest distance between any checked pair when the state is valid (slower:
  /// no bounding-box pre-check applies).
  bool computeDistance = false;
};

/// A diagnostic report for one world state.
struct CollisionReport {
  bool valid = true;
  /// Every colliding body pair (one entry per pair of bodies), in a deterministic order.
  std::vector<CollisionContact> contacts;
  /// When requested and valid: the smallest distance between checked bodies and their names
  /// (+infinity when there is no pair to check). When invalid: minus the largest penetration.
  double minimumDistance = 0.0;
  std::string closestFirst;
  std::string closestSecond;
};

/// Configuration and base pose of every robot of the checker's scene, in scene order.
struct WorldState {
  std::vector<VectorX> configurations;
  std::vector<Pose> basePoses;
};

/// The interface (non-virtual public methods that check their arguments once, then call the
/// protected virtual DoX(), as Drake's CollisionChecker does).
///
/// A checker is built for one Scene: the robots, the objects and the attachments are fixed at
/// construction (build a new checker when the world changes). Single-robot calls move one robot;
/// every other robot stays at its scene configuration. Only collisions are checked (not joint
/// limits). A robot link or held object that penetrates a fixed object by no more than
/// scene().contactTolerance() rests on it: contact, not collision. Object–object pairs are never checked (the world is static); objects whose
/// collisionEnabled is false are ignored.
///
/// Thread-safety: a checker is immutable after construction; all its methods are const and may be
/// called from several threads at once, each thread with its own CollisionContext.
class CollisionChecker {
 public:
  virtual ~CollisionChecker() = default;
  CollisionChecker(const CollisionChecker&) = delete;
  CollisionChecker& operator=(const CollisionChecker&) = delete;

  /// The scene the checker was built for.
  [[nodiscard]] const Scene& scene() const noexcept { return scene_; }

  /// Index of robot `name` in scene().robots(); throws InputError listing the robots if unknown.
  [[nodiscard]] int robotIndex(const std::string& name) const;

  /// A fresh per-thread context (allocates; make one per thread and reuse it).
  [[nodiscard]] std::unique_ptr<CollisionContext> makeContext() const;

  /// True when robot `robot` at `q` touches nothing it may not touch (itself beyond the allowed
  /// pairs, other robots, enabled objects; attached objects included).
  /// @throws InputError for an unknown robot index, a configuration of the wrong size or with
  ///         NaN/infinite values, or a context made by another checker.
  [[nodiscard]] bool isStateValid(int robot, const VectorX& q, CollisionContext& context) const;

  /// True when every state of the straight joint-space segment q0 -> q1 is valid, sampled so that
  /// no joint moves more than `resolution` (rad or m) between samples; both ends are checked.
  /// @throws InputError as isStateValid(), and for a resolution that is not positive and finite.
  [[nodiscard]] bool isMotionValid(int robot, const VectorX& q0, const VectorX& q1,
                                   double resolution, CollisionContext& context) const;

  /// Validity of many configurations of one robot in one call (result i is configuration i);
  /// a vectorized backend checks them together. Throws as isStateValid() (naming the index).
  [[nodiscard]] std::vector<bool> checkStates(int robot, const std::vector<VectorX>& configurations,
                                              CollisionContext& context) const;

  /// Diagnostic report for robot `robot` at `q` (others at their scene configuration).
  /// @throws InputError as isStateValid().
  [[nodiscard]] CollisionReport checkState(int robot, const VectorX& q,
                                           const CollisionRequest& request,
                                           CollisionContext& context) const;

  /// Diagnostic report with every robot moved: robot-vs-robot pairs are checked with both
  /// robots at the given states. @throws InputError when the state does not have one
  /// configuration and one finite base pose per robot, or a configuration is invalid.
  [[nodiscard]] CollisionReport checkWorld(const WorldState& state, const CollisionRequest& request,
                                           CollisionContext& context) const;

  /// The scene's configurations and base poses as a WorldState.
  [[nodiscard]] WorldState sceneState() const;

 protected:
  explicit CollisionChecker(Scene scene) : scene_(std::move(scene)) {}

  [[nodiscard]] virtual std::unique_ptr<CollisionContext> DoMakeContext() const = 0;
  /// Arguments already checked; inner-loop calls: noexcept and allocation-free.
  [[nodiscard]] virtual bool DoIsStateValid(int robot, const VectorX& q,
                                            CollisionContext& context) const noexcept = 0;
  [[nodiscard]] virtual bool DoIsMotionValid(int robot, const VectorX& q0, const VectorX& q1,
                                             double resolution,
                                             CollisionContext& context) const noexcept = 0;
  /// `valid` has configurations.size() entries on entry.
  virtual void DoCheckStates(int robot, const std::vector<VectorX>& configurations,
                             std::vector<bool>& valid, CollisionContext& context) const noexcept = 0;
  [[nodiscard]] virtual CollisionReport DoCheckWorld(const WorldState& state,
                                                     const CollisionRequest& request,
                                                     CollisionContext& context) const = 0;

 private:
  void checkRobot(int robot) const;
  void checkContext(const CollisionContext& context) const;
  void checkQ(int robot, const VectorX& q, const std::string& what) const;

  Scene scene_;
};

}  // namespace lang2manip
