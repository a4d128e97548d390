#include "lang2manip/grounding/reachability.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/kinematics/forward_kinematics.hpp"
#include "lang2manip/kinematics/kinematic_chain.hpp"

namespace lang2manip {
namespace {

std::string contactText(const CollisionContact& contact) { return contact.first + " - " + contact.second; }

/// `q` with each revolute joint turned by whole turns (within its limits) to the value nearest
/// to `seed`'s: the same pose, and no needless full turn for a motion planner to make.
VectorX nearestTurns(const RobotModel& model, VectorX q, const VectorX& seed) {
  constexpr double kTurn = 2.0 * M_PI;
  for (int v = 0; v < model.variableCount(); ++v) {
    const Joint& joint = model.joints()[static_cast<std::size_t>(model.variableJoints()[static_cast<std::size_t>(v)])];
    if (joint.type != JointType::kRevolute && joint.type != JointType::kContinuous) continue;
    const double value = q[v];
    const double turns = std::round((seed[v] - value) / kTurn);
    for (double k : {turns, turns - 1.0, turns + 1.0}) {
      const double candidate = value + k * kTurn;
      if (candidate >= model.lowerLimits()[v] && candidate <= model.upperLimits()[v] &&
          std::abs(candidate - seed[v]) < std::abs(q[v] - seed[v])) {
        q[v] = candidate;
      }
    }
  }
  return q;
}

}  // namespace

std::string reachFailureName(ReachFailure failure) {
  switch (failure) {
    case ReachFailure::kNone: return "none";
    case ReachFailure::kOutOfReach: return "out of reach";
    case ReachFailure::kNoIk: return "no IK solution";
    case ReachFailure::kInCollision: return "in collision";
  }
  return "unknown";
}

ReachabilityChecker::ReachabilityChecker(std::shared_ptr<const CollisionChecker> checker,
                                         std::shared_ptr<const IkSolver> ik, const std::string& robot,
                                         const std::string& manipulator, ReachSettings settings,
                                         std::shared_ptr<const GripperGeometry> gripper)
    : checker_(std::move(checker)), ik_(std::move(ik)), gripper_(std::move(gripper)), settings_(settings) {
  if (!checker_) throw InputError("reachability: no collision checker");
  if (!ik_) throw InputError("reachability: no IK solver");
  if (checker_->scene().robots().empty()) throw InputError("reachability: the scene has no robot");
  robotName_ = robot.empty() ? checker_->scene().robots().front().name : robot;
  robotIndex_ = checker_->robotIndex(robotName_);
  if (!gripper_) gripper_ = std::make_shared<const GripperGeometry>(describeGripper(model(), manipulator));
  const Manipulator& arm = findManipulator(model(), gripper_->manipulator);
  chainBase_ = this->robot().basePose * computeLinkPose(model(), currentConfiguration(), arm.baseLink);
  chainReach_ = KinematicChain(model(), arm.baseLink, arm.toolFrame).reach();
  chainBaseLink_ = arm.baseLink;
  armJoints_ = arm.armJoints.size();
  toolFrame_ = arm.toolFrame;
  context_ = std::shared_ptr<CollisionContext>(checker_->makeContext());
}

const SceneRobot& ReachabilityChecker::robot() const { return checker_->scene().robot(robotName_); }

bool ReachabilityChecker::allowedContact(const CollisionContact& contact, const std::string& touchable) const {
  if (touchable.empty()) return false;
  const std::string* other = nullptr;
  if (contact.first == touchable) other = &contact.second;
  if (contact.second == touchable) other = &contact.first;
  if (other == nullptr) return false;
  for (const std::string& finger : gripper_->fingerLinks) {
    if (*other == robotName_ + "/" + finger) return true;
  }
  return false;
}

bool ReachabilityChecker::isFree(const VectorX& q, const std::string& touchable) const {
  ++statistics_.collisionChecks;
  if (touchable.empty()) return checker_->isStateValid(robotIndex_, q, *context_);
  const CollisionReport report = checker_->checkState(robotIndex_, q, {}, *context_);
  return std::all_of(report.contacts.begin(), report.contacts.end(),
                     [&](const CollisionContact& c) { return allowedContact(c, touchable); });
}

std::string ReachabilityChecker::collisionReason(const VectorX& q, const std::string& touchable) const {
  const CollisionReport report = checker_->checkState(robotIndex_, q, {}, *context_);
  std::string pairs;
  for (const CollisionContact& contact : report.contacts) {
    if (!allowedContact(contact, touchable)) pairs += (pairs.empty() ? "" : ", ") + contactText(contact);
  }
  return "in collision: " + pairs;
}

std::string ReachabilityChecker::beyondReach(const std::string& object) const {
  const AlignedBox3 bounds = scene().object(object).worldBounds();
  const Vector3 base = chainBase_.translation();
  const Vector3 nearest = base.cwiseMax(bounds.min()).cwiseMin(bounds.max());
  const double distance = (nearest - base).norm();
  const double reach = chainReach_ + gripper_->graspFrame.translation().norm() + std::max(gripper_->fingertipOffset(), 0.0);
  if (distance <= reach) return {};
  return object + " is " + metresText(distance) + " from the arm base of " + robotName_ + " (link " + chainBaseLink_ +
         "), beyond its reach of " + metresText(reach) + ": move the robot (its <Home> in the problem file) or " + object +
         " closer";
}

ReachResult ReachabilityChecker::reach(const Pose& X_WG, const VectorX& seed, double opening,
                                       const std::string& touchable) const {
  ReachResult result;
  const Pose X_BT = chainBase_.inverse() * X_WG * gripper_->graspFrame.inverse();
  if (X_BT.translation().norm() > chainReach_) {
    result.failure = ReachFailure::kOutOfReach;
    result.reason = "out of reach: " + metresText(X_BT.translation().norm()) + " from the arm base, reach " + metresText(chainReach_);
    return result;
  }
  IkRequest request;
  request.model = &model();
  request.manipulator = gripper_->manipulator;
  request.target = IkTarget::pose(X_BT);
  request.seed = seed.size() == 0 ? currentConfiguration() : seed;
  request.timeoutSeconds = settings_.ikTimeoutSeconds;
  request.solutionCount = settings_.ikSolutions;
  request.randomSeed = settings_.seed;
  ++statistics_.ikCalls;
  const IkResult ik = ik_->solve(request);
  if (ik.status != IkStatus::kSuccess) {
    result.failure = ReachFailure::kNoIk;
    result.reason = "no IK solution (" + ikStatusName(ik.status) + (ik.message.empty() ? "" : ": " + ik.message) + ")";
    return result;
  }
  for (const VectorX& solution : ik.solutions) {
    VectorX q = withGripperOpening(model(), *gripper_, nearestTurns(model(), solution, request.seed), opening);
    if (isFree(q, touchable)) result.solutions.push_back(std::move(q));
  }
  if (result.solutions.empty()) {
    result.failure = ReachFailure::kInCollision;
    result.reason = collisionReason(withGripperOpening(model(), *gripper_, ik.solutions.front(), opening), touchable);
  }
  return result;
}

std::optional<Pose> ReachabilityChecker::turnedToReach(const Pose& X_WG, const VectorX& seed) const {
  constexpr double kOnTheAxis = 2e-3;
  const Pose X_BG = chainBase_.inverse() * X_WG;
  const Pose X_BT = X_BG * gripper_->graspFrame.inverse();
  if (X_BT.translation().norm() > chainReach_) return std::nullopt;
  IkRequest request;
  request.model = &model();
  request.manipulator = gripper_->manipulator;
  request.target = IkTarget::positionAndAxis(X_BT.translation(), X_BG.linear().col(2), gripper_->graspFrame.linear().col(2));
  request.seed = seed.size() == 0 ? currentConfiguration() : seed;
  request.timeoutSeconds = settings_.ikTimeoutSeconds;
  request.solutionCount = 1;
  request.randomSeed = settings_.seed;
  ++statistics_.ikCalls;
  const IkResult ik = ik_->solve(request);
  if (ik.status != IkStatus::kSuccess || ik.solutions.empty()) return std::nullopt;
  const Pose turned = robot().basePose * computeLinkPose(model(), ik.solutions.front(), toolFrame_) * gripper_->graspFrame;
  // The tool frame turns about its own origin: the grasp frame's origin must stay on the axis.
  if ((turned.translation() - X_WG.translation()).norm() > kOnTheAxis) return std::nullopt;
  return turned;
}

double ReachabilityChecker::clearance(const VectorX& q) const {
  CollisionRequest request;
  request.computeDistance = true;
  ++statistics_.collisionChecks;
  return checker_->checkState(robotIndex_, q, request, *context_).minimumDistance;
}

ReachabilityChecker ReachabilityChecker::withScene(Scene scene) const {
  FclCheckerSettings fcl;
  if (const auto* exact = dynamic_cast<const FclCollisionChecker*>(checker_.get())) {
    if (exact->scene().robots().size() == scene.robots().size()) {
      for (std::size_t r = 0; r < scene.robots().size(); ++r) {
        fcl.precomputedMatrices.push_back(exact->sharedAllowedCollisions(static_cast<int>(r)));
      }
    }
  }
  auto checker = std::make_shared<const FclCollisionChecker>(std::move(scene), fcl);
  return ReachabilityChecker(checker, ik_, robotName_, gripper_->manipulator, settings_, gripper_);
}

}  // namespace lang2manip
