#pragma once
/// @file Object-versus-world collision for placement: one object at hypothetical poses against
/// every other object of the scene (exact FCL narrow phase after a bounding-box pre-check).

#include <string>
#include <vector>

#include "lang2manip/collision/fcl_geometry.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// See the file comment. Obstacles are the scene's objects other than the moving one, except
/// objects that are attached to a robot or have collision disabled. Robots are not included
/// (the reachability check covers the robot holding the object). Immutable after construction.
class ObjectCollisionWorld {
 public:
  /// Throws InputError for an unknown object (listing the objects).
  ObjectCollisionWorld(const Scene& scene, const std::string& object);

  /// Names of the obstacles the object would touch or penetrate at `X_WO`, in scene order
  /// (empty when the pose is free).
  [[nodiscard]] std::vector<std::string> collisions(const Pose& X_WO) const;

 private:
  struct Obstacle {
    std::string name;
    std::vector<FclShape> shapes;
    Pose pose;
    AlignedBox3 bounds;
  };
  [[nodiscard]] bool touches(const Obstacle& obstacle, const Pose& X_WO) const;

  SceneObject object_;
  std::vector<FclShape> shapes_;
  std::vector<Obstacle> obstacles_;
};

}  // namespace lang2manip
