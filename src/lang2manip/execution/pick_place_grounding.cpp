// Pick and place (see action_grounding.hpp).

#include <algorithm>
#include <chrono>
#include <cmath>

#include "lang2manip/execution/action_grounding.hpp"
#include "lang2manip/grounding/object_geometry.hpp"

namespace lang2manip {
namespace {

/// The gripper is opened before a transit when it is farther than this from the wanted gap (m).
constexpr double kWidthTolerance = 1e-4;

/// True for a grasp failure of the object's shape (too wide, too narrow, no candidate fits),
/// which no other IK seed changes.
bool fitsNoGrasp(GraspFailure failure) {
  return failure == GraspFailure::kTooWide || failure == GraspFailure::kNotGraspable || failure == GraspFailure::kNoCandidate;
}

void countReach(const ReachabilityChecker& reach, ExecutionCounters& counters) {
  counters.ikCalls += reach.statistics().ikCalls;
  counters.collisionChecks += reach.statistics().collisionChecks;
}

/// Where the IK searches of grasps and placements start: the current configuration, then the
/// arm at "home" (a second chance for arms parked far from their workspace, or with IK branches
/// that a far seed does not reach).
std::vector<VectorX> ikSeeds(const ArmContext& arm, const Scene& world) {
  std::vector<VectorX> seeds{robotConfiguration(arm, world)};
  if (arm.homeArm()) {
    const VectorX home = arm.withArm(seeds.front(), *arm.homeArm());
    if ((home - seeds.front()).cwiseAbs().maxCoeff() > 1e-3) seeds.push_back(home);
  }
  return seeds;
}

std::optional<GroundingAttempt> tryPick(const GroundingContext& c, const Scene& world, const GraspCandidate& grasp,
                                        const SymbolicAction& action, ActionExecution& record) {
  const ArmContext& arm = c.arm;
  const std::string& name = grasp.object;
  GroundingAttempt a(arm, world);
  if (std::abs(arm.gripperWidth(a.q) - grasp.opening) > kWidthTolerance &&
      !a.add(arm, gripperMotion(arm, a.world, a.q, grasp.opening, "open gripper for " + name), c.counters)) {
    return a;
  }
  if (!a.add(arm, planTransit(arm, a.world, a.q, grasp.preGraspSolutions, action.planner, "transit to pre-grasp of " + name, c.stop),
             c.counters, record.times)) {
    return a;
  }
  if (!a.add(arm, planCartesian(arm, a.world, a.q, grasp.graspPose, "approach " + name, fingersMayTouch(arm, name)), c.counters,
             record.times)) {
    return a;
  }
  if (!a.add(arm, closeGripperOn(arm, a.world, a.q, name, "close gripper on " + name), c.counters, record.times)) return a;
  const SceneObject* support = currentSupport(a.world, a.world.object(name), kSupportTolerance);
  const Pose X_GO = arm.toolPose(a.world, a.q).inverse() * a.world.object(name).pose;
  a.world.attach({name, arm.robotName(), arm.gripper().toolFrame, arm.gripper().graspFrame * X_GO});
  CartesianAllowance leave;
  if (support != nullptr) leave.allowedContacts.emplace_back(name, support->name);
  a.add(arm, planCartesian(arm, a.world, a.q, grasp.postGraspPose, "lift " + name, leave), c.counters, record.times);
  return a;
}

/// After a release: back along the approach axis, else straight up, else back and up.
void retreat(const GroundingContext& c, GroundingAttempt& a, const PlacementCandidate& place, ActionExecution& record) {
  const Vector3 back = place.retreatPose.translation() - place.placePose.translation();
  const Pose up = Pose(Eigen::Translation3d(Vector3::UnitZ() * back.norm())) * place.placePose;
  const Pose backAndUp = Pose(Eigen::Translation3d((back + Vector3::UnitZ() * back.norm()) * std::sqrt(0.5))) * place.placePose;
  addFirstCartesian(c, a, {place.retreatPose, up, backAndUp}, "retreat from " + place.object, fingersMayTouch(c.arm, place.object),
                    record.times);
}

std::optional<GroundingAttempt> tryPlace(const GroundingContext& c, const Scene& world, const PlacementCandidate& place,
                                         const SymbolicAction& action, ActionExecution& record) {
  const ArmContext& arm = c.arm;
  const std::string& name = place.object;
  GroundingAttempt a(arm, world);
  if (!a.add(arm, planTransit(arm, a.world, a.q, place.prePlaceSolutions, action.planner, "transit holding " + name, c.stop),
             c.counters, record.times)) {
    return a;
  }
  if (!a.add(arm, planCartesian(arm, a.world, a.q, place.placePose, "lower " + name), c.counters, record.times)) return a;
  MotionSegment release = gripperMotion(arm, a.world, a.q, place.releaseOpening, "release " + name);
  release.gripperEvent = GripperEvent::kRelease;
  if (!a.add(arm, std::move(release), c.counters)) return a;
  a.world.detach(name, place.restingPose);
  retreat(c, a, place, record);
  return a;
}

/// Tries `candidates` best first with `attempt`; the first success, or the failures joined.
template <typename Candidate, typename Attempt>
std::optional<GroundingAttempt> firstThatMoves(const GroundingContext& c, const std::vector<Candidate>& candidates, int limit,
                                               const std::string& what, ActionExecution& record, Attempt attempt) {
  std::string failures;
  const std::size_t count = std::min(candidates.size(), static_cast<std::size_t>(limit));
  for (std::size_t i = 0; i < count; ++i) {
    if (c.stop.shouldStop()) return refuse(record, "motion", what + ": stopped before a candidate could be executed");
    std::optional<GroundingAttempt> a = attempt(candidates[i]);
    if (a && a->stage.empty()) {
      record.choice = candidates[i].label;
      return a;
    }
    record.stage = a ? a->stage : "motion";
    failures += "; [" + candidates[i].label + "] " + (a ? a->reason : std::string("failed"));
  }
  record.reason = what + ": none of the " + std::to_string(count) + " best candidates could be executed" + failures;
  return std::nullopt;
}

/// The objects `plan` places in the same relation to the same target after action `index`.
std::vector<std::string> placedAfter(const Plan* plan, std::size_t index, const SymbolicAction& action) {
  std::vector<std::string> later;
  if (plan == nullptr || !action.params.relation) return later;
  for (std::size_t i = index + 1; i < plan->actions.size(); ++i) {
    const SymbolicAction& next = plan->actions[i];
    if (next.type == ActionType::kPlace && next.params.relation == action.params.relation &&
        next.params.target == action.params.target && next.object != action.object) {
      later.push_back(next.object);
    }
  }
  return later;
}

/// `grasps` with those that leave `place` a placement first (in the order of the placements
/// found), then the others; as they were when none does.
std::vector<GraspCandidate> graspsForPlace(const GroundingContext& c, const ReachabilityChecker& reach, const std::vector<GraspCandidate>& grasps,
                                           const SymbolicAction& place, const VectorX& seed, std::size_t placeIndex, ActionExecution& record) {
  const auto began = std::chrono::steady_clock::now();
  PlacementRequest request;
  request.object = place.object;
  request.target = placementTargetFromParams(place.params);
  for (const GraspCandidate& grasp : grasps) request.grasps.push_back(grasp.objectToGripper);
  request.seed = seed;
  request.placedAfter = placedAfter(c.plan, placeIndex, place);
  request.settings = c.arm.settings().placement;
  request.settings.seed = c.arm.settings().seed;
  const PlacementPlan places = planPlacement(reach, request);
  ++c.counters.placementPlans;
  record.times.placement += secondsSince(began);
  std::vector<GraspCandidate> ordered;
  std::vector<bool> taken(grasps.size(), false);
  for (const PlacementCandidate& candidate : places.candidates) {
    if (candidate.graspIndex < grasps.size() && !taken[candidate.graspIndex]) {
      taken[candidate.graspIndex] = true;
      ordered.push_back(grasps[candidate.graspIndex]);
    }
  }
  for (std::size_t g = 0; g < grasps.size(); ++g) {
    if (!taken[g]) ordered.push_back(grasps[g]);
  }
  return ordered;
}

}  // namespace

std::optional<GroundingAttempt> groundPick(const GroundingContext& c, const Scene& world, const SymbolicAction& action,
                                           ActionExecution& record) {
  const ArmContext& arm = c.arm;
  const SceneObject& object = world.object(action.object);
  if (!arm.gripper().hasGripper()) return refuse(record, "precondition", noGripperReason(arm.model(), arm.gripper(), "pick " + object.name));
  if (world.findAttachment(object.name) != nullptr) return refuse(record, "precondition", object.name + " is already held");
  if (const Attachment* held = heldByRobot(world, arm.robotName())) {
    return refuse(record, "precondition", "cannot pick " + object.name + ": the gripper already holds " + held->object);
  }
  const ReachabilityChecker reach = arm.reachIn(world);
  if (std::string far = reach.beyondReach(object.name); !far.empty()) return refuse(record, "grasp", "pick " + object.name + ": " + far);
  for (const VectorX& seed : ikSeeds(arm, world)) {
    const auto began = std::chrono::steady_clock::now();
    GraspRequest request;
    request.object = object.name;
    request.direction = action.refinements.grasp;
    request.seed = seed;
    request.settings = arm.settings().grasp;
    const GraspPlan grasps = makeGraspPlanner(arm.settings().graspPlanner)->plan(reach, request);
    ++c.counters.graspPlans;
    record.times.grasp += secondsSince(began);
    if (!grasps.success()) {
      refuse(record, "grasp", grasps.reason);
      // No grasp of any direction fits the object's shape: no other seed changes that.
      record.objectUngraspable = request.direction == GraspDirection::kAuto && fitsNoGrasp(grasps.failure);
      if (record.objectUngraspable) break;
      continue;
    }
    const std::vector<GraspCandidate> candidates =
        c.placeAfterPick ? graspsForPlace(c, reach, grasps.candidates, *c.placeAfterPick, seed, record.index + 1, record) : grasps.candidates;
    auto done = firstThatMoves(c, candidates, arm.settings().maxGraspAttempts, "pick " + object.name, record,
                               [&](const GraspCandidate& grasp) { return tryPick(c, world, grasp, action, record); });
    if (done) {
      countReach(reach, c.counters);
      return done;
    }
  }
  countReach(reach, c.counters);
  return std::nullopt;
}


std::optional<GroundingAttempt> groundPlace(const GroundingContext& c, const Scene& world, const SymbolicAction& action,
                                            ActionExecution& record) {
  const ArmContext& arm = c.arm;
  const SceneObject& object = world.object(action.object);
  const Attachment* held = world.findAttachment(object.name);
  if (held == nullptr || held->robot != arm.robotName()) {
    return refuse(record, "precondition", "cannot place " + object.name + ": it is not held; pick it first");
  }
  const ReachabilityChecker reach = arm.reachIn(world);
  const PlacementTarget target = placementTargetFromParams(action.params);
  if (target.relation == SpatialRelation::kIn && world.findObject(target.target) != nullptr) {
    if (std::string far = reach.beyondReach(target.target); !far.empty()) {
      return refuse(record, "placement", "place " + object.name + " in " + target.target + ": " + far);
    }
  }
  for (const VectorX& seed : ikSeeds(arm, world)) {
    const auto began = std::chrono::steady_clock::now();
    PlacementRequest request;
    request.object = object.name;
    request.target = placementTargetFromParams(action.params);
    request.seed = seed;
    request.placedAfter = placedAfter(c.plan, record.index, action);
    request.settings = arm.settings().placement;
    request.settings.seed = arm.settings().seed;
    const PlacementPlan places = planPlacement(reach, request);
    ++c.counters.placementPlans;
    record.times.placement += secondsSince(began);
    if (!places.success()) {
      refuse(record, "placement", places.reason);
      record.blockingObjects = places.blockers;
      continue;
    }
    auto done = firstThatMoves(c, places.candidates, arm.settings().maxPlacementAttempts,
                               "place " + object.name + " " + describePlacementTarget(request.target), record,
                               [&](const PlacementCandidate& place) { return tryPlace(c, world, place, action, record); });
    if (done) {
      countReach(reach, c.counters);
      return done;
    }
  }
  countReach(reach, c.counters);
  return std::nullopt;
}

}  // namespace lang2manip
