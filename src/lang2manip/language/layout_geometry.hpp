#pragma once
/// @file Geometry of where objects stand, for the sequencer (internal to the language module):
/// free spots to set an object aside, the turn that points an object at another, what goals
/// about places and turns need.

#include <cstddef>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/language/sequencer.hpp"

namespace lang2manip::language_detail {

/// Centres (x, y; z = the area's top) where a footprint of `size` (x, y) fits inside `area`
/// (`gap` from its edges) without coming within `gap` of any box of `occupied` (x and y
/// compared), on a 2 cm grid, nearest to `near` first, each at least 5 cm from those before; at
/// most `wanted` of them.
std::vector<Vector3> freeSpots(const Vector3& size, const AlignedBox3& area, const std::vector<AlignedBox3>& occupied,
                               const Vector3& near, double gap, std::size_t wanted);

/// `box` moved by `by`.
AlignedBox3 shifted(const AlignedBox3& box, const Vector3& by);

/// Throws PlanningError when an at_position, turned, facing or displaced goal cannot be planned:
/// no layout for its object (or target), no position, a turn that leaves the object looking the
/// same (turnSymmetry()), an object without a long side to point with, a displacement that takes
/// the object off the support it stands on.
void validatePoseGoal(const Goal& goal, const SequencingOptions& options);

/// The smaller turn (rad) that makes the long side of `goal.object` point at `goal.target` (or,
/// without a target, lie along the base-frame yaw `goal.angle`); nullopt when where they stand is
/// not in `layout`.
std::optional<double> facingTurn(const std::map<std::string, ObjectLayout>& layout, const Goal& goal);

/// Records in `layout` that `object` now has its origin at `origin`, turned by `turn` about the
/// vertical through it when given (nothing when `object` has no layout).
void moveLayout(std::map<std::string, ObjectLayout>& layout, const std::string& object, const Vector3& origin,
                std::optional<double> turn);

/// How far (m) a position's height may be above where an object stands and still be where it
/// stands; higher, it is put onto what stands there (restingUnder()).
inline constexpr double kRaisedPosition = 0.01;
/// How far (m) an object's top may reach into a spot's bottom and still be what the spot rests on.
inline constexpr double kRestingContact = 0.001;

/// The objects of `objects` (in that order) standing where `spot` is (footprints overlapping, not
/// below it: their tops above its bottom by more than kRestingContact), other than `ignored` and
/// the supports.
std::vector<std::string> standingIn(const std::map<std::string, ObjectLayout>& layout, const AlignedBox3& spot,
                                    const std::vector<std::string>& objects, const std::vector<std::string>& ignored,
                                    const std::set<std::string>& supports);

/// What a body at `spot` rests on: of the objects of `layout` (other than `object`) whose tops are
/// within kRaisedPosition of its bottom, the one whose footprint it overlaps most; none when none.
std::optional<std::string> restingUnder(const std::map<std::string, ObjectLayout>& layout, const AlignedBox3& spot, const std::string& object);

/// What a free spot for `object` must keep clear of: the footprint of every object standing
/// (other than `object`, the `held` one and the supports) and every place an at_position goal of
/// `goals` wants for another object (the held one's too).
std::vector<AlignedBox3> placesTaken(const std::map<std::string, ObjectLayout>& layout, const std::vector<Goal>& goals,
                                     const std::string& object, const std::string& held, const std::set<std::string>& supports);

/// True when the x-y extents of `a` and `b` come within `gap` of each other.
bool footprintsOverlap(const AlignedBox3& a, const AlignedBox3& b, double gap);

}  // namespace lang2manip::language_detail
