#include "lang2manip/collision/collision_checker.hpp"

#include <cmath>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {
namespace {

std::string robotNames(const Scene& scene) {
  std::string names;
  for (const SceneRobot& robot : scene.robots()) names += (names.empty() ? "" : ", ") + robot.name;
  return names.empty() ? "(none)" : names;
}

bool finitePose(const Pose& pose) { return pose.matrix().allFinite(); }

}  // namespace

int CollisionChecker::robotIndex(const std::string& name) const {
  const auto& robots = scene_.robots();
  for (std::size_t r = 0; r < robots.size(); ++r) {
    if (robots[r].name == name) return static_cast<int>(r);
  }
  throw InputError("collision checker: unknown robot '" + name + "'; valid robots: " +
                   robotNames(scene_));
}

std::unique_ptr<CollisionContext> CollisionChecker::makeContext() const { return DoMakeContext(); }

void CollisionChecker::checkRobot(int robot) const {
  if (robot < 0 || robot >= static_cast<int>(scene_.robots().size())) {
    throw InputError("collision checker: no robot with index " + std::to_string(robot) +
                     "; valid robots: " + robotNames(scene_));
  }
}

void CollisionChecker::checkContext(const CollisionContext& context) const {
  if (context.owner() != this) {
    throw InputError("collision checker: the context was made by another checker");
  }
}

void CollisionChecker::checkQ(int robot, const VectorX& q, const std::string& what) const {
  const SceneRobot& sceneRobot = scene_.robots()[static_cast<std::size_t>(robot)];
  sceneRobot.model->checkConfiguration(q, what);
}

bool CollisionChecker::isStateValid(int robot, const VectorX& q, CollisionContext& context) const {
  checkRobot(robot);
  checkContext(context);
  checkQ(robot, q, "configuration");
  return DoIsStateValid(robot, q, context);
}

bool CollisionChecker::isMotionValid(int robot, const VectorX& q0, const VectorX& q1,
                                     double resolution, CollisionContext& context) const {
  checkRobot(robot);
  checkContext(context);
  checkQ(robot, q0, "motion start");
  checkQ(robot, q1, "motion end");
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw InputError("collision checker: motion resolution must be positive and finite, got " +
                     numberText(resolution));
  }
  return DoIsMotionValid(robot, q0, q1, resolution, context);
}

std::vector<bool> CollisionChecker::checkStates(int robot, const std::vector<VectorX>& configurations,
                                                CollisionContext& context) const {
  checkRobot(robot);
  checkContext(context);
  for (std::size_t i = 0; i < configurations.size(); ++i) {
    checkQ(robot, configurations[i], "configuration " + std::to_string(i));
  }
  std::vector<bool> valid(configurations.size(), false);
  DoCheckStates(robot, configurations, valid, context);
  return valid;
}

CollisionReport CollisionChecker::checkState(int robot, const VectorX& q,
                                             const CollisionRequest& request,
                                             CollisionContext& context) const {
  checkRobot(robot);
  WorldState state = sceneState();
  state.configurations[static_cast<std::size_t>(robot)] = q;
  return checkWorld(state, request, context);
}

CollisionReport CollisionChecker::checkWorld(const WorldState& state, const CollisionRequest& request,
                                             CollisionContext& context) const {
  checkContext(context);
  const std::size_t robots = scene_.robots().size();
  if (state.configurations.size() != robots || state.basePoses.size() != robots) {
    throw InputError("collision checker: the world state has " +
                     std::to_string(state.configurations.size()) + " configurations and " +
                     std::to_string(state.basePoses.size()) + " base poses; the scene has " +
                     std::to_string(robots) + " robots (" + robotNames(scene_) + ")");
  }
  for (std::size_t r = 0; r < robots; ++r) {
    checkQ(static_cast<int>(r), state.configurations[r], "configuration");
    if (!finitePose(state.basePoses[r])) {
      throw InputError("collision checker: the base pose of robot '" + scene_.robots()[r].name +
                       "' is not finite");
    }
  }
  return DoCheckWorld(state, request, context);
}

WorldState CollisionChecker::sceneState() const {
  WorldState state;
  for (const SceneRobot& robot : scene_.robots()) {
    state.configurations.push_back(robot.configuration);
    state.basePoses.push_back(robot.basePose);
  }
  return state;
}

}  // namespace lang2manip
