#pragma once
/// @file The exact collision checker: FCL 0.7 narrow phase on primitives, capsules and
/// BVHModel<OBBRSS> meshes, with a world-aligned bounding-box pre-check per geometry pair.

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lang2manip/collision/allowed_collision_matrix.hpp"
#include "lang2manip/collision/collision_checker.hpp"

namespace lang2manip {

struct FclWorldTables;
struct FclGeometryPair;

/// Settings of FclCollisionChecker.
struct FclCheckerSettings {
  /// Skip the narrow phase of a pair whose world-aligned boxes do not overlap (exact: the boxes
  /// enclose the geometries). Off only to measure what it saves.
  bool boundingBoxPrecheck = true;
  /// How each robot's allowed-collision matrix is computed.
  AllowedCollisionSettings allowedCollisions;
  /// Matrices computed before (e.g. for a model loaded twice), one per scene robot in scene
  /// order; empty: take them from the process-wide cache (computed on a model's first use).
  std::vector<std::shared_ptr<const AllowedCollisionMatrix>> precomputedMatrices;
};

/// CollisionChecker backed by FCL (see the file comment). Bodies: every robot link with
/// collision geometry, every enabled object; an attached object moves with its link and is not
/// checked against that link, the links rigidly fixed to it, nor the fingers of a gripper
/// mounted there; it is checked against the other links and the rest of the world.
/// Self-collision pairs are filtered by each robot's AllowedCollisionMatrix (computed at
/// construction: adjacency, SRDF, never/always over seeded random samples).
///
/// Construction costs the ACM sampling (a few thousand FK + self checks per robot model) the first
/// time a model is used in the process: the matrices are cached per model
/// (cachedAllowedCollisionMatrix), so later checkers of the same model share them.
/// Thread-safe as described in CollisionChecker: immutable after construction.
class FclCollisionChecker final : public CollisionChecker {
 public:
  /// Builds the checker for `scene`. Throws InputError for an SRDF or an attachment naming an
  /// unknown link, or invalid settings (a precomputed matrix count or size that does not match).
  explicit FclCollisionChecker(Scene scene, const FclCheckerSettings& settings = {});
  ~FclCollisionChecker() override;

  /// The allowed-collision matrix of robot `robot` (index into scene().robots()).
  /// Throws InputError for an unknown index.
  [[nodiscard]] const AllowedCollisionMatrix& allowedCollisions(int robot) const;
  /// The same, shared (to pass as FclCheckerSettings::precomputedMatrices to another checker).
  [[nodiscard]] std::shared_ptr<const AllowedCollisionMatrix> sharedAllowedCollisions(int robot) const;

  /// Number of geometry pairs a single-robot check of `robot` visits (self + world).
  [[nodiscard]] std::size_t pairCount(int robot) const;

  /// Shapes left out because they cannot collide (meshes without triangles, zero sizes).
  [[nodiscard]] int skippedShapes() const noexcept;

 protected:
  [[nodiscard]] std::unique_ptr<CollisionContext> DoMakeContext() const override;
  [[nodiscard]] bool DoIsStateValid(int robot, const VectorX& q,
                                    CollisionContext& context) const noexcept override;
  [[nodiscard]] bool DoIsMotionValid(int robot, const VectorX& q0, const VectorX& q1,
                                     double resolution,
                                     CollisionContext& context) const noexcept override;
  void DoCheckStates(int robot, const std::vector<VectorX>& configurations, std::vector<bool>& valid,
                     CollisionContext& context) const noexcept override;
  [[nodiscard]] CollisionReport DoCheckWorld(const WorldState& state, const CollisionRequest& request,
                                             CollisionContext& context) const override;

 private:
  class Context;
  void placeRobot(int robot, const VectorX& q, const Pose& X_WB, Context& context) const noexcept;
  [[nodiscard]] bool pairCollides(const FclGeometryPair& pair, Context& context) const noexcept;
  [[nodiscard]] static bool boxesOverlap(const Context& context, std::size_t a, std::size_t b) noexcept;
  /// Colliding body pairs of the world pairs (with contacts) -> largest penetration depth.
  [[nodiscard]] std::map<std::pair<int, int>, double> touchingBodies(Context& context) const;
  void closestPair(Context& context, CollisionReport& report) const;
  [[nodiscard]] const std::string& bodyName(int body) const;

  FclCheckerSettings settings_;
  std::unique_ptr<const FclWorldTables> tables_;
  /// X_WG and world boxes of every geometry with the robots at their scene state.
  std::vector<Pose> scenePoses_;
};

}  // namespace lang2manip
