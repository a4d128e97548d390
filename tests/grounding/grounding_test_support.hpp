#pragma once
/// Shared helpers of the grounding tests: built-in desk scenes with an exact checker and the
/// default IK solver, cached per problem (building a checker samples its collision matrix).

#include <map>
#include <memory>
#include <string>

#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/grounding/reachability.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"

namespace lang2manip::test {

inline Scene deskScene(const std::string& robot) {
  return readKauthamProblem(resolveProblem(robot + "_desk")).scene;
}

/// The robot's desk scene with the desk alone on it (marker, eraser and holder taken away).
inline Scene emptyDeskScene(const std::string& robot) {
  Scene scene = deskScene(robot);
  for (const char* object : {"marker", "eraser", "holder"}) scene.removeObject(object);
  return scene;
}

/// A reachability checker for `scene` (robot arm `manipulator`), seeded, reusing the collision
/// matrices computed for the robot's desk problem.
/// `ikTimeoutSeconds`: IK's time budget per pose; rankings are deterministic only while IK ends
/// by finding its solutions rather than by running out of time.
inline ReachabilityChecker reachFor(const std::string& robot, Scene scene, const std::string& manipulator = {},
                                    double ikTimeoutSeconds = ReachSettings{}.ikTimeoutSeconds) {
  static std::map<std::string, std::shared_ptr<const FclCollisionChecker>> base;
  auto& checker = base[robot];
  if (!checker) checker = std::make_shared<const FclCollisionChecker>(deskScene(robot));
  static const std::shared_ptr<const IkSolver> ik = makeIkSolver(defaultIkSolverName());
  ReachSettings settings;
  settings.seed = 7;
  settings.ikTimeoutSeconds = ikTimeoutSeconds;
  const ReachabilityChecker prototype(checker, ik, {}, manipulator, settings);
  return prototype.withScene(std::move(scene));
}

/// A box-shaped movable object resting at world (x, y, z) (its bottom face centre).
inline SceneObject boxObject(const std::string& name, const Vector3& size, const Vector3& bottomCentre) {
  SceneObject object;
  object.name = name;
  object.kind = name;
  object.movable = true;
  Shape shape;
  shape.geometry = Box{size};
  shape.origin.translation() = Vector3(0, 0, size.z() / 2.0);
  object.collisions.push_back(shape);
  object.pose.translation() = bottomCentre;
  return object;
}

}  // namespace lang2manip::test
