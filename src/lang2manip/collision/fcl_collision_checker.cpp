#include "lang2manip/collision/fcl_collision_checker.hpp"

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "lang2manip/collision/fcl_collision_world.hpp"
#include "lang2manip/collision/fcl_penetration.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/kinematics/forward_kinematics.hpp"

namespace lang2manip {
/// Poses and world boxes of every geometry, FK workspaces and FCL results of one thread.
class FclCollisionChecker::Context final : public CollisionContext {
 public:
  Context(const FclCollisionChecker& owner, const std::vector<Pose>& scenePoses)
      : CollisionContext(&owner), poses(scenePoses) {
    for (const SceneRobot& robot : owner.scene().robots()) {
      kinematics.emplace_back(*robot.model);
      scratch.emplace_back(robot.model->variableCount());
    }
    centers.resize(poses.size());
    halfExtents.resize(poses.size());
    for (std::size_t g = 0; g < poses.size(); ++g) updateBox(owner.tables_->geometries[g].shape, g);
    restingRequest.enable_contact = owner.scene().contactTolerance() > 0.0;
  }

  void updateBox(const FclShape& shape, std::size_t g) noexcept {
    centers[g].noalias() = poses[g] * shape.localCenter;
    halfExtents[g].noalias() = poses[g].linear().cwiseAbs() * shape.localHalfExtent;
  }

