#pragma once
/// @file What the instruction families share (internal to the cli module): drawing words, the
/// checks of final worlds, and reference plans.

#include <optional>
#include <string>
#include <vector>

#include "lang2manip/cli/instruction_families.hpp"
#include "lang2manip/symbolic/surface_region.hpp"

namespace lang2manip::families {

/// A region as the benchmarks name it ("top left corner", "bottom side") and what it is.
struct RegionWords {
  const char* words;
  SurfaceRegion region;
};
/// CaP's corners and sides.
const std::vector<RegionWords>& cornersAndSides();
const std::vector<RegionWords>& corners();

/// One of `items`, drawn with `random`.
template <typename T>
const T& drawOne(const std::vector<T>& items, Random& random) {
  return items[static_cast<std::size_t>(random.uniform(0.0, static_cast<double>(items.size()) - 1e-9))];
}
/// A whole number in [low, high].
int drawCount(int low, int high, Random& random);

/// Centre of an object's bounds in the robot's base frame.
Vector3 centreInBase(const Scene& scene, const std::string& object);

/// "red" -> "red block" words of an object's name ("red_block_2" -> "red block").
std::string spoken(const std::string& object);

/// How many blocks of edge `edge` stand side by side, 1 cm apart and clear of the walls by
/// placement's margin, on the floor of `bowl`'s cavity.
int blocksHeld(const Scene& scene, const std::string& bowl, double edge);

/// True when no bowl of `scene` stands in `region` of the desk's reachable part (a region a bowl
/// takes has no room for a block, and an instance asking for it is no test of understanding).
bool bowlsClearOf(const Scene& scene, const SurfaceRegion& region);

/// True when a footprint of `size` (x, y) centred at `centre` (base frame) keeps `clearance` from
/// the footprint of every object of `scene` that is not a support nor in `ignore`.
bool footprintClear(const Scene& scene, const Vector3& centre, const Vector3& size, double clearance,
                    const std::vector<std::string>& ignore);

/// How many blocks of edge `edge` stand in `region` of the desk's reachable part at once, as
/// placement puts them (centres in the region, footprints kRegionEdgeMargin inside the reach,
/// 2 cm apart, 3 cm clear of the bowls): a greedy packing on a 5 mm grid, so at most that many.
int blocksFitting(const Scene& scene, const SurfaceRegion& region, double edge);

using Check = std::function<GoalCheck(const Scene& final, const Scene& initial)>;

/// Every goal holds (checkGoalInScene with the initial scene).
Check allOf(std::vector<Goal> goals);
/// `object` `relation` `target` (and in `region` of it).
Goal relationGoal(const std::string& object, SpatialRelation relation, const std::string& target,
                  std::optional<SurfaceRegion> region = std::nullopt);
/// The objects form one tower: one of them stands on the desk (in `region`, when given), each
/// other on exactly one of them, none with two on it.
Check tower(std::vector<std::string> objects, std::optional<SurfaceRegion> region = std::nullopt);
/// Each object on the desk in a corner of its own.
Check differentCorners(std::vector<std::string> objects);
/// Each object in a container whose colour differs from its own.
Check mismatchedContainers(std::vector<std::string> objects, std::vector<std::string> containers);
/// Each object in one of `containers` (any of them: "in a green bowl").
Check inAnyOf(std::vector<std::string> objects, std::vector<std::string> containers);
/// The objects' centres on one line (within 2 cm) along base-frame `heading` (0 = x, pi/2 = y,
/// within 20 degrees), each at least its width from the next, all on the desk.
Check inLine(std::vector<std::string> objects, double heading);
/// `object` on the desk beside `reference` on the side of `relation`, the gap between their
/// boxes within [least, most] metres.
Check besideWithin(std::string object, SpatialRelation relation, std::string reference, double least, double most);

/// pick `object`, place it `relation` `target` (in `region`).
void addPickPlace(Plan& plan, const std::string& object, SpatialRelation relation, const std::string& target,
                  std::optional<SurfaceRegion> region = std::nullopt);
/// pick `object`, place it with its frame's origin at `position` (base frame).
void addPickPlaceAt(Plan& plan, const std::string& object, const Vector3& position);

/// `make`, refusing instances whose check already holds on the scene as drawn.
std::function<std::optional<FamilyInstance>(const Scene&, Random&)> notYetDone(std::optional<FamilyInstance> (*make)(const Scene&, Random&));

/// The arrangement families (arrangement_families.cpp): lines along an edge, circles,
/// triangles and squares, blocks spread out.
std::vector<InstructionFamily> arrangementFamilies();

/// The families of VIMA-Bench and LIBERO that pick and place can do (peer_families.cpp).
std::vector<InstructionFamily> peerFamilies();

}  // namespace lang2manip::families
