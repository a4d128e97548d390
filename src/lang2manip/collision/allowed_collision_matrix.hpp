#pragma once
/// @file Which link pairs of a robot may touch (and so are never checked): the allowed-collision
/// matrix, computed automatically the way MoveIt's setup assistant does (adjacent links, pairs
/// never or always in collision over random samples) plus the SRDF's disabled pairs.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

/// Why a link pair is allowed to touch (kNone: it is checked).
enum class AllowedReason : std::uint8_t { kNone, kSameLink, kAdjacent, kSrdf, kNever, kAlways, kDefault };

/// "none", "same link", "adjacent", "srdf", "never", "always".
std::string allowedReasonName(AllowedReason reason);

/// A symmetric link-by-link matrix of AllowedReason. Immutable once computed; const methods are
/// thread-safe.
class AllowedCollisionMatrix {
 public:
  /// Every pair checked except a link with itself.
  explicit AllowedCollisionMatrix(int linkCount);

  [[nodiscard]] int linkCount() const noexcept { return count_; }
  /// True when links `a` and `b` may touch (indices not checked: inner-loop call).
  [[nodiscard]] bool isAllowed(int a, int b) const noexcept {
    return reasons_[index(a, b)] != AllowedReason::kNone;
  }
  [[nodiscard]] AllowedReason reason(int a, int b) const noexcept { return reasons_[index(a, b)]; }
  /// Allows a pair unless it is allowed already (the first reason is kept).
  void allow(int a, int b, AllowedReason reason) noexcept;
  /// Number of distinct pairs a < b allowed for `reason`.
  [[nodiscard]] int count(AllowedReason reason) const noexcept;

 private:
  [[nodiscard]] std::size_t index(int a, int b) const noexcept {
    return static_cast<std::size_t>(a) * static_cast<std::size_t>(count_) + static_cast<std::size_t>(b);
  }
  int count_ = 0;
  std::vector<AllowedReason> reasons_;
};

/// Settings of computeAllowedCollisionMatrix() (the tuning constants, documented in one place).
/// Most link-pair cells times samples the never/always sampling may visit (about 220 links at
/// 2000 samples); beyond it sampling is skipped with a warning and every non-adjacent pair stays
/// checked (safe, only slower), so a robot of thousands of links loads in bounded time.
inline constexpr double kMaxSampledPairTests = 1e8;

struct AllowedCollisionSettings {
  /// Random configurations sampled uniformly within the joint limits.
  int samples = 2000;
  std::uint64_t seed = 20240611;
  /// Disable pairs that never collide in the samples (MoveIt's "Never"): faster checks, at the
  /// risk of missing a rare contact the samples did not find.
  bool disableNever = true;
  /// Disable pairs that collide in every sample (MoveIt's "Always": built-in overlaps).
  bool disableAlways = true;
  /// The share of samples in which a pair must collide to count as always colliding (MoveIt's
  /// setup assistant uses 95 %): faces that touch at zero depth flicker between colliding and
  /// free from one sample to the next.
  double alwaysFraction = 0.95;
  /// Disable pairs that collide in the robot's default configuration, every joint at 0 or the
  /// limit nearest it (MoveIt's "Default"), between a part on a movable joint no manipulator
  /// drives and a link no manipulator moves: a part the vendor left overlapping where the robot
  /// starts, such as a torso's bellows in its base, which the real robot moves by itself.
  bool disableDefault = true;
};

/// Tells, for configuration `q`, which link pairs collide: sets inCollision[a * linkCount + b]
/// (and [b * linkCount + a]) to 1 for each colliding pair of distinct links among those with
/// pairsToTest[a * linkCount + b] != 0 (the others are decided; their entries are ignored). Both
/// vectors have linkCount^2 entries; inCollision is all 0 on entry.
using LinkCollisionTest =
    std::function<void(const VectorX& q, const std::vector<char>& pairsToTest, std::vector<char>& inCollision)>;

/// 1 for each link (indexed like RobotModel::links()) whose collisions are off by default (SRDF
/// <disable_default_collisions>): checked against no object nor other robot, and against its
/// own robot's links only where an <enable_collisions> pair says so.
std::vector<char> linksWithDefaultCollisionsOff(const RobotModel& model);

/// Links rigidly connected to each other (through fixed joints) share a group id; indexed like
/// RobotModel::links().
std::vector<int> rigidLinkGroups(const RobotModel& model);

/// True when links `a` and `b` are rigidly connected or joined by one movable joint, possibly
/// through fixed joints on either side.
bool linksAdjacent(const RobotModel& model, const std::vector<int>& rigidGroups, int a, int b);

/// The matrix for `model`: adjacent pairs, the SRDF's disabled pairs and the pairs of links whose
/// default is off and that no <enable_collisions> names (unknown link names in the SRDF throw
/// InputError naming them), then, when enabled, the never/always pairs found by
/// `test` over `settings.samples` seeded random configurations (deterministic).
/// @throws InputError for samples < 1 when never/always detection is on.
AllowedCollisionMatrix computeAllowedCollisionMatrix(const RobotModel& model,
                                                     const LinkCollisionTest& test,
                                                     const AllowedCollisionSettings& settings = {});

/// True when `stored` allows no pair of links that `reference` does not allow: how a matrix read
/// from disk is checked against one computed here from the first few of the same seeded samples
/// (confirmationSettings()), so that a file claiming pairs "never" collide when they do is not
/// believed.
bool allowsNoMoreThan(const AllowedCollisionMatrix& stored, const AllowedCollisionMatrix& reference);

/// `settings` for checking a stored matrix: the first 64 of its samples, and "always" for pairs
/// colliding in at least 60% of them (a pair colliding in 95% of all samples does in 60% of the
/// first few).
AllowedCollisionSettings confirmationSettings(const AllowedCollisionSettings& settings);

}  // namespace lang2manip