  std::vector<KinematicsData> kinematics;
  std::vector<VectorX> scratch;
  std::vector<Pose> poses;
  std::vector<Vector3> centers;
  std::vector<Vector3> halfExtents;
  fcl::CollisionRequestd request;
  /// For pairs that may rest on each other: the first contact tells how to probe.
  fcl::CollisionRequestd restingRequest;
  fcl::CollisionResultd result;
};

FclCollisionChecker::FclCollisionChecker(Scene scene, const FclCheckerSettings& settings)
    : CollisionChecker(std::move(scene)),
      settings_(settings),
      tables_(std::make_unique<const FclWorldTables>(buildFclWorld(this->scene(), settings))) {
  scenePoses_.reserve(tables_->geometries.size());
  for (const FclGeometryEntry& entry : tables_->geometries) scenePoses_.push_back(entry.shape.origin);
  const WorldState state = sceneState();
  std::vector<KinematicsData> kinematics;
  for (std::size_t r = 0; r < state.configurations.size(); ++r) {
    const RobotModel& model = *this->scene().robots()[r].model;
    KinematicsData data(model);
    computeForwardKinematics(model, state.configurations[r], data);
    for (const int g : tables_->robotGeometries[r]) {
      const FclGeometryEntry& entry = tables_->geometries[static_cast<std::size_t>(g)];
      const int link = tables_->bodies[static_cast<std::size_t>(entry.body)].link;
      scenePoses_[static_cast<std::size_t>(g)] =
          state.basePoses[r] * data.linkPoses[static_cast<std::size_t>(link)] * entry.shape.origin;
    }
  }
}

FclCollisionChecker::~FclCollisionChecker() = default;

const AllowedCollisionMatrix& FclCollisionChecker::allowedCollisions(int robot) const {
  return *sharedAllowedCollisions(robot);
}

std::shared_ptr<const AllowedCollisionMatrix> FclCollisionChecker::sharedAllowedCollisions(int robot) const {
  if (robot < 0 || robot >= static_cast<int>(tables_->allowedCollisions.size())) {
    throw InputError("collision checker: no robot with index " + std::to_string(robot));
  }
  return tables_->allowedCollisions[static_cast<std::size_t>(robot)];
}

std::size_t FclCollisionChecker::pairCount(int robot) const {
  return tables_->robotPairs.at(static_cast<std::size_t>(robot)).size();
}

int FclCollisionChecker::skippedShapes() const noexcept { return tables_->skippedShapes; }

std::unique_ptr<CollisionContext> FclCollisionChecker::DoMakeContext() const {
  return std::make_unique<Context>(*this, scenePoses_);
}

void FclCollisionChecker::placeRobot(int robot, const VectorX& q, const Pose& X_WB,
                                     Context& context) const noexcept {
  const std::size_t r = static_cast<std::size_t>(robot);
  KinematicsData& data = context.kinematics[r];
  computeForwardKinematics(*scene().robots()[r].model, q, data);
  for (const int g : tables_->robotGeometries[r]) {
    const std::size_t i = static_cast<std::size_t>(g);
    const FclGeometryEntry& entry = tables_->geometries[i];
    const int link = tables_->bodies[static_cast<std::size_t>(entry.body)].link;
    context.poses[i] = X_WB * data.linkPoses[static_cast<std::size_t>(link)] * entry.shape.origin;
    context.updateBox(entry.shape, i);
  }
}

bool FclCollisionChecker::boxesOverlap(const Context& context, std::size_t a, std::size_t b) noexcept {
  // Written so that a NaN (a pose gone wrong) counts as overlapping: FCL then decides.
  return !(((context.centers[a] - context.centers[b]).cwiseAbs() - context.halfExtents[a] -
            context.halfExtents[b]).maxCoeff<Eigen::PropagateNaN>() > 0.0);
}

bool FclCollisionChecker::pairCollides(const FclGeometryPair& pair, Context& context) const noexcept {
  const std::size_t a = static_cast<std::size_t>(pair.first);
  const std::size_t b = static_cast<std::size_t>(pair.second);
  if (settings_.boundingBoxPrecheck && !boxesOverlap(context, a, b)) return false;
  context.result.clear();
  const FclShape& shapeA = tables_->geometries[a].shape;
  const FclShape& shapeB = tables_->geometries[b].shape;
  fcl::collide(shapeA.geometry.get(), context.poses[a], shapeB.geometry.get(), context.poses[b],
               pair.mayRest ? context.restingRequest : context.request, context.result);
  if (!context.result.isCollision()) return false;
  if (!pair.mayRest || context.result.numContacts() == 0) return true;
  return !separableWithin({&shapeA, &context.poses[a]}, {&shapeB, &context.poses[b]},
                          context.result.getContact(0), scene().contactTolerance());
}

bool FclCollisionChecker::DoIsStateValid(int robot, const VectorX& q,
                                         CollisionContext& context) const noexcept {
  auto& ctx = static_cast<Context&>(context);
  placeRobot(robot, q, scene().robots()[static_cast<std::size_t>(robot)].basePose, ctx);
  for (const FclGeometryPair& pair : tables_->robotPairs[static_cast<std::size_t>(robot)]) {
    if (pairCollides(pair, ctx)) return false;
  }
  return true;
}

bool FclCollisionChecker::DoIsMotionValid(int robot, const VectorX& q0, const VectorX& q1,
                                          double resolution,
                                          CollisionContext& context) const noexcept {
  if (!DoIsStateValid(robot, q0, context) || !DoIsStateValid(robot, q1, context)) return false;
  const double longest = (q1 - q0).cwiseAbs().maxCoeff();
  const int steps = static_cast<int>(std::ceil(longest / resolution));
  VectorX& q = static_cast<Context&>(context).scratch[static_cast<std::size_t>(robot)];
  for (int i = 1; i < steps; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(steps);
    q.noalias() = q0 + t * (q1 - q0);
    if (!DoIsStateValid(robot, q, context)) return false;
  }
  return true;
}

void FclCollisionChecker::DoCheckStates(int robot, const std::vector<VectorX>& configurations,
                                        std::vector<bool>& valid,
                                        CollisionContext& context) const noexcept {
  for (std::size_t i = 0; i < configurations.size(); ++i) {
    valid[i] = DoIsStateValid(robot, configurations[i], context);
  }
}

std::map<std::pair<int, int>, double> FclCollisionChecker::touchingBodies(Context& context) const {
  std::map<std::pair<int, int>, double> touching;
  for (const FclGeometryPair& pair : tables_->worldPairs) {
    const std::size_t a = static_cast<std::size_t>(pair.first);
    const std::size_t b = static_cast<std::size_t>(pair.second);
    if (!pairCollides(pair, context)) continue;
    const double depth = penetrationDepth({&tables_->geometries[a].shape, &context.poses[a]},
                                          {&tables_->geometries[b].shape, &context.poses[b]});
    const auto key = std::minmax(tables_->geometries[a].body, tables_->geometries[b].body);
    touching[key] = std::max(touching[key], depth);
  }
  return touching;
}

void FclCollisionChecker::closestPair(Context& context, CollisionReport& report) const {
  // Pairs nearest by their world boxes first: the gap between two boxes bounds the distance of
  // what they hold from below, so the search stops at the first box gap beyond the best distance.
  std::vector<std::pair<double, const FclGeometryPair*>> byGap;
  byGap.reserve(tables_->worldPairs.size());
  for (const FclGeometryPair& pair : tables_->worldPairs) {
    const std::size_t a = static_cast<std::size_t>(pair.first);
    const std::size_t b = static_cast<std::size_t>(pair.second);
    const double gap = ((context.centers[a] - context.centers[b]).cwiseAbs() - context.halfExtents[a] -
                        context.halfExtents[b]).cwiseMax(0.0).norm();
    byGap.emplace_back(std::isfinite(gap) ? gap : 0.0, &pair);
  }
  std::stable_sort(byGap.begin(), byGap.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  const fcl::DistanceRequestd request;
  for (const auto& [gap, pairPointer] : byGap) {
    if (gap > 0.0 && gap >= report.minimumDistance) break;
    const FclGeometryPair& pair = *pairPointer;
    const FclGeometryEntry& a = tables_->geometries[static_cast<std::size_t>(pair.first)];
    const FclGeometryEntry& b = tables_->geometries[static_cast<std::size_t>(pair.second)];
    fcl::DistanceResultd result;
    const double d = fcl::distance(a.shape.geometry.get(), context.poses[static_cast<std::size_t>(pair.first)],
                                   b.shape.geometry.get(), context.poses[static_cast<std::size_t>(pair.second)],
                                   request, result);
    const PlacedFclShape first{&a.shape, &context.poses[static_cast<std::size_t>(pair.first)]};
    const PlacedFclShape second{&b.shape, &context.poses[static_cast<std::size_t>(pair.second)]};
    if (!(d > 0.0) && pair.mayRest && separableWithin(first, second, scene().contactTolerance())) {
      if (report.minimumDistance > 0.0) {
        report.minimumDistance = 0.0;
        report.closestFirst = bodyName(a.body);
        report.closestSecond = bodyName(b.body);
      }
      continue;
    }
    if (!(d > 0.0)) {
      // FCL answers -1 (or NaN) when it finds the pair overlapping although collide() did not:
      // the state is never reported free on an inconclusive answer.
      report.valid = false;
      report.contacts.push_back(CollisionContact{bodyName(a.body), bodyName(b.body), 0.0});
      report.minimumDistance = 0.0;
      report.closestFirst = bodyName(a.body);
      report.closestSecond = bodyName(b.body);
      continue;
    }
    if (report.valid && d < report.minimumDistance) {
      report.minimumDistance = d;
      report.closestFirst = bodyName(a.body);
      report.closestSecond = bodyName(b.body);
    }
  }
}

const std::string& FclCollisionChecker::bodyName(int body) const {
  return tables_->bodies[static_cast<std::size_t>(body)].name;
}

CollisionReport FclCollisionChecker::DoCheckWorld(const WorldState& state,
                                                  const CollisionRequest& request,
                                                  CollisionContext& context) const {
  auto& ctx = static_cast<Context&>(context);
  for (std::size_t r = 0; r < state.configurations.size(); ++r) {
    placeRobot(static_cast<int>(r), state.configurations[r], state.basePoses[r], ctx);
  }
  CollisionReport report;
  report.minimumDistance = std::numeric_limits<double>::infinity();
  for (const auto& [bodies, depth] : touchingBodies(ctx)) {
    report.contacts.push_back(CollisionContact{bodyName(bodies.first), bodyName(bodies.second), depth});
    if (-depth < report.minimumDistance) {
      report.minimumDistance = -depth;
      report.closestFirst = bodyName(bodies.first);
      report.closestSecond = bodyName(bodies.second);
    }
  }
  report.valid = report.contacts.empty();
  if (report.valid && request.computeDistance) closestPair(ctx, report);
  if (report.valid && !request.computeDistance) report.minimumDistance = 0.0;
  // Back to the scene state for the single-robot calls.
  ctx.poses = scenePoses_;
  for (std::size_t g = 0; g < ctx.poses.size(); ++g) ctx.updateBox(tables_->geometries[g].shape, g);
  return report;
}

}  // namespace lang2manip
