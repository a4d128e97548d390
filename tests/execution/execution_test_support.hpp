#pragma once
/// Shared helpers of the execution tests: the built-in desk scenes, symbolic actions written out,
/// and checks that an executed action's motion is continuous and within the joint limits.

#include <gtest/gtest.h>

#include <string>

#include "grounding/grounding_test_support.hpp"
#include "lang2manip/execution/task_executor.hpp"

namespace lang2manip::test {

/// Wall-clock budgets are those of an optimized build; sanitized builds run about ten times
/// slower.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitizedBuild = true;
#else
constexpr bool kSanitizedBuild = false;
#endif

/// A box object (see boxObject()) that is fixed in place.
inline SceneObject fixedBox(const std::string& name, const Vector3& size, const Vector3& bottomCentre) {
  SceneObject object = boxObject(name, size, bottomCentre);
  object.movable = false;
  return object;
}

inline ExecutionSettings testSettings(const std::string& manipulator = {}) {
  ExecutionSettings settings;
  settings.manipulator = manipulator;
  settings.seed = 3;
  if (kSanitizedBuild) {
    settings.planningTimeSeconds *= 10.0;
    settings.reach.ikTimeoutSeconds *= 10.0;
  }
  return settings;
}

inline SymbolicAction pickAction(const std::string& object, GraspDirection grasp = GraspDirection::kAuto) {
  SymbolicAction action;
  action.type = ActionType::kPick;
  action.object = object;
  action.refinements.grasp = grasp;
  return action;
}

inline SymbolicAction placeAction(const std::string& object, SpatialRelation relation, const std::string& target) {
  SymbolicAction action;
  action.type = ActionType::kPlace;
  action.object = object;
  action.params.relation = relation;
  action.params.target = target;
  return action;
}

inline SymbolicAction moveHomeAction() {
  SymbolicAction action;
  action.type = ActionType::kMove;
  action.params.configuration = "home";
  return action;
}

inline SymbolicAction moveToAction(const Vector3& positionInBase) {
  SymbolicAction action;
  action.type = ActionType::kMove;
  action.params.position = positionInBase;
  return action;
}

inline SymbolicAction pushAction(const std::string& object, const Vector3& direction, double distance) {
  SymbolicAction action;
  action.type = ActionType::kPush;
  action.object = object;
  action.params.direction = direction;
  action.params.distance = distance;
  return action;
}

inline Plan planOf(std::vector<SymbolicAction> actions) {
  Plan plan;
  plan.actions = std::move(actions);
  return plan;
}

/// Each succeeded action's trajectory starts where the previous one ended (the robot's start
/// for the first), is continuous between its points and within the velocity limits.
inline void expectContinuousMotion(const TaskExecutor& executor, const ExecutionRecord& record) {
  const std::string& robot = executor.arm().robotName();
  VectorX previous = executor.initialScene().robot(robot).configuration;
  const VectorX velocity = executor.initialScene().robot(robot).model->velocityLimits();
  for (const ActionExecution& action : record.actions) {
    if (action.status != ActionStatus::kSucceeded) continue;
    ASSERT_GE(action.trajectory.points.size(), 1u) << action.index;
    EXPECT_LT((action.trajectory.points.front().positions - previous).cwiseAbs().maxCoeff(), 1e-6) << "step " << action.index + 1;
    for (std::size_t i = 1; i < action.trajectory.points.size(); ++i) {
      const TrajectoryPoint& a = action.trajectory.points[i - 1];
      const TrajectoryPoint& b = action.trajectory.points[i];
      ASSERT_GT(b.time, a.time - 1e-12);
      EXPECT_LE((b.velocities.cwiseAbs() - velocity).maxCoeff(), 1e-6) << "step " << action.index + 1 << " point " << i;
    }
    previous = action.trajectory.points.back().positions;
  }
  EXPECT_LT((record.finalScene.robot(robot).configuration - previous).cwiseAbs().maxCoeff(), 1e-6);
}

}  // namespace lang2manip::test
