#pragma once
/// @file What the objects of a scene are for, when their models do not say (Kautham's obstacles
/// carry no <lang2manip_object> element): supports and containers from their shape, movable
/// objects from where they rest and whether a gripper of the scene could hold them; and the
/// user's overrides (--movable, --fixed).

#include <optional>
#include <string>
#include <vector>

#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// The user's word on which objects move.
struct ObjectSemanticsOverrides {
  std::vector<std::string> movable;
  std::vector<std::string> fixed;
};

/// What was decided for one object, and why (for `show` and `observe`).
struct ObjectSemanticsDecision {
  std::string object;
  bool movable = false;
  ObjectRole role = ObjectRole::kNone;
  SemanticsSource source = SemanticsSource::kGiven;
  std::string reason;
};

/// For every object whose semantics are SemanticsSource::kInferred:
/// - container: a body whose top is open over a hollow at least 40% of its height deep, walled
///   on all four sides (found by probing its collision geometry); its cavity is that hollow;
/// - support: a wide flat body (both horizontal extents >= 0.3 m, not taller than wide);
/// - movable: held by a robot at the start (Kautham's InitialAttachedObstacle), or not a support,
///   resting on another object (bottom within kSupportTolerance of its top) and narrow enough
///   (its smaller horizontal extent) for the widest-opening gripper of the scene's robots (none
///   without a gripper).
/// Then `overrides` mark objects movable or fixed (source kUser). Throws InputError for a name
/// the scene does not have (listing them) and for a name in both lists.
/// The hollow of an open-topped body, measured by probing its collision geometry (object frame):
/// as deep as the free column under the middle of its top, walled on all four sides, and the box
/// of it that holds the most (a round or tapered bowl's floor raised to where its walls are wide
/// enough; see object_semantics.cpp). Nullopt when the body has no such hollow.
std::optional<AlignedBox3> measuredCavity(const SceneObject& object);

std::vector<ObjectSemanticsDecision> inferObjectSemantics(Scene& scene, const ObjectSemanticsOverrides& overrides = {});

}  // namespace lang2manip
