#pragma once
/// @file What an instruction can say about an object: its name, kind, the nouns it answers to,
/// its colour, size and place. Built from a Scene; the instruction parser grounds noun phrases
/// against these descriptors only.

#include <optional>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/scene.hpp"
#include "lang2manip/symbolic/object_appearance.hpp"

namespace lang2manip {

struct ObjectDescriptor {
  std::string name;
  /// The object's category ("marker", "pen_holder", "desk").
  std::string kind;
  /// Other nouns for it, from its kind: "pen" and "felt tip" for a marker, "rubber" for an
  /// eraser, "cup" and "pot" for a pen holder, "table" for a desk (see kindSynonyms()).
  std::vector<std::string> synonyms;
  /// Colour names: the colour words of its name, else the nearest named colour of its largest
  /// visual.
  std::vector<std::string> colours;
  /// Volume of its bounding box, m^3; size words compare it among candidates.
  double volume = 0.0;
  /// "small", "medium" or "large" by volume among the scene's movable objects (thirds of their
  /// ranking); "large" for an unmovable object bigger than all of them. Size words in
  /// instructions ("the big cup") compare volumes among the candidates instead.
  std::string sizeClass;
  /// Bounding-box extent along x, y, z of the object frame, metres.
  Vector3 dimensions = Vector3::Zero();
  /// Centre of its world bounds in the robot's base frame (x forward, y left), metres.
  Vector3 position = Vector3::Zero();
  /// Its world bounds' corners in the robot's base frame, bounded by an axis-aligned box.
  AlignedBox3 bounds;
  /// The origin of its frame in the robot's base frame, metres.
  Vector3 origin = Vector3::Zero();
  /// Its category from its shape (objectCategory(): "cube", "cylinder", "bowl", ...), empty when
  /// the shape says none; its nouns are among the synonyms when the kind names nothing familiar.
  std::string category{};
  /// "box", "cylinder" or "sphere" when its collision geometry is one such shape; empty otherwise.
  std::string shape;
  /// The yaw of its long side in the robot's base frame, in [0, pi) (see longSideYaw()); none for
  /// a square or round footprint.
  std::optional<double> longSideYaw;
  bool movable = false;
  ObjectRole role = ObjectRole::kNone;
  /// For a container: the size of its cavity (x, y, depth), metres.
  std::optional<Vector3> cavitySize{};
  /// For a support: the part of its top the robot reaches (base frame), what its regions are of
  /// (supportArea()).
  std::optional<AlignedBox3> reachableTop{};
};

/// Descriptors of every object of `scene`, in scene order. Positions are in the base frame of
/// `robot` (the first robot when empty; the world frame when the scene has no robot); reachable
/// tops are of the part its arm `arm` reaches (every arm when empty). Throws InputError when
/// `robot` or `arm` is given but not in the scene.
std::vector<ObjectDescriptor> describeObjects(const Scene& scene, const std::string& robot = "", const std::string& arm = "");



/// Nouns that also name an object of `kind` (the kind's words are matched separately); empty
/// for an unfamiliar kind.
std::vector<std::string> kindSynonyms(const std::string& kind);

}  // namespace lang2manip
