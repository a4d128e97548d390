#pragma once
/// @file From goals to a symbolic plan: searches for an order of the goals, and the actions
/// each needs (pick, place, push, move), that respects the preconditions of the symbolic state:
/// one free gripper, nothing on or in an object that is picked, a clear top to stack on, room
/// in a container. Objects in the way are moved to the support first; an object standing where
/// another must go is set aside on a free spot of its support (the buffer placement of task and
/// motion planning); a turn is a pick and a place where the object stood, turned (in several
/// steps with regrasps when the repair asks for it). Deterministic.

#include <map>
#include <optional>
#include <string>

#include "lang2manip/language/instruction.hpp"
#include "lang2manip/symbolic/action.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"

namespace lang2manip {

/// Where an object stands, in the robot's base frame: what goals about places and turns are
/// planned with.
struct ObjectLayout {
  /// The object frame's origin and orientation.
  Vector3 origin = Vector3::Zero();
  Quaternion orientation = Quaternion::Identity();
  /// Its world bounds' corners, bounded by an axis-aligned box.
  AlignedBox3 bounds;
  /// The yaw of its long side (see longSideYaw()); none for a square or round footprint.
  std::optional<double> longSideYaw;
  /// The smallest turn about the vertical that leaves it looking the same (see turnSymmetry()).
  double turnSymmetry = 2.0 * 3.14159265358979323846;
  /// Set once the plan puts the object somewhere by a relation (the grounding chooses where): its
  /// size and orientation stay known, its place does not (it takes no place from others).
  bool placeUnknown = false;
};

struct SequencingOptions {
  /// container -> floor area of its cavity, m^2; a container not listed has unlimited room.
  std::map<std::string, double> containerFloorArea;
  /// object -> the smallest cross-section it can be put into a container with, m^2.
  std::map<std::string, double> objectFootprint;
  /// object -> where it stands (every object of the scene), for at_position, turned and facing
  /// goals and for setting objects aside; goals of those kinds need it.
  std::map<std::string, ObjectLayout> layout;
  /// support -> its flat top, base frame: where objects in the way are set aside.
  std::map<std::string, AlignedBox3> supportAreas;
  /// Clearance kept around other objects, and around the places goals want, when setting one
  /// aside (room for the fingers of a gripper placing next to it), metres.
  double asideGap = 0.06;
  /// object -> how many free spots to pass over when setting it aside (those a repair found
  /// failing), and in how many pick-and-place steps to turn it (a regrasp between steps).
  std::map<std::string, int> skippedSpots;
  std::map<std::string, int> turnSteps;
  /// Orders of goals tried before giving up.
  int maxOrdersTried = 5000;
};

/// A plan going through `specification.steps` (the goals when there are no steps) from `state`,
/// in the instruction's order when that
/// works, else in the first order (in lexicographic order of goal indices) that does. A goal
/// already true is skipped; a goal later undone by the instruction itself (holding the marker,
/// then putting it in the holder; going home, then moving on) only has to hold when it is
/// reached. Actions carry the requested grasps and planners. Throws PlanningError naming the
/// object for an unknown or unmovable object, and when no order achieves every goal.
Plan sequenceGoals(const TaskSpecification& specification, const SymbolicState& state,
                   const SequencingOptions& options = {});

}  // namespace lang2manip
