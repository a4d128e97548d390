#pragma once
/// Shared helpers of the collision tests: scenes built from the built-in robots and problems.

#include <memory>
#include <string>

#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/model/urdf_reader.hpp"

namespace lang2manip::test {

/// The built-in robot `name` (with its SRDF).
inline RobotModelPtr builtinRobot(const std::string& name) { return readUrdfFile(builtinRobotUrdf(name)); }

/// A scene holding only robot `name` at its base frame, at the "home" configuration.
inline Scene robotOnlyScene(const std::string& name) {
  Scene scene;
  SceneRobot robot;
  robot.name = name;
  robot.model = builtinRobot(name);
  robot.configuration = robot.model->namedConfiguration("home");
  scene.addRobot(robot);
  return scene;
}

/// The scene of built-in problem `problem` (e.g. "panda_desk").
inline Scene problemScene(const std::string& problem) {
  return readKauthamProblem(resolveProblem(problem)).scene;
}

/// "first – second" names of the colliding pairs of a report, one per line.
inline std::string contactList(const CollisionReport& report) {
  std::string text;
  for (const CollisionContact& contact : report.contacts) {
    text += contact.first + " - " + contact.second + " (" + std::to_string(contact.penetrationDepth) + ")\n";
  }
  return text;
}

}  // namespace lang2manip::test
