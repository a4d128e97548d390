#include "lang2manip/execution/action_grounding.hpp"

#include <chrono>

#include "lang2manip/core/error.hpp"
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

/// When each segment ends in `trajectory`, which passes through every waypoint in order: the time
/// of the segment's last waypoint (a segment without waypoints ends where the previous one did).
std::vector<double> segmentEndTimes(const JointTrajectory& trajectory, const std::vector<MotionSegment>& segments) {
  std::vector<double> ends;
  std::size_t point = 0;
  double end = 0.0;
  for (const MotionSegment& segment : segments) {
    for (std::size_t p = point; !segment.waypoints.empty() && p < trajectory.points.size(); ++p) {
      if ((trajectory.points[p].positions - segment.waypoints.back()).cwiseAbs().maxCoeff() <= 1e-9) {
        point = p;
        end = trajectory.points[p].time;
        break;
      }
    }
    ends.push_back(end);
  }
  return ends;
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
  std::vector<VectorX> waypoints;
  for (const MotionSegment& segment : done->segments) {
    waypoints.insert(waypoints.end(), segment.waypoints.begin(), segment.waypoints.end());
  }
  if (waypoints.empty()) waypoints.push_back(done->q);
  record.trajectory = context.arm.timeParameterize(waypoints);
  record.segmentEndTimes = segmentEndTimes(record.trajectory, done->segments);
  record.segments = std::move(done->segments);
  record.status = ActionStatus::kSucceeded;
  world = std::move(done->world);
  return record;
}

}  // namespace lang2manip
