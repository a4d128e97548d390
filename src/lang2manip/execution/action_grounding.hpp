#pragma once
/// @file Grounding one symbolic action into motions and executing it in the world:
/// - pick: grasp planning, transit to the pre-grasp pose with the action's planner, Cartesian
///   approach, close the gripper on the object, attach it to the tool frame, Cartesian lift;
/// - place: placement planning for the action's relation or pose, transit holding the object,
///   Cartesian descent, open the gripper, detach it where it comes to rest, Cartesian retreat;
/// - move: transit to a named configuration ("home") or to a tool pose (IK);
/// - push: close the gripper, transit above the contact pose behind the object, Cartesian
///   descent, a straight Cartesian push by the given distance along the given direction with the
///   object carried by the contact, Cartesian retreat upwards.
/// Candidates (grasps, placements, IK solutions) are tried best first until one can be moved to.

#include <cstddef>
#include <string>
#include <vector>

#include "lang2manip/execution/arm_motion.hpp"

namespace lang2manip {

/// A candidate being grounded: its own copy of the world and the motions so far, so that a
/// failed candidate leaves nothing behind.
struct GroundingAttempt {
  Scene world;
  /// The robot's configuration at the end of the last motion (also set in `world`).
  VectorX q;
  std::vector<MotionSegment> segments;
  /// Why the attempt failed: stage and reason.
  std::string stage;
  std::string reason;

  GroundingAttempt(const ArmContext& arm, Scene start);
  /// Appends the motion and moves the robot to its end; records the failure and returns false
  /// when there is none. Counts the work in `counters` and `times`.
  bool add(const ArmContext& arm, MotionResult result, ExecutionCounters& counters, StageTimes& times);
  /// Appends a motion known to be valid up to its collision check, which is done here.
  bool add(const ArmContext& arm, MotionSegment segment, ExecutionCounters& counters);
};

/// What every grounding step needs.
struct GroundingContext {
  const ArmContext& arm;
  ExecutionCounters& counters;
  const StopCondition& stop;
  /// The plan being executed (placements leave room for what it puts in the same place later);
  /// null when actions are executed on their own.
  const Plan* plan = nullptr;
  /// The place that follows a pick, when the grasp chosen first left it no placement: the pick
  /// then tries first the grasps with which planPlacement() finds one (null: the grasp planner's
  /// order).
  const SymbolicAction* placeAfterPick = nullptr;
};

/// Moves the tool in a straight line from the end of `attempt` to the first of `targets` that
/// can be reached that way; records every failure in the attempt when none can.
bool addFirstCartesian(const GroundingContext& context, GroundingAttempt& attempt, const std::vector<Pose>& targets,
                       const std::string& label, const CartesianAllowance& allowance, StageTimes& times);

/// Grounds and executes `action` (number `index` in its plan) starting from `world`, which is
/// updated to the world after it on success and left as it was on failure. Never throws for
/// geometric or kinematic failures or unknown names: they are the record's failure.
ActionExecution executeAction(const GroundingContext& context, Scene& world, const SymbolicAction& action,
                              std::size_t index);

/// The steps of each action type (action_grounding.cpp dispatches to them). Each returns the
/// successful attempt, or fills `record`'s stage and reason and returns nothing.
std::optional<GroundingAttempt> groundPick(const GroundingContext& context, const Scene& world,
                                           const SymbolicAction& action, ActionExecution& record);
std::optional<GroundingAttempt> groundPlace(const GroundingContext& context, const Scene& world,
                                            const SymbolicAction& action, ActionExecution& record);
std::optional<GroundingAttempt> groundMove(const GroundingContext& context, const Scene& world,
                                           const SymbolicAction& action, ActionExecution& record);
std::optional<GroundingAttempt> groundPush(const GroundingContext& context, const Scene& world,
                                           const SymbolicAction& action, ActionExecution& record);

/// The robot's configuration in `world`.
const VectorX& robotConfiguration(const ArmContext& arm, const Scene& world);


/// Records `stage` and `reason` as the action's failure; returns no attempt.
std::optional<GroundingAttempt> refuse(ActionExecution& record, const std::string& stage, std::string reason);

/// The attachment of whatever `robot` holds, or nullptr.
const Attachment* heldByRobot(const Scene& world, const std::string& robot);

}  // namespace lang2manip
