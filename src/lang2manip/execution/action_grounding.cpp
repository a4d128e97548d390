#include "lang2manip/execution/action_grounding.hpp"

#include <chrono>

#include "lang2manip/core/error.hpp"
#include "lang2manip/execution/motion_timing.hpp"
#include "lang2manip/symbolic/plan_json.hpp"

namespace lang2manip {

const VectorX& robotConfiguration(const ArmContext& arm, const Scene& world) {
  return world.robot(arm.robotName()).configuration;
}

std::optional<GroundingAttempt> refuse(ActionExecution& record, const std::string& stage, std::string reason) {
  record.stage = stage;
  record.reason = std::move(reason);
  return std::nullopt;
}

const Attachment* heldByRobot(const Scene& world, const std::string& robot) {
  for (const Attachment& attachment : world.attachments()) {
    if (attachment.robot == robot) return &attachment;
  }
  return nullptr;
}

namespace {

/// Adds the work of `result` (found or not) to the counters and times.
void countWork(const MotionResult& result, ExecutionCounters& counters, StageTimes& times) {
  counters.plannerCalls += result.plannerCalls;
  counters.plannerSolved += result.plannerSolved;
  counters.ikCalls += result.ikCalls;
  counters.collisionChecks += result.collisionChecks;
  times.ik += result.ikSeconds;
}

}  // namespace

GroundingAttempt::GroundingAttempt(const ArmContext& arm, Scene start)
    : world(std::move(start)), q(robotConfiguration(arm, world)) {}

bool GroundingAttempt::add(const ArmContext& arm, MotionResult result, ExecutionCounters& counters, StageTimes& times) {
  countWork(result, counters, times);
  if (!result.ok()) {
    stage = result.stage;
    reason = result.reason;
    return false;
  }
  q = result.segment->waypoints.back();
  world.setConfiguration(arm.robotName(), q);
  segments.push_back(std::move(*result.segment));
  return true;
}

bool GroundingAttempt::add(const ArmContext& arm, MotionSegment segment, ExecutionCounters& counters) {
  const SegmentCheck check = checkSegment(arm, segment, arm.settings().verificationResolution);
  counters.collisionChecks += check.checks;
  if (!check.collision.empty()) {
    stage = "motion";
    reason = check.collision;
    return false;
  }
  q = segment.waypoints.back();
  world.setConfiguration(arm.robotName(), q);
  segments.push_back(std::move(segment));
  return true;
}

bool addFirstCartesian(const GroundingContext& c, GroundingAttempt& a, const std::vector<Pose>& targets,
                       const std::string& label, const CartesianAllowance& allowance, StageTimes& times) {
  std::string failures;
  std::string stage;
  for (const Pose& target : targets) {
    MotionResult motion = planCartesian(c.arm, a.world, a.q, target, label, allowance);
    if (motion.ok()) return a.add(c.arm, std::move(motion), c.counters, times);
    countWork(motion, c.counters, times);
    stage = motion.stage;
    failures += (failures.empty() ? "" : "; ") + motion.reason;
  }
  a.stage = stage;
  a.reason = targets.size() == 1 ? failures : "no " + label + " is free: " + failures;
  return false;
}

namespace {

std::optional<GroundingAttempt> groundByType(const GroundingContext& context, const Scene& world,
                                             const SymbolicAction& action, ActionExecution& record) {
  switch (action.type) {
    case ActionType::kPick: return groundPick(context, world, action, record);
    case ActionType::kPlace: return groundPlace(context, world, action, record);
    case ActionType::kMove: return groundMove(context, world, action, record);
    case ActionType::kPush: return groundPush(context, world, action, record);
  }
  record.stage = "precondition";
  record.reason = "unknown action type";
  return std::nullopt;
}

void fail(ActionExecution& record, const std::string& stage, const std::string& reason) {
  record.status = ActionStatus::kFailed;
  record.stage = stage;
  record.reason = reason;
}

/// One point at rest at `q`: the trajectory of an action that had nothing to move.
JointTrajectory restingTrajectory(const PlanningSpace& space, const VectorX& q) {
  JointTrajectory trajectory;
  trajectory.jointNames = space.trajectoryJointNames();
  const VectorX zero = VectorX::Zero(static_cast<Eigen::Index>(trajectory.jointNames.size()));
  trajectory.points.push_back({space.trajectoryPositions(q), zero, zero, 0.0});
  return trajectory;
}

}  // namespace

ActionExecution executeAction(const GroundingContext& context, Scene& world, const SymbolicAction& action,
                              std::size_t index) {
  ActionExecution record;
  record.index = index;
  record.action = action;
  const auto began = std::chrono::steady_clock::now();
  std::optional<GroundingAttempt> done;
  try {
    done = groundByType(context, world, action, record);
  } catch (const InputError& error) {
    fail(record, "precondition", describeAction(action) + ": " + error.what());
    return record;
  } catch (const NotSupportedError& error) {
    fail(record, "precondition", describeAction(action) + ": " + error.what());
    return record;
  }
  record.times.motion = secondsSince(began) - record.times.grasp - record.times.placement - record.times.ik;
  if (!done) {
    record.status = ActionStatus::kFailed;
    return record;
  }
  ActionTiming timing = timeActionMotions(context.arm, done->segments);
  if (timing.trajectory.points.empty()) timing.trajectory = restingTrajectory(context.arm.robotSpace(), done->q);
  context.counters.collisionChecks += timing.collisionChecks;
  record.trajectory = std::move(timing.trajectory);
  record.segmentEndTimes = std::move(timing.segmentEndTimes);
  record.runs = std::move(timing.runs);
  record.quality = timing.quality;
  record.segments = std::move(done->segments);
  record.status = ActionStatus::kSucceeded;
  world = std::move(done->world);
  return record;
}

}  // namespace lang2manip
