#pragma once
/// @file A path through joint-space waypoints made of straight segments joined by circular arcs,
/// parameterized by arc length: the path that time-optimal parameterization follows (Kunz and
/// Stilman, "Time-optimal trajectory generation for path following with bounded acceleration
/// and velocity", RSS 2012, section IV).

#include <cstddef>
#include <vector>

#include "lang2manip/core/types.hpp"

namespace lang2manip {

/// One straight segment or circular arc of a BlendedPath, in local arc length u in [0, length].
/// Line: position(u) = origin + u * axisX. Arc: position(u) = origin + radius * (axisX cos(u/r) +
/// axisY sin(u/r)).
struct PathSegment {
  enum class Kind { kLine, kArc };

  Kind kind = Kind::kLine;
  /// Arc length of the path at the segment's start, and the segment's length.
  double start = 0.0;
  double length = 0.0;
  /// Line: its start point. Arc: the circle's centre.
  VectorX origin;
  /// Line: the unit direction. Arc: the unit vector from the centre to the arc's start.
  VectorX axisX;
  /// Arc: the unit tangent at the arc's start (orthogonal to axisX). Empty for a line.
  VectorX axisY;
  /// Arc radius; 0 for a line.
  double radius = 0.0;
  /// The end point, returned exactly at u = length (a waypoint, for a line ending on one).
  VectorX end;
  /// Where it comes from, as an index into BlendedPath::waypoints(): a line lies on the straight
  /// segment from this waypoint to the next; an arc replaces the corner at this waypoint.
  std::size_t waypoint = 0;

  /// Position, first and second derivative with respect to arc length at local u (clamped).
  [[nodiscard]] VectorX position(double u) const;
  [[nodiscard]] VectorX tangent(double u) const;
  [[nodiscard]] VectorX curvature(double u) const;
};

/// Straight segments through the waypoints, each corner replaced by a circular arc tangent to
/// both neighbours that stays within `maxDeviation` (Euclidean, in joint space) of the corner and
/// uses at most half of either adjacent segment. Corners where no arc is used are stop points:
/// a reversal (the direction turns by nearly pi) and every corner when maxDeviation is 0. The
/// path is continuous; its tangent is continuous except at stop points.
/// Immutable after construction; every method is const and thread-safe.
class BlendedPath {
 public:
  /// Waypoints closer than kMinWaypointDistance to the previous kept one are dropped (the last
  /// waypoint replaces the kept point it repeats, so the path ends exactly on it).
  /// Throws InputError (naming the waypoint index) for an empty list, points of different sizes
  /// or of size 0, values that are not finite, or a negative or non-finite maxDeviation.
  BlendedPath(const std::vector<VectorX>& waypoints, double maxDeviation);

  /// The same with a deviation bound per waypoint: cornerDeviations[i] bounds the arc at
  /// waypoints[i] (0 leaves that corner sharp: a stop point); the first and last entries are
  /// unused. A dropped repeated waypoint takes its deviation with it.
  /// Throws InputError as above, and when the sizes differ or a deviation is negative or not
  /// finite.
  BlendedPath(const std::vector<VectorX>& waypoints, const std::vector<double>& cornerDeviations);

  /// Waypoints closer than this (Euclidean) to the previous one are dropped.
  static constexpr double kMinWaypointDistance = 1e-9;
  /// A corner turning by more than pi minus this (rad) is a reversal: the path stops there.
  static constexpr double kReversalAngle = 1e-3;
  /// A corner turning by less than this (rad) is kept as a straight continuation, unblended.
  static constexpr double kMinBlendAngle = 1e-6;

  [[nodiscard]] int dimension() const noexcept { return dimension_; }
  /// Total arc length (0 when every waypoint is the same point).
  [[nodiscard]] double length() const noexcept { return length_; }
  /// The segments in order; empty for a path of length 0.
  [[nodiscard]] const std::vector<PathSegment>& segments() const noexcept { return segments_; }
  /// The waypoints kept (repeated ones dropped); the path starts and ends exactly on them.
  [[nodiscard]] const std::vector<VectorX>& waypoints() const noexcept { return waypoints_; }
  /// The segment holding arc length s (clamped to [0, length()]): at a boundary between two
  /// segments, the later one. Requires a path with at least one segment.
  [[nodiscard]] std::size_t segmentIndex(double s) const noexcept;

  /// Position at arc length s (clamped to [0, length()]).
  [[nodiscard]] VectorX position(double s) const;
  /// First derivative with respect to arc length (a unit vector; zero for a path of length 0).
  /// At a stop point, the derivative of the segment after it.
  [[nodiscard]] VectorX tangent(double s) const;
  /// Second derivative with respect to arc length (the curvature vector: zero on straight
  /// segments, of norm 1/radius towards the centre on arcs).
  [[nodiscard]] VectorX curvature(double s) const;

  /// Arc lengths where the curvature is discontinuous (both ends of every arc), sorted, strictly
  /// inside (0, length()).
  [[nodiscard]] const std::vector<double>& switchingPoints() const noexcept { return switching_; }
  /// Arc lengths of the corners left sharp (reversals; every corner when maxDeviation is 0),
  /// sorted, strictly inside (0, length()): a trajectory must be at rest there. Each equals the
  /// start of a segment exactly.
  [[nodiscard]] const std::vector<double>& stopPoints() const noexcept { return stops_; }

  /// Positions at arc lengths 0, resolution, 2 resolution, ... and length() (so consecutive
  /// positions are at most `resolution` apart along the path, for re-checking it for collisions).
  /// Throws InputError unless resolution is positive and finite, or for more than 10^8 samples.
  [[nodiscard]] std::vector<VectorX> sample(double resolution) const;

 private:
  void addLine(const VectorX& from, const VectorX& to, std::size_t waypoint);
  void addCorner(std::size_t index, double maxDeviation, VectorX& lineStart);

  int dimension_ = 0;
  double length_ = 0.0;
  std::vector<VectorX> waypoints_;
  std::vector<PathSegment> segments_;
  std::vector<double> starts_;  // segments_[i].start, for binary search
  std::vector<double> switching_;
  std::vector<double> stops_;
};

}  // namespace lang2manip
