#pragma once
/// @file The symbolic state: facts derived from geometry that plans are validated against and
/// that the offline planner searches over. Computed from a Scene by observeSymbolicState() and
/// updated by the effects of actions.

#include <map>
#include <set>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"

namespace lang2manip {

struct SymbolicState {
  /// Every object of the scene, in scene order.
  std::vector<std::string> objects;
  /// Objects that can be picked up.
  std::set<std::string> movable;
  /// Objects with the container role, and with the support role (tables, desks).
  std::set<std::string> containers;
  std::set<std::string> supports;
  /// object -> the container it is inside.
  std::map<std::string, std::string> inside;
  /// object -> the object it rests on (a support or another object; absent when inside one).
  std::map<std::string, std::string> onTopOf;
  /// object -> its flat top (supportSurface()), for objects others may rest on.
  std::map<std::string, AlignedBox3> flatTops;
  /// support -> the part of its flat top the robot reaches, robot base frame (supportArea()):
  /// what the regions of an on relation are of. Absent when the robot reaches none of it.
  std::map<std::string, AlignedBox3> reachableTops;
  /// object -> why nothing can rest on it (round, tilted, open at the top).
  std::map<std::string, std::string> noFlatTop;
  /// Movable object -> its size (footprint x, y and height): in its own frame when it stands
  /// upright (its frame's z vertical), else of its world bounds.
  std::map<std::string, Vector3> sizes;
  /// The object the robot holds, empty when its gripper is free.
  std::string held;
  /// The robot's current named configuration ("home"), empty when it is elsewhere.
  std::string atConfiguration;
  /// The robot's named arm configurations (SRDF group states that set arm joints), for `move`.
  std::set<std::string> namedConfigurations;

  /// True when nothing rests on `object` (and, for a container, nothing is inside it).
  [[nodiscard]] bool isClear(const std::string& object) const;
  /// The objects resting on or inside `object`.
  [[nodiscard]] std::vector<std::string> objectsOn(const std::string& object) const;
  [[nodiscard]] bool hasObject(const std::string& object) const;
};

}  // namespace lang2manip

namespace lang2manip {

class Scene;

/// Tolerances of the geometric tests behind observeSymbolicState().
struct SymbolicStateTolerances {
  /// How far an object's bottom may be from a support's top for "on", metres.
  double contactGap = 0.015;
  /// How far below a cavity's floor an object's centre may be and still count as "in", metres.
  double cavityMargin = 0.01;
  /// How far each arm joint may be from a named configuration's value for atConfiguration,
  /// radians (or metres for prismatic joints).
  double configurationTolerance = 1e-3;
};

/// The symbolic state of `scene` from geometry: "in" when an object's centre lies inside a
/// container's cavity, "on" when its bottom rests on the top of the highest object under its
/// centre, "held" from the scene's attachments. atConfiguration is the first named state of the
/// robot's SRDF whose arm joints all match the robot's configuration within tolerance (every
/// group state of that name must match, so "home" of a two-armed robot covers both arms);
/// named states that set only gripper joints ("open", "close") are not configurations. The
/// robot is `robot`, or the scene's first robot when empty; a scene without robots leaves
/// atConfiguration empty. reachableTops are of the part its arm `arm` reaches (every arm when
/// empty). Throws InputError for an unknown robot or arm name.
SymbolicState observeSymbolicState(const Scene& scene, const SymbolicStateTolerances& tolerances = {},
                                   const std::string& robot = {}, const std::string& arm = {});

}  // namespace lang2manip
