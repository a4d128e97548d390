#include "lang2manip/grounding/placement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

#include "lang2manip/core/error.hpp"
#include "lang2manip/grounding/object_collision.hpp"
#include "lang2manip/grounding/object_geometry.hpp"
#include "lang2manip/grounding/placement_poses.hpp"
#include "lang2manip/kinematics/forward_kinematics.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"

namespace lang2manip {
namespace {

PlacementPlan failed(PlacementPlan plan, PlacementFailure failure, std::string reason) {
  plan.failure = failure;
  plan.reason = std::move(reason);
  return plan;
}

/// X_OG of an object the robot holds, from the scene's attachment at the current configuration.
Pose heldGrasp(const ReachabilityChecker& reach, const std::string& object) {
  const Pose X_WG = reach.robot().basePose * computeLinkPose(reach.model(), reach.currentConfiguration(), reach.gripper().toolFrame) *
                     reach.gripper().graspFrame;
  return currentObjectPose(reach.scene(), object).inverse() * X_WG;
}

/// The grasps to try and whether the object is already held by the robot.
std::vector<Pose> graspsToTry(const ReachabilityChecker& reach, const PlacementRequest& request, bool held) {
  if (!request.grasps.empty()) return request.grasps;
  if (!held) throw InputError("placement of " + request.object + ": the object is not held and no grasp was given");
  return {heldGrasp(reach, request.object)};
}

/// Reachability of the robot holding the object by grasp X_OG (one checker per grasp, built once).
class HeldObjectReach {
 public:
  HeldObjectReach(const ReachabilityChecker& reach, std::string object, bool held)
      : reach_(reach), object_(std::move(object)), held_(held) {}

  const ReachabilityChecker& forGrasp(std::size_t index, const Pose& X_OG) {
    if (held_) return reach_;
    auto& slot = checkers_[index];
    if (!slot) {
      Scene scene = reach_.scene();
      scene.attach({object_, reach_.robot().name, reach_.gripper().toolFrame, reach_.gripper().graspFrame * X_OG.inverse()});
      slot = std::make_unique<ReachabilityChecker>(reach_.withScene(std::move(scene)));
    }
    return *slot;
  }

