#pragma once
/// Shared helpers of the execution tests: the built-in desk scenes, symbolic actions written out,
/// and checks that an executed action's motion is continuous and within the joint limits.

#include <gtest/gtest.h>

#include <string>

#include "grounding/grounding_test_support.hpp"
#include "lang2manip/execution/execution_verification.hpp"
#include "lang2manip/execution/task_executor.hpp"
#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/symbolic/repair_loop.hpp"

namespace lang2manip::test {

/// Wall-clock budgets are those of an optimized build; sanitized builds run about ten times
/// slower.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitizedBuild = true;
#else
constexpr bool kSanitizedBuild = false;
#endif

/// A task run by the offline planner through the repair loop, and its last execution verified.
struct OfflineRun {
  RepairResult repair;
  ExecutionVerification verification;
};

/// `task` planned offline with repair on `executor`'s scene; the last execution is verified against
/// the goals the instruction states.
inline OfflineRun runOffline(TaskExecutor& executor, const std::string& task) {
  const Scene& scene = executor.initialScene();
  OfflineTaskPlanner planner;
  PlanningRequest request;
  request.task = task;
  request.scene = &scene;
  request.robot = executor.arm().robotName();
  OfflineRun run;
  run.repair = planWithRepair(planner, request, &executor, RepairOptions{}, StopCondition::never());
  if (!executor.executions().empty()) {
    const std::vector<Goal> goals = understandInstruction(task, describeObjects(scene, request.robot)).goals;
    run.verification = verifyExecution(executor.arm(), scene, executor.lastExecution(), goals);
  }
  return run;
}

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

/// Relative slack of limit checks on time-optimal samples (see motion_timing.cpp).
constexpr double kTimingSlack = 2e-3;

/// Each succeeded action's trajectory starts where the previous one ended (the robot's start
/// for the first), has strictly increasing times, and every sample (not only the waypoints) is
/// within the scaled velocity and acceleration limits.
inline void expectContinuousMotion(const TaskExecutor& executor, const ExecutionRecord& record) {
  const std::string& robot = executor.arm().robotName();
  const ExecutionSettings& settings = executor.arm().settings();
  VectorX previous = executor.initialScene().robot(robot).configuration;
  for (const ActionExecution& action : record.actions) {
    if (action.status != ActionStatus::kSucceeded) continue;
    ASSERT_GE(action.trajectory.points.size(), 1u) << action.index;
    EXPECT_LT((action.trajectory.points.front().positions - previous).cwiseAbs().maxCoeff(), 1e-6) << "step " << action.index + 1;
    EXPECT_EQ(checkTrajectoryLimits(executor.arm().robotSpace(), action.trajectory, kTimingSlack, settings.velocityScaling,
                                    settings.accelerationScaling),
              "")
        << "step " << action.index + 1;
    previous = action.trajectory.points.back().positions;
  }
  EXPECT_LT((record.finalScene.robot(robot).configuration - previous).cwiseAbs().maxCoeff(), 1e-6);
}

}  // namespace lang2manip::test
