#pragma once
/// Shared helpers of the execution tests: the built-in desk scenes, symbolic actions written out,
/// and checks that an executed action's motion is continuous and within the joint limits.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "grounding/grounding_test_support.hpp"
#include "lang2manip/execution/execution_verification.hpp"
#include "lang2manip/execution/task_executor.hpp"
#include "lang2manip/planning/jerk_limiting.hpp"
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
    if (settings.limitJerk) {
      EXPECT_EQ(checkJerkLimits(action.trajectory, executor.arm().robotSpace().jointJerkLimits(), kTimingSlack), "") << "step " << action.index + 1;
    }
    previous = action.trajectory.points.back().positions;
  }
  EXPECT_LT((record.finalScene.robot(robot).configuration - previous).cwiseAbs().maxCoeff(), 1e-6);
}

/// The tool follows every Cartesian move's straight line within settings.cartesianDeviation on
/// the trajectory's samples, except within one cartesianStep of the move's ends (where a blend
/// from or into a transit may leave it).
inline void expectCartesianMovesStraight(const TaskExecutor& executor, const ExecutionRecord& record) {
  const ArmContext& arm = executor.arm();
  const ExecutionSettings& settings = arm.settings();
  int checked = 0;
  for (const ActionExecution& action : record.actions) {
    for (std::size_t k = 0; k < action.segments.size() && k < action.segmentEndTimes.size(); ++k) {
      const MotionSegment& segment = action.segments[k];
      if (!segment.planner.empty() || segment.waypoints.size() < 3 || segment.gripperEvent != GripperEvent::kNone) continue;
      const Vector3 from = arm.toolPose(segment.world, segment.waypoints.front()).translation();
      const Vector3 to = arm.toolPose(segment.world, segment.waypoints.back()).translation();
      if ((to - from).norm() < 2.0 * settings.cartesianStep) continue;
      const double begin = k == 0 ? 0.0 : action.segmentEndTimes[k - 1];
      for (const TrajectoryPoint& point : action.trajectory.points) {
        if (point.time < begin || point.time > action.segmentEndTimes[k]) continue;
        const Vector3 tool = arm.toolPose(segment.world, point.positions).translation();
        if ((tool - from).norm() < settings.cartesianStep || (tool - to).norm() < settings.cartesianStep) continue;
        const double along = std::clamp((tool - from).dot(to - from) / (to - from).squaredNorm(), 0.0, 1.0);
        EXPECT_LE((tool - (from + along * (to - from))).norm(), settings.cartesianDeviation + 1e-5)
            << "step " << action.index + 1 << ", " << segment.label << " at " << point.time << " s";
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 20) << "samples of Cartesian moves checked";
}

}  // namespace lang2manip::test
