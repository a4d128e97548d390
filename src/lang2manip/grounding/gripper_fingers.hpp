#pragma once
/// @file Internal to gripper_geometry.cpp: the fingers of a gripper found from its joints, the
/// points of their collision geometry, and the pad gap at any position of the travel.

#include <optional>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/robot_model.hpp"

namespace lang2manip::gripper_detail {

/// A link of a finger with the points of its collision geometry (link frame).
struct FingerLink {
  int link = -1;
  std::vector<Vector3> points;
};

/// The links the gripper joints move and where their geometry is, over the travel.
class FingerSet {
 public:
  /// Throws InputError when the gripper joints move no link with collision geometry.
  FingerSet(const RobotModel& model, const std::string& toolFrame, const std::vector<std::string>& joints,
            std::vector<double> closed, std::vector<double> open);

  /// Every link moved by a gripper joint (with or without geometry).
  [[nodiscard]] const std::vector<int>& movedLinks() const noexcept { return moved_; }
  /// The moved links that have collision geometry.
  [[nodiscard]] const std::vector<FingerLink>& links() const noexcept { return links_; }
  /// Positions (in the tool frame) of the joints where fingers start, fully open.
  [[nodiscard]] const std::vector<Vector3>& rootsOpen() const noexcept { return rootsOpen_; }
  /// Poses in the tool frame of every link with the gripper at `fraction` (0 closed, 1 open).
  [[nodiscard]] std::vector<Pose> linkPoses(double fraction) const;
  /// linkPoses(1.0), computed once.
  [[nodiscard]] const std::vector<Pose>& openPoses() const noexcept { return openPoses_; }
  /// The points of finger link `i` in the tool frame for link poses `poses`.
  [[nodiscard]] std::vector<Vector3> pointsInTool(std::size_t i, const std::vector<Pose>& poses) const;
  /// Centroid of the points of finger link `i` in the tool frame.
  [[nodiscard]] Vector3 centroid(std::size_t i, const std::vector<Pose>& poses) const;
  /// Mean distance of the finger links' centroids from their mean at `fraction`: larger where
  /// the fingers are open.
  [[nodiscard]] double spread(double fraction) const;
  /// The full configuration with the gripper at `fraction` (other joints at the middle).
  [[nodiscard]] VectorX configuration(double fraction) const;

 private:
  const RobotModel& model_;
  int tool_ = -1;
  std::vector<int> variables_;
  std::vector<double> closed_;
  std::vector<double> open_;
  std::vector<int> moved_;
  std::vector<FingerLink> links_;
  std::vector<Vector3> rootsOpen_;
  std::vector<Pose> openPoses_;
};

/// How the pad gap is measured: two opposed sides (parallel grippers) or radial fingers.
struct PadLayout {
  /// Closing axis (tool frame, unit, perpendicular to the approach axis).
  Vector3 closing = Vector3::UnitY();
  /// Approach axis (tool frame, unit).
  Vector3 approach = Vector3::UnitZ();
  /// Indices into FingerSet::links() of each finger's pad (its farthest-reaching link).
  std::vector<std::size_t> pads;
  /// For two sides: pads[0] is on the +closing side, pads[1] on the -closing side. For radial
  /// fingers: the outward unit direction of each pad and the hand's axis point.
  bool radial = false;
  std::vector<Vector3> outward;
  Vector3 axisPoint = Vector3::Zero();
};

/// Finds the approach axis (unless `approach` gives it: unit, tool frame), the closing axis and
/// the pads from the fingers' motion between closed and open. Throws InputError when the
/// fingers do not move across the approach axis.
PadLayout layoutPads(const FingerSet& fingers, const std::string& where,
                     const std::optional<Vector3>& approach = std::nullopt);

/// The gap between the pads (m) for link poses `poses` (negative when they overlap).
double padGap(const FingerSet& fingers, const PadLayout& layout, const std::vector<Pose>& poses);

/// Where along the closing axis the middle of the gap between the pads lies (for radial
/// fingers, the hand's axis).
double gapMiddle(const FingerSet& fingers, const PadLayout& layout, const std::vector<Pose>& poses);

/// Points on the collision geometry of `link` in its frame: box corners, cylinder rims, sphere
/// poles and equator, mesh vertices (at most `limit` per mesh, evenly picked).
std::vector<Vector3> collisionPoints(const Link& link, std::size_t limit = 4000);

}  // namespace lang2manip::gripper_detail