 private:
  const ReachabilityChecker& reach_;
  std::string object_;
  bool held_;
  std::map<std::size_t, std::unique_ptr<ReachabilityChecker>> checkers_;
};

struct Attempt {
  const Scene& scene;
  const GripperGeometry& gripper;
  const PlacementRequest& request;
  const SceneObject& object;
  const std::vector<Pose>& grasps;
  HeldObjectReach& held;
  VectorX seed;
};

/// Tries every grasp at one object pose; appends a candidate or rejections.
bool tryPoseAt(Attempt& a, const PoseCandidate& pose, double drop, int& checks, PlacementPlan& plan);

/// True when, released `drop` above `pose` by some grasp, the fully open fingers either stay
/// above the container's rim or fit inside its cavity (seen from above).
bool fingersFit(const Attempt& a, const PoseCandidate& pose, const SceneObject& container, double drop) {
  const AlignedBox3 cavity = transformedBox(*container.cavity, container.pose);
  const double rim = container.worldBounds().max().z();
  const Pose release = Pose(Eigen::Translation3d(Vector3::UnitZ() * drop)) * pose.pose;
  for (const Pose& X_OG : a.grasps) {
    const AlignedBox3 fingers = transformedBox(a.gripper.fingerBounds, release * X_OG);
    const bool inside = fingers.min().x() >= cavity.min().x() && fingers.max().x() <= cavity.max().x() &&
                        fingers.min().y() >= cavity.min().y() && fingers.max().y() <= cavity.max().y();
    if (fingers.min().z() >= rim || inside) return true;
  }
  return false;
}

/// Release heights above `pose` to try: none but 0 outside a container; inside one, the
/// settings' drop heights below the rim drop at which the open fingers fit, then the rim drop
/// (the lowest of the object and the fingers, for any of the grasps, rimClearance above the
/// container's rim, so that the hand stays out of the opening).
std::vector<double> dropHeightsFor(const Attempt& a, const PoseCandidate& pose) {
  if (a.request.target.relation != SpatialRelation::kIn) return {0.0};
  const PlacementSettings& s = a.request.settings;
  const SceneObject& container = a.scene.object(pose.support);
  const double rim = container.worldBounds().max().z();
  double lowest = boundsAtPose(a.object, pose.pose).min().z();
  for (const Pose& X_OG : a.grasps) lowest = std::min(lowest, transformedBox(a.gripper.fingerBounds, pose.pose * X_OG).min().z());
  const double rimDrop = std::max(rim + s.rimClearance - lowest, 0.0);
  std::vector<double> drops;
  for (double drop : s.dropHeights) {
    if (drop < rimDrop && (!container.cavity || fingersFit(a, pose, container, drop))) drops.push_back(drop);
  }
  drops.push_back(rimDrop);
  return drops;
}

void tryPose(Attempt& a, const PoseCandidate& pose, int& checks, PlacementPlan& plan) {
  for (double drop : dropHeightsFor(a, pose)) {
    if (tryPoseAt(a, pose, drop, checks, plan)) return;
  }
}

/// `pose` turned about the hand's approach axis to the turn an arm of fewer than six joints
/// reaches its place pose with (grasp `g`, released `drop` above it), when the object there still
/// stands upright, clear of the world and, for a relation, in it (the goal check's words); for a
/// position without an orientation, at that position. Nullopt otherwise.
std::optional<PoseCandidate> turnedPose(const Attempt& a, const ReachabilityChecker& reach, const PoseCandidate& pose, double drop,
                                        std::size_t g) {
  const Pose lift(Eigen::Translation3d(Vector3::UnitZ() * drop));
  const std::optional<Pose> hand = reach.turnedToReach(lift * pose.pose * a.grasps[g], a.seed);
  if (!hand) return std::nullopt;
  const Pose turned = lift.inverse() * *hand * a.grasps[g].inverse();
  const bool upright = (turned.linear().col(2) - pose.pose.linear().col(2)).norm() < 1e-2;
  if (!upright || !ObjectCollisionWorld(a.scene, a.object.name).collisions(turned).empty()) return std::nullopt;
  const PlacementTarget& target = a.request.target;
  if (target.relation) {
    Scene placed = a.scene;
    const Pose resting = Pose(Eigen::Translation3d(-Vector3::UnitZ() * a.request.settings.releaseGap)) * turned;
    if (placed.findAttachment(a.object.name) != nullptr) placed.detach(a.object.name, resting);
    placed.object(a.object.name).pose = resting;
    Goal goal;
    goal.kind = GoalKind::kRelation;
    goal.object = a.object.name;
    goal.relation = *target.relation;
    goal.target = target.target;
    goal.distance = target.distance;
    goal.region = target.region;
    if (!checkGoalInScene(placed, goal).holds) return std::nullopt;
  } else if (target.orientation || (turned.translation() - pose.pose.translation()).norm() > 0.01) {
    return std::nullopt;
  }
  return PoseCandidate{turned, pose.support, pose.label + " (turned as the arm reaches it)"};
}

/// The candidate placing the object at `at` with grasp `g`, released `drop` above it (poses and
/// openings; no reach checked yet).
PlacementCandidate candidateAt(const Attempt& a, const ReachabilityChecker& reach, const PoseCandidate& at, double drop, std::size_t g) {
  const PlacementSettings& s = a.request.settings;
  PlacementCandidate c;
  c.object = a.object.name;
  c.support = at.support;
  c.label = at.label;
  c.objectPose = at.pose;
  c.restingPose = Pose(Eigen::Translation3d(-Vector3::UnitZ() * s.releaseGap)) * at.pose;
  c.graspIndex = g;
  c.objectToGripper = a.grasps[g];
  c.dropHeight = drop;
  c.placePose = Pose(Eigen::Translation3d(Vector3::UnitZ() * drop)) * at.pose * a.grasps[g];
  c.prePlacePose = Pose(Eigen::Translation3d(Vector3::UnitZ() * s.approachHeight)) * c.placePose;
  c.retreatPose = c.placePose * Pose(Eigen::Translation3d(-reach.gripper().approachAxis * s.retreatDistance));
  c.heldWidth = 2.0 * halfExtentAlong(a.object, Pose::Identity(), a.grasps[g].linear() * reach.gripper().closingAxis);
  c.releaseOpening = std::min(reach.gripper().maxOpening, c.heldWidth + 2.0 * s.releaseMargin);
  return c;
}

bool tryPoseAt(Attempt& a, const PoseCandidate& asked, double drop, int& checks, PlacementPlan& plan) {
  const PlacementSettings& s = a.request.settings;
  for (std::size_t g = 0; g < a.grasps.size() && checks < s.maxReachChecks; ++g) {
    const ReachabilityChecker& reach = a.held.forGrasp(g, a.grasps[g]);
    PoseCandidate pose = asked;
    PlacementCandidate c = candidateAt(a, reach, pose, drop, g);
    ++checks;
    // Checked with the gripper opened for the release: fingers that open into a container's wall
    // rule the pose out.
    ReachResult place = reach.reach(c.placePose, a.seed, c.releaseOpening);
    if (!place.reachable() && place.failure == ReachFailure::kNoIk && reach.turnIsConstrained()) {
      if (const std::optional<PoseCandidate> turned = turnedPose(a, reach, pose, drop, g)) {
        pose = *turned;
        c = candidateAt(a, reach, pose, drop, g);
        place = reach.reach(c.placePose, a.seed, c.releaseOpening);
      }
    }
    if (!place.reachable()) {
      plan.rejections.push_back({pose.label, PlacementFailure::kUnreachable, "place pose " + place.reason, {}});
      continue;
    }
    const ReachResult pre = reach.reach(c.prePlacePose, place.solutions.front(), c.heldWidth);
    if (!pre.reachable()) {
      plan.rejections.push_back({pose.label, PlacementFailure::kUnreachable, "pre-place pose " + pre.reason, {}});
      continue;
    }
    c.placeSolutions = place.solutions;
    c.prePlaceSolutions = pre.solutions;
    c.score = 1.0 / (1.0 + static_cast<double>(plan.candidates.size() + plan.rejections.size())) +
              0.1 * static_cast<double>(place.solutions.size()) / reach.settings().ikSolutions;
    plan.candidates.push_back(std::move(c));
    return true;
  }
  return false;
}

/// The failure when every pose was dropped: blocked if any pose was, else the reach reason.
PlacementPlan noPlacement(PlacementPlan plan, const std::string& what) {
  const PlacementRejection* blocked = nullptr;
  const PlacementRejection* unreachable = nullptr;
  for (const PlacementRejection& r : plan.rejections) {
    if (r.failure == PlacementFailure::kBlocked && blocked == nullptr) blocked = &r;
    if (r.failure == PlacementFailure::kUnreachable && unreachable == nullptr) unreachable = &r;
  }
  if (unreachable != nullptr) return failed(std::move(plan), PlacementFailure::kUnreachable, what + ": no placement is reachable (" + unreachable->reason + ")");
  if (blocked != nullptr) {
    for (const PlacementRejection& r : plan.rejections) {
      for (const std::string& blocker : r.blockers) {
        if (std::find(plan.blockers.begin(), plan.blockers.end(), blocker) == plan.blockers.end()) plan.blockers.push_back(blocker);
      }
    }
    return failed(std::move(plan), PlacementFailure::kBlocked, what + ": every position is blocked (" + blocked->reason + ")");
  }
  return failed(std::move(plan), PlacementFailure::kUnreachable, what + ": no placement found");
}

/// Where an object the plan places later could go at the target: the world boxes of its poses
/// that are free of the scene's other objects (the object being placed now is held, so it is
/// not among them).
std::vector<AlignedBox3> laterObjectRoom(const Scene& scene, const std::string& later, const PlacementRequest& request,
                                         const SceneRobot& robot, const std::string& arm) {
  const SceneObject* object = scene.findObject(later);
  if (object == nullptr || scene.findAttachment(later) != nullptr) return {};
  const Pose current = currentObjectPose(scene, later);
  const PoseSamplingInput input{&scene, object, Quaternion(current.linear()), current.translation(), robot.basePose, robot.name, arm};
  const PoseSampling sampling = samplePlacementPoses(input, request.target, request.settings);
  const ObjectCollisionWorld world(scene, later);
  std::vector<AlignedBox3> room;
  for (const PoseCandidate& pose : sampling.poses) {
    if (world.collisions(pose.pose).empty()) room.push_back(boundsAtPose(*object, pose.pose));
  }
  return room;
}

/// Puts first the poses after which the objects of `request.placedAfter` all still have free
/// positions at the target, one each (several objects into one container: the first must not
/// take the middle that the next ones need). Boxes are compared, which is conservative: it only
/// orders.
void leaveRoomForLaterObjects(const Scene& scene, const PlacementRequest& request, const SceneObject& object,
                              const SceneRobot& robot, const std::string& arm, std::vector<PoseCandidate>& poses) {
  std::vector<std::vector<AlignedBox3>> rooms;
  for (const std::string& later : request.placedAfter) {
    if (later != object.name) rooms.push_back(laterObjectRoom(scene, later, request, robot, arm));
  }
  if (rooms.empty()) return;
  // Each later object in turn takes the first of its free positions clear of this one and of
  // those taken before it: all of them must find one.
  std::stable_partition(poses.begin(), poses.end(), [&](const PoseCandidate& pose) {
    std::vector<AlignedBox3> taken{boundsAtPose(object, pose.pose)};
    for (const std::vector<AlignedBox3>& room : rooms) {
      const auto free = std::find_if(room.begin(), room.end(), [&](const AlignedBox3& box) {
        return std::none_of(taken.begin(), taken.end(), [&](const AlignedBox3& other) { return box.intersects(other); });
      });
      if (free == room.end()) return false;
      taken.push_back(*free);
    }
    return true;
  });
}

}  // namespace

void checkPlacementSettings(const PlacementSettings& s) {
  for (auto [value, field] : {std::pair{s.releaseGap, "releaseGap"}, {s.sideGap, "sideGap"}, {s.nextToGap, "nextToGap"},
                              {s.wallMargin, "wallMargin"}, {s.edgeMargin, "edgeMargin"}, {s.approachHeight, "approachHeight"},
                              {s.retreatDistance, "retreatDistance"}, {s.supportTolerance, "supportTolerance"},
                              {s.releaseMargin, "releaseMargin"}}) {
    requireSettingLength(value, "placement", field);
  }
  for (double drop : s.dropHeights) requireSettingLength(drop, "placement", "dropHeights");
  requireSettingLength(s.rimClearance, "placement", "rimClearance");
  for (double shift : s.lateralShifts) {
    if (!std::isfinite(shift)) throw InputError("placement settings: lateralShifts must be finite");
  }
  if (s.lateralShifts.empty()) throw InputError("placement settings: lateralShifts must not be empty");
  requireSettingCount(s.cavityGrid, "placement", "cavityGrid");
  requireSettingCount(s.surfaceSamples, "placement", "surfaceSamples");
  requireSettingCount(s.maxCandidates, "placement", "maxCandidates");
  requireSettingCount(s.maxReachChecks, "placement", "maxReachChecks");
}

PlacementPlan planPlacement(const ReachabilityChecker& reach, const PlacementRequest& request) {
  checkPlacementSettings(request.settings);
  const Scene& scene = reach.scene();
  const SceneObject& object = scene.object(request.object);
  if (request.target.relation) static_cast<void>(scene.object(request.target.target));
  if (request.target.distance && !(std::isfinite(*request.target.distance) && *request.target.distance >= 0.0)) {
    throw InputError("placement of " + object.name + ": the distance must be finite and >= 0");
  }
  const Attachment* attachment = scene.findAttachment(object.name);
  const bool held = attachment != nullptr && attachment->robot == reach.robot().name;
  const std::vector<Pose> grasps = graspsToTry(reach, request, held);
  const std::string what = object.name + " " + describePlacementTarget(request.target);
  const Pose current = currentObjectPose(scene, object.name);
  const PoseSamplingInput input{&scene, &object, Quaternion(object.pose.linear()), current.translation(), reach.robot().basePose,
                                 reach.robot().name, reach.gripper().manipulator, request.placedAfter.empty()};
  PoseSampling sampling = samplePlacementPoses(input, request.target, request.settings);
  PlacementPlan plan;
  if (sampling.poses.empty()) return failed(std::move(plan), sampling.failure, what + ": " + sampling.reason);
  leaveRoomForLaterObjects(scene, request, object, reach.robot(), reach.gripper().manipulator, sampling.poses);

  const ObjectCollisionWorld world(scene, object.name);
  HeldObjectReach heldReach(reach, object.name, held);
  Attempt attempt{scene, reach.gripper(), request, object, grasps, heldReach, request.seed};
  int checks = 0;
  for (const PoseCandidate& pose : sampling.poses) {
    if (static_cast<int>(plan.candidates.size()) >= request.settings.maxCandidates || checks >= request.settings.maxReachChecks) break;
    const std::vector<std::string> blockers = world.collisions(pose.pose);
    if (!blockers.empty()) {
      std::string names;
      for (const std::string& name : blockers) names += (names.empty() ? "" : ", ") + name;
      plan.rejections.push_back({pose.label, PlacementFailure::kBlocked, "blocked by " + names, blockers});
      continue;
    }
    tryPose(attempt, pose, checks, plan);
  }
  if (plan.candidates.empty()) return noPlacement(std::move(plan), what);
  return plan;
}

PlacementTarget placementTargetFromParams(const ActionParams& params) {
  PlacementTarget target;
  target.relation = params.relation;
  target.target = params.target;
  target.distance = params.distance;
  target.position = params.position;
  target.orientation = params.orientation;
  target.region = params.region;
  return target;
}

std::string describePlacementTarget(const PlacementTarget& target) {
  char buffer[96];
  if (!target.relation) {
    if (!target.position) return "(no target)";
    std::snprintf(buffer, sizeof buffer, "at (%.3f, %.3f, %.3f)", target.position->x(), target.position->y(), target.position->z());
    return buffer;
  }
  std::string text = spatialRelationWords(*target.relation) + " " + target.target;
  if (target.region) text += " (" + surfaceRegionWords(*target.region) + ")";
  if (target.distance) {
    std::snprintf(buffer, sizeof buffer, " (%.3f m)", *target.distance);
    text += buffer;
  }
  return text;
}

std::string placementFailureName(PlacementFailure failure) {
  switch (failure) {
    case PlacementFailure::kNone: return "none";
    case PlacementFailure::kBadTarget: return "bad target";
    case PlacementFailure::kTooLarge: return "too large";
    case PlacementFailure::kNoSupport: return "no support";
    case PlacementFailure::kBlocked: return "blocked";
    case PlacementFailure::kUnreachable: return "unreachable";
  }
  return "unknown";
}

}  // namespace lang2manip
