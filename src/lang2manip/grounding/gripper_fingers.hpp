#pragma once
/// @file Internal to gripper_geometry.cpp: the fingers of a gripper found from its joints, the
/// points of their collision geometry, and the pad gap at any position of the travel.

#include <optional>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/robot_model.hpp"

namespace lang2manip::gripper_detail {

/// A flat piece of a link's collision surface (link frame): outward unit normal, area, corners.
struct Facet {
  Vector3 normal = Vector3::UnitZ();
  double area = 0.0;
  std::vector<Vector3> corners;
};

/// A link of a finger with the points and the flat pieces of its collision geometry (link frame).
struct FingerLink {
  int link = -1;
  std::vector<Vector3> points;
  std::vector<Facet> facets;
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
  /// For a gripper of one jaw that closes against its body (one joint, no mimics): that body's
  /// geometry as one link (the body's root link, facets and points in its frame). Else none.
  [[nodiscard]] const std::optional<FingerLink>& fixedJaw() const noexcept { return fixedJaw_; }
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
  std::optional<FingerLink> fixedJaw_;
};

/// The face of a pad that meets an object, in the pad link's frame: the corners of its facets
/// (how deep it reaches along the approach axis), and the corners and centres that lie in the
/// face's layer (where its surface is: a bevelled edge's outer corners stand back from it).
struct ContactFace {
  std::vector<Vector3> corners;
  std::vector<Vector3> surface;
  [[nodiscard]] bool empty() const noexcept { return surface.empty(); }
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
  /// For each pad: its contact face, where it meets an object (see contactFace). Empty when none
  /// is found: the whole pad counts.
  std::vector<ContactFace> contactFaces;
  /// With a single pad and a fixed jaw: the jaw's face that meets an object (in the frame of
  /// FingerSet::fixedJaw()'s link); otherwise empty, and the pad closes onto the tool's axis.
  ContactFace jawFace;
};

/// Along the approach axis, the band in which the pads' contact faces lie at link poses `poses`
/// (where their depths overlap; all of them when they do not).
std::pair<double, double> contactBand(const FingerSet& fingers, const PadLayout& layout, const std::vector<Pose>& poses);

/// The surface points of the contact face of pad `f` (an index into layout.pads) in the tool frame
/// at link poses `poses` (every point of the pad when it has no contact face): where the pad gap
/// is measured, not at ribs or lips elsewhere on the finger.
/// The surface points of the fixed jaw's face in the tool frame (none without one).
std::vector<Vector3> jawContactPoints(const FingerSet& fingers, const PadLayout& layout, const std::vector<Pose>& poses);

std::vector<Vector3> padContactPoints(const FingerSet& fingers, const PadLayout& layout, std::size_t f,
                                      const std::vector<Pose>& poses);

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

/// The flat pieces of the collision geometry of `link` in its frame: box faces, a cylinder's
/// side as 16 strips, mesh triangles (spheres have none).
std::vector<Facet> collisionFacets(const Link& link);

/// The face of `link` that meets an object coming along -`inward`
/// (tool frame) at pose X_TL: of the facets within about 45 degrees of `inward`, grouped into
/// layers 1 mm deep along it, the innermost layer of at least a quarter of the largest one's area.
/// Empty when no facet looks that way.
/// Only facets whose centres lie at least `nearest` along `approach` (tool frame) count.
ContactFace contactFace(const FingerLink& link, const Pose& X_TL, const Vector3& inward, const Vector3& approach = Vector3::Zero(),
                        double nearest = 0.0);

}  // namespace lang2manip::gripper_detail
