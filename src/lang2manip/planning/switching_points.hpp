#pragma once
/// @file Switching points of the phase plane (Kunz and Stilman, RSS 2012, section VI): where the
/// time-optimal trajectory may touch the limit curve. Internal to timeOptimalParameterize.

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "lang2manip/planning/phase_plane.hpp"

namespace lang2manip::totg {

/// A point (s, v) on the limit curve from which integrating backward (first with
/// beforeAcceleration) and forward (first with afterAcceleration) both stay below the curve.
/// Both accelerations are the one-sided limits at s (they differ where the curve has a corner).
struct SwitchingPoint {
  double s = 0.0;
  double v = 0.0;
  double beforeAcceleration = 0.0;
  double afterAcceleration = 0.0;
};

/// Finds the switching points of one rest-to-rest piece (segments first..last), segment by
/// segment on demand. With g(s) = (the path acceleration of a trajectory leaving the limit curve
/// at s) / v - (the curve's slope), a switching point is where g turns from > 0 (a trajectory can
/// arrive there from below) to <= 0 (it can leave without going above): at segment boundaries
/// (where the curvature and the curve jump), at corners of the acceleration-limit curve (where a
/// joint's derivative is zero, one-sided values), at the points where the constraint that makes
/// the curve changes (the curve bends down there and may then fall faster than the trajectory
/// can brake), and between grid points of each arc (kMaxNodeAngle apart), found by regula falsi.
/// Covers the acceleration-limit curve (continuous, discontinuous and non-differentiable cases)
/// and the velocity-limit curve alike.
class SwitchingPointFinder {
 public:
  SwitchingPointFinder(const PhasePlane& plane, std::size_t first, std::size_t last);

  /// The first switching point at s >= from beyond every one returned before; nullopt when
  /// none is left before the piece's end.
  [[nodiscard]] std::optional<SwitchingPoint> next(double from);

  /// Largest angle (rad) of an arc between two grid points of the search.
  static constexpr double kMaxNodeAngle = 0.2;

 private:
  // The limit curve at one node: value, and g on each side, from the one-sided limits (g > 0
  // on the left: a trajectory can reach it from below; g <= 0 on the right: it can leave it
  // without going above).
  struct Node {
    double s = 0.0;
    double v = 0.0;
    double gLeft = 0.0;
    double gRight = 0.0;
    double slopeRight = 0.0;
    CurveBranch branch;  // what makes the curve there
  };
  // `corner`: s is a corner of the curve (a joint's derivative is zero), where the one-sided
  // values are taken next to it; elsewhere the curve's analytic slope is used.
  [[nodiscard]] Node evaluate(std::size_t k, double s, bool hasLeft, bool hasRight, bool corner) const;
  // g from the path acceleration range and the curve's slope at a point next to a node.
  [[nodiscard]] static double sideG(const CurveLimits& curve, bool leaving, double slope);
  void add(std::size_t before, std::size_t after, double s, double v, double slopeRight, bool onCurve);
  void scanBoundary(std::size_t k);
  void scanArc(std::size_t k);
  // Adds the switching point between two nodes, or at `right` (when it is inside the arc).
  void compare(std::size_t k, const Node& left, const Node& right, bool rightIsInside);
  // Where the constraint that makes the curve changes between two nodes.
  [[nodiscard]] double changeOfBranch(std::size_t k, const Node& left, const Node& right) const;
  void bisect(std::size_t k, double below, double above);

  const PhasePlane& plane_;
  std::size_t first_;
  std::size_t last_;
  std::size_t scanned_;  // segments before this one are scanned (or skipped)
  std::size_t cursor_ = 0;
  double lastReturned_ = -std::numeric_limits<double>::infinity();
  std::vector<SwitchingPoint> found_;
  std::vector<double> corners_;  // scratch
};

}  // namespace lang2manip::totg
