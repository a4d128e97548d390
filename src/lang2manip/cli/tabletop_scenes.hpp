#pragma once
/// @file Random tabletop scenes for measuring instruction understanding on scenes nobody tuned
/// to: a built-in robot's desk cleared of its objects, then 3-10 objects drawn from blocks,
/// cylinders and bowls of several sizes, in the colours of the benchmarks' palettes, standing at
/// seeded random places of the part of the desk the arm reaches, none closer than a gap to
/// another. Names follow the benchmarks: "red_block", "blue_bowl", "green_cylinder" (a second
/// object of a kind and colour gets "_2").

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lang2manip/core/random.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// The colour names of the generated objects (Code as Policies' tabletop palette) and their RGB.
struct PaletteColour {
  const char* name;
  double r, g, b;
};
const std::vector<PaletteColour>& tabletopPalette();

/// What to put on the desk.
struct TabletopRequest {
  int blocks = 3;
  int bowls = 0;
  /// The share of bowls drawn round and tapered (a mesh whose cavity is measured, as a user's
  /// bowl model is) rather than square (primitives with a declared cavity).
  double roundBowlShare = 0.5;
  int cylinders = 0;
  /// Colours are drawn without repetition per kind unless a kind needs more than the palette.
  bool distinctColours = true;
  /// Every block of one colour, drawn once (Ravens' "the left red block").
  bool oneBlockColour = false;
  /// Edge of the blocks, metres (each block draws its edge from [blockEdgeMin, blockEdgeMax]).
  double blockEdgeMin = 0.04;
  double blockEdgeMax = 0.04;
  /// Every bowl holds at least this many of the largest blocks side by side.
  int blocksPerBowl = 1;
  /// Clearance kept between the objects' footprints, metres.
  double gap = 0.05;
};

/// `desk` (a built-in desk scene: a support named "desk" and its objects) with every movable or
/// contained object removed and the requested ones added at random places the acting arm
/// reaches (deskReach(), seeded by `random`): bowls of the benchmarks' sizes, or, when 200 draws
/// of those do not fit, scaled down to 40 % of the reach's short side and at most 3 cm apart
/// (YuMi's one arm). Nullopt
/// when the objects do not fit after 200 draws of each.
std::optional<Scene> generateTabletop(const Scene& desk, const TabletopRequest& request, Random& random);

/// The objects of `scene` whose kind is `kind` ("block", "bowl", "cylinder"), in scene order.
std::vector<std::string> objectsOfKind(const Scene& scene, const std::string& kind);

/// The arm a run on `scene` uses unless told otherwise: its first robot's first manipulator
/// (empty without one). Tabletops are generated, and the families checked, in its reach.
std::string actingArm(const Scene& scene);

/// The part of the desk's top the acting arm reaches (base frame). Throws InputError when the
/// scene has no desk it reaches.
AlignedBox3 deskReach(const Scene& scene);

/// The colour word an object was generated with ("red" for "red_block_2").
std::string colourOf(const std::string& object);

}  // namespace lang2manip
