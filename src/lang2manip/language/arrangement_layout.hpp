#pragma once
/// @file Where the members of an arrangement go (internal to the language module): a line, a
/// circle, a triangle, a square or a pyramid laid out on a support's reachable top clear of the other
/// objects, or the members spread out with the fewest moves. Deterministic.

#include <optional>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/symbolic/action.hpp"

namespace lang2manip::language_detail {

/// What an arrangement is laid out from (robot base frame, metres; x and y are used).
struct ArrangementLayoutRequest {
  ArrangementShape shape = ArrangementShape::kLine;
  /// The members' bounds where they stand now, in the goal's order.
  std::vector<AlignedBox3> members;
  /// Whether each member stands on the support now (spread_out leaves those that do in place
  /// when they are far enough from the rest).
  std::vector<bool> onSupport;
  /// Where the members may stand: the support's reachable top.
  AlignedBox3 area;
  /// Where the shape's centre may be (a region of the area; the whole area when none).
  std::optional<AlignedBox3> centreArea;
  /// What must stay clear: the other objects standing on the support, and whether each can be
  /// set aside (a layout over movable ones is the last tried).
  std::vector<AlignedBox3> others;
  std::vector<bool> othersMovable;
  /// A line's direction (unit, x-y).
  Vector3 direction = Vector3::UnitY();
  /// The spacing of neighbouring centres ("10 cm apart"); none: the widest member plus a gap.
  std::optional<double> spacing;
  /// What a circle goes around ("around the bowl"): its centre is that box's and it clears it.
  std::optional<AlignedBox3> around;
  /// spread_out: the least gap between two members' boxes.
  double spreadGap = 0.10;
  /// A line between two objects: their boxes; the members go evenly spaced between their centres.
  std::optional<std::pair<AlignedBox3, AlignedBox3>> between;
};

/// The centre (x, y; z = 0) each member goes to, in the members' order: for a line, in the
/// order they stand along it; for a circle or polygon, the assignment that moves them least; for a
/// pyramid (the largest at the base), z is how far the member's bottom rises above the support. None
/// when no layout fits: `why` then says what it needs.
std::optional<std::vector<Vector3>> layOutArrangement(const ArrangementLayoutRequest& request, std::string& why);

}  // namespace lang2manip::language_detail
