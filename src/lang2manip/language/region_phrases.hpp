#pragma once
/// @file Region phrases of an instruction (internal to the language module): "the top left
/// corner", "the far edge", "the bottom side", "the middle", "the right half", "the upper right
/// quadrant", "the corner closest to the green bowl", each optionally followed by "of the table".
/// "top", "far", "front", "upper" and "back of the room" mean far from the robot (+x); "bottom",
/// "near", "lower" and "back" mean near it; left is +y.

#include <cstddef>
#include <optional>

#include "lang2manip/language/words.hpp"
#include "lang2manip/symbolic/surface_region.hpp"

namespace lang2manip::language_detail {

struct RegionPhrase {
  SurfaceRegion region;
  /// Words read, from the determiner ("the") to the region noun or the last modifier word.
  std::size_t length = 0;
  /// "the corner closest to X" / "farthest from X": the corner is chosen by where X stands; the
  /// words of X start at words[referenceAt].
  bool nearestCorner = false;
  bool farthestCorner = false;
  std::size_t referenceAt = 0;
};

/// The region phrase at words[at] (after its preposition), or nullopt. A phrase that names a
/// corner without saying which ("a corner") is read with depth = side = 0 for the caller to
/// choose; "upper right" alone is a corner.
std::optional<RegionPhrase> matchRegionPhrase(const Words& words, std::size_t at);

/// The length of a preposition that can introduce a region at words[at] ("in", "on", "at", "to",
/// "into", "onto", "toward(s)", "in to", "over to"); 0 when none.
std::size_t regionPreposition(const Words& words, std::size_t at);

}  // namespace lang2manip::language_detail
