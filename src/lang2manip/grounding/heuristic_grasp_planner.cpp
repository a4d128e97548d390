#include "lang2manip/grounding/heuristic_grasp_planner.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "lang2manip/grounding/grasp_candidates.hpp"
#include "lang2manip/grounding/object_geometry.hpp"

namespace lang2manip {
namespace {

/// Height tolerance when looking for the support under the object.

double directionPreference(GraspDirection direction) {
  switch (direction) {
    case GraspDirection::kTop: return 1.0;
    case GraspDirection::kFront: return 2.0 / 3.0;
    default: return 1.0 / 3.0;
  }
}

GraspPlan failed(GraspPlan plan, GraspFailure failure, std::string reason) {
  plan.failure = failure;
  plan.reason = std::move(reason);
  return plan;
}

std::string directionWords(GraspDirection direction) {
  return direction == GraspDirection::kAuto ? "grasp" : graspDirectionName(direction) + " grasp";
}

/// The failure when geometry left no candidate: too wide if every rejection says so.
GraspPlan noGeometricGrasp(GraspPlan plan, const std::string& object, GraspDirection direction) {
  const bool allTooWide = !plan.rejections.empty() &&
                          std::all_of(plan.rejections.begin(), plan.rejections.end(),
                                      [](const GraspRejection& r) { return r.failure == GraspFailure::kTooWide; });
  if (allTooWide) {
    std::string narrowest = plan.rejections.front().reason;
    return failed(std::move(plan), GraspFailure::kTooWide, object + ": too wide for the gripper (" + narrowest + ")");
  }
  const std::string why = plan.rejections.empty() ? "" : " (" + plan.rejections.front().reason + ")";
  return failed(std::move(plan), GraspFailure::kNoCandidate, object + ": no " + directionWords(direction) + " fits its shape" + why);
}

/// The failure when no candidate passed the reachability checks: the most frequent reason.
GraspPlan noReachableGrasp(GraspPlan plan, const std::string& object, GraspDirection direction) {
  int collisions = 0;
  const GraspRejection* example = nullptr;
  const GraspRejection* collisionExample = nullptr;
  for (const GraspRejection& r : plan.rejections) {
    if (r.failure == GraspFailure::kInCollision) {
      ++collisions;
      if (collisionExample == nullptr) collisionExample = &r;
    }
    if (r.failure == GraspFailure::kUnreachable && example == nullptr) example = &r;
  }
  const bool collision = example == nullptr || (collisionExample != nullptr && 2 * collisions >= static_cast<int>(plan.rejections.size()));
  const GraspRejection* shown = collision ? collisionExample : example;
  const std::string detail = shown == nullptr ? "" : ": " + shown->reason;
  const GraspFailure failure = collision ? GraspFailure::kInCollision : GraspFailure::kUnreachable;
  const std::string words = collision ? " is collision-free" : " is reachable";
  const std::string widened =
      plan.widenedTilt > 0.0 ? " (top grasps tilted up to " + std::to_string(static_cast<int>(std::lround(plan.widenedTilt * 180.0 / M_PI))) + " deg too)" : "";
  return failed(std::move(plan), failure, object + ": no " + directionWords(direction) + words + widened + detail);
}

struct Context {
  const ReachabilityChecker& reach;
  const ReachabilityChecker& free;
  const GraspRequest& request;
  const SceneObject& object;
};

std::optional<GraspCandidate> checkGrasp(const Context& c, const GeometricGrasp& g, GraspPlan& plan, bool mayTurn = true);

/// `g` turned about its approach axis to the turn an arm of fewer than six joints reaches it
/// with, when the object still fits between the fingers there (its width across them within the
/// opening); nullopt otherwise.
std::optional<GeometricGrasp> turnedGrasp(const Context& c, const GeometricGrasp& g) {
  const std::optional<Pose> turned = c.reach.turnedToReach(g.pose, c.request.seed);
  if (!turned) return std::nullopt;
  const GripperGeometry& gripper = c.reach.gripper();
  const double width = 2.0 * halfExtentAlong(c.object, c.object.pose, turned->linear() * gripper.closingAxis);
  if (width > gripper.maxOpening - 2.0 * c.request.settings.openingMargin || width < gripper.minOpening) return std::nullopt;
  const Vector3 before = g.pose.linear() * gripper.closingAxis, after = turned->linear() * gripper.closingAxis;
  const double angle = std::atan2(before.cross(after).dot(g.approach), before.dot(after));
  GeometricGrasp result = g;
  result.pose = *turned;
  result.width = width;
  result.label = g.label + " turned " + std::to_string(static_cast<int>(std::lround(angle * 180.0 / M_PI))) + " deg";
  return result;
}

/// Full checks of one geometric grasp; nullopt (and a rejection) when it fails. An arm of fewer
/// than six joints that does not reach the grasp as it is tries it at the turn it reaches.
std::optional<GraspCandidate> checkGrasp(const Context& c, const GeometricGrasp& g, GraspPlan& plan, bool mayTurn) {
  const GraspSettings& s = c.request.settings;
  GraspCandidate candidate;
  candidate.object = c.object.name;
  candidate.direction = g.direction;
  candidate.label = g.label;
  candidate.graspPose = g.pose;
  candidate.approachDirection = g.approach;
  candidate.preGraspPose = Pose(Eigen::Translation3d(-g.approach * s.approachDistance)) * g.pose;
  candidate.postGraspPose = Pose(Eigen::Translation3d(Vector3::UnitZ() * s.liftDistance)) * g.pose;
  candidate.objectToGripper = c.object.pose.inverse() * g.pose;
  candidate.objectWidth = g.width;
  candidate.opening = std::min(c.reach.gripper().maxOpening, g.width + 2.0 * s.openingMargin);
  auto reject = [&](const std::string& stage, const ReachResult& r) {
    const GraspFailure failure = r.failure == ReachFailure::kInCollision ? GraspFailure::kInCollision : GraspFailure::kUnreachable;
    plan.rejections.push_back({g.label, failure, stage + " " + r.reason});
    return std::nullopt;
  };
  const ReachResult grasp = c.reach.reach(g.pose, c.request.seed, candidate.opening, c.object.name);
  if (!grasp.reachable() && grasp.failure == ReachFailure::kNoIk && mayTurn && c.reach.turnIsConstrained()) {
    if (const std::optional<GeometricGrasp> turned = turnedGrasp(c, g)) return checkGrasp(c, *turned, plan, false);
  }
  if (!grasp.reachable()) return reject("grasp pose", grasp);
  const ReachResult pre = c.reach.reach(candidate.preGraspPose, grasp.solutions.front(), candidate.opening);
  if (!pre.reachable()) return reject("pre-grasp pose", pre);
  const ReachResult post = c.free.reach(candidate.postGraspPose, grasp.solutions.front(), candidate.opening);
  candidate.graspSolutions = grasp.solutions;
  candidate.preGraspSolutions = pre.solutions;
  candidate.postGraspSolutions = post.solutions;
  candidate.clearance = c.free.clearance(grasp.solutions.front());
  const double length = std::max(1e-3, halfExtentAlong(c.object, c.object.pose, g.approach.cross(g.pose.linear() * c.reach.gripper().closingAxis)));
  const double solutions = static_cast<double>(grasp.solutions.size()) / c.reach.settings().ikSolutions;
  candidate.score = std::min(std::max(candidate.clearance, 0.0), 0.05) / 0.05 + 0.3 * directionPreference(g.direction) +
                    0.2 * (1.0 - std::abs(g.offset) / length) + 0.2 * std::min(1.0, solutions);
  return candidate;
}

/// Direction preference first, then grasps nearer the object's centre.
void orderGrasps(std::vector<GeometricGrasp>& grasps) {
  std::stable_sort(grasps.begin(), grasps.end(), [](const GeometricGrasp& a, const GeometricGrasp& b) {
    const double pa = directionPreference(a.direction), pb = directionPreference(b.direction);
    if (pa != pb) return pa > pb;
    return std::abs(a.offset) < std::abs(b.offset);
  });
}

/// Round-robin over top, front and side (each in orderGrasps() order), so that every direction
/// gets checked within the budget.
std::vector<GeometricGrasp> interleaveByDirection(std::vector<GeometricGrasp> grasps) {
  orderGrasps(grasps);
  std::vector<std::vector<GeometricGrasp>> byDirection(3);
  for (const GeometricGrasp& g : grasps) {
    const std::size_t slot = g.direction == GraspDirection::kTop ? 0 : g.direction == GraspDirection::kFront ? 1 : 2;
    byDirection[slot].push_back(g);
  }
  std::vector<GeometricGrasp> order;
  for (std::size_t i = 0; order.size() < grasps.size(); ++i) {
    for (const auto& list : byDirection) {
      if (i < list.size()) order.push_back(list[i]);
    }
  }
  return order;
}

/// Checks `grasps` in order into `plan` until enough candidates or the reach-check budget.
void checkGrasps(const Context& context, std::vector<GeometricGrasp> grasps, GraspPlan& plan) {
  int checks = 0;
  for (const GeometricGrasp& g : grasps) {
    if (static_cast<int>(plan.candidates.size()) >= context.request.settings.maxCandidates) break;
    if (checks++ >= context.request.settings.maxReachChecks) break;
    if (auto candidate = checkGrasp(context, g, plan)) plan.candidates.push_back(std::move(*candidate));
  }
}

}  // namespace

GraspPlan HeuristicGraspPlanner::plan(const ReachabilityChecker& reach, const GraspRequest& request) const {
  checkGraspSettings(request.settings);
  const Scene& scene = reach.scene();
  const SceneObject& object = scene.object(request.object);
  GraspPlan plan;
  if (scene.findAttachment(object.name) != nullptr) {
    return failed(std::move(plan), GraspFailure::kNotGraspable, object.name + ": already held");
  }
  if (!object.movable) return failed(std::move(plan), GraspFailure::kNotGraspable, object.name + ": not movable");
  const SceneObject* support = currentSupport(scene, object, kSupportTolerance);
  const AlignedBox3 bounds = object.worldBounds();
  const Vector3 bottom(bounds.center().x(), bounds.center().y(), bounds.min().z());
  GraspGeometryInput input{&object, object.pose, reach.robot().basePose,
                           support != nullptr ? surfaceUnder(*support, bottom, kSupportTolerance) : bounds.min().z()};
  GraspGeneration generation = generateGrasps(input, reach.gripper(), request.direction, request.settings);
  plan.rejections = std::move(generation.rejections);
  if (generation.grasps.empty()) return noGeometricGrasp(std::move(plan), object.name, request.direction);

  Scene withoutObject = scene;
  withoutObject.object(object.name).collisionEnabled = false;
  const ReachabilityChecker free = reach.withScene(std::move(withoutObject));
  const Context context{reach, free, request, object};
  checkGrasps(context, interleaveByDirection(std::move(generation.grasps)), plan);
  if (plan.candidates.empty()) {
    // Near other objects or at the edge of the workspace: lean the hand before giving up.
    GraspGeneration widened = generateWidenedGrasps(input, reach.gripper(), request.direction, request.settings);
    orderGrasps(widened.grasps);
    if (!widened.grasps.empty()) {
      plan.widenedTilt = *std::max_element(request.settings.widenedTopTilts.begin(), request.settings.widenedTopTilts.end());
    }
    checkGrasps(context, std::move(widened.grasps), plan);
  }
  std::stable_sort(plan.candidates.begin(), plan.candidates.end(),
                   [](const GraspCandidate& a, const GraspCandidate& b) { return a.score > b.score; });
  if (plan.candidates.empty()) return noReachableGrasp(std::move(plan), object.name, request.direction);
  return plan;
}

std::unique_ptr<GraspPlanner> makeHeuristicGraspPlanner() { return std::make_unique<HeuristicGraspPlanner>(); }

}  // namespace lang2manip
