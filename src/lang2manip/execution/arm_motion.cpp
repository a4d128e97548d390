#include "lang2manip/execution/arm_motion.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "lang2manip/core/error.hpp"
#include "lang2manip/grounding/object_collision.hpp"
#include "lang2manip/kinematics/forward_kinematics.hpp"
#include "lang2manip/planning/motion_planner.hpp"
#include "lang2manip/planning/planning_space.hpp"

namespace lang2manip {
namespace {

/// A resting object slides on its support during a push: its sweep is checked this far above
/// the support so that the resting contact is not a collision.
constexpr double kSlideLift = 0.001;
/// Step of the carried object's sweep check (m).
constexpr double kSweepStep = 0.002;

MotionResult failedMotion(const std::string& stage, std::string reason) {
  MotionResult result;
  result.stage = stage;
  result.reason = std::move(reason);
  return result;
}

std::string armPart(const VectorX& x) {
  std::string text = "(";
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    char value[24];
    std::snprintf(value, sizeof value, "%s%.3f", i == 0 ? "" : ", ", x[i]);
    text += value;
  }
  return text + ")";
}

VectorX valuesOf(const std::vector<int>& variables, const VectorX& q) {
  VectorX x(static_cast<Eigen::Index>(variables.size()));
  for (std::size_t i = 0; i < variables.size(); ++i) x[static_cast<Eigen::Index>(i)] = q[variables[i]];
  return x;
}

VectorX withValues(const std::vector<int>& variables, VectorX q, const VectorX& x) {
  for (std::size_t i = 0; i < variables.size(); ++i) q[variables[i]] = x[static_cast<Eigen::Index>(i)];
  return q;
}

VectorX armValues(const ArmContext& arm, const VectorX& q) { return valuesOf(arm.armVariables(), q); }

std::string contactsText(const std::vector<CollisionContact>& contacts) {
  std::string text;
  for (const CollisionContact& c : contacts) text += (text.empty() ? "" : ", ") + c.first + " - " + c.second;
  return text;
}

/// The contacts of robot `robot` at `q` that the segment does not allow.
std::vector<CollisionContact> forbiddenContacts(const CollisionChecker& checker, int robot, const VectorX& q,
                                                const MotionSegment& segment, CollisionContext& context) {
  const CollisionReport report = checker.checkState(robot, q, {}, context);
  std::vector<CollisionContact> forbidden;
  for (const CollisionContact& c : report.contacts) {
    const bool allowed = std::any_of(segment.allowedContacts.begin(), segment.allowedContacts.end(), [&](const auto& pair) {
      return (pair.first == c.first && pair.second == c.second) || (pair.first == c.second && pair.second == c.first);
    });
    if (!allowed) forbidden.push_back(c);
  }
  return forbidden;
}

/// The world a segment's robot is checked in: the carried object left out.
Scene robotCheckWorld(const MotionSegment& segment) {
  Scene world = segment.world;
  if (!segment.carried.empty()) world.object(segment.carried).collisionEnabled = false;
  return world;
}

std::string findCarriedCollision(const MotionSegment& segment) {
  const ObjectCollisionWorld objects(segment.world, segment.carried);
  const double length = segment.carriedDisplacement.norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / kSweepStep)));
  for (int i = 0; i <= steps; ++i) {
    Pose X_WO = segment.carriedStart;
    X_WO.translation() += segment.carriedDisplacement * (static_cast<double>(i) / steps) + Vector3::UnitZ() * kSlideLift;
    const std::vector<std::string> hits = objects.collisions(X_WO);
    if (!hits.empty()) {
      char at[64];
      std::snprintf(at, sizeof at, " after %.3f m", length * i / steps);
      std::string names;
      for (const std::string& name : hits) names += (names.empty() ? "" : ", ") + name;
      return segment.carried + " would hit " + names + at;
    }
  }
  return {};
}

}  // namespace

ArmContext::ArmContext(const Scene& scene, ExecutionSettings settings) : settings_(std::move(settings)) {
  checkExecutionSettings(settings_);
  if (scene.robots().empty()) throw InputError("execution: the scene has no robot");
  robot_ = settings_.robot.empty() ? scene.robots().front().name : settings_.robot;
  model_ = scene.robot(robot_).model;
  manipulator_ = findManipulator(*model_, settings_.manipulator);
  gripper_ = std::make_shared<const GripperGeometry>(describeGripper(*model_, manipulator_.name));
  ik_ = makeIkSolver(settings_.ikSolver);
  (void)makeGraspPlanner(settings_.graspPlanner);
  for (const std::string& joint : manipulator_.armJoints) armVariables_.push_back(model_->variableIndex(joint));
  const auto first = std::make_shared<const FclCollisionChecker>(scene);
  for (std::size_t r = 0; r < scene.robots().size(); ++r) matrices_.push_back(first->sharedAllowedCollisions(static_cast<int>(r)));
  robotSpace_ = std::make_shared<const JointPlanningSpace>(first, std::vector<std::string>{robot_});
  for (const NamedState& state : model_->semantics().namedStates) {
    if (state.name == kHomeConfiguration) homeArm_ = armValues(*this, model_->namedConfiguration(kHomeConfiguration));
  }
}

VectorX ArmContext::withArm(VectorX q, const VectorX& arm) const { return withValues(armVariables_, std::move(q), arm); }

std::shared_ptr<const FclCollisionChecker> ArmContext::checkerFor(const Scene& world) const {
  FclCheckerSettings fcl;
  if (world.robots().size() == matrices_.size()) fcl.precomputedMatrices = matrices_;
  return std::make_shared<const FclCollisionChecker>(world, fcl);
}

ReachabilityChecker ArmContext::reachIn(const Scene& world) const {
  ReachSettings reach = settings_.reach;
  reach.seed = settings_.seed;
  return ReachabilityChecker(checkerFor(world), ik_, robot_, manipulator_.name, reach, gripper_);
}

Pose ArmContext::toolPose(const Scene& world, const VectorX& q) const {
  return world.robot(robot_).basePose * computeLinkPose(*model_, q, gripper_->toolFrame) * gripper_->graspFrame;
}

double ArmContext::gripperWidth(const VectorX& q) const {
  return gripperOpening(*model_, *gripper_, q);
}

namespace {

MotionResult planDirectTransit(const ArmContext& arm, const Scene& world, const VectorX& start,
                               const std::vector<VectorX>& goals, const std::string& planner, const std::string& label,
                               const StopCondition& stop, const std::vector<std::string>& joints = {}) {
  const auto checker = arm.checkerFor(world);
  const std::vector<std::string>& planned = joints.empty() ? arm.manipulator().armJoints : joints;
  std::vector<int> variables;
  for (const std::string& joint : planned) variables.push_back(arm.model().variableIndex(joint));
  auto space = std::make_shared<const JointPlanningSpace>(checker, std::vector<std::string>{arm.robotName()},
                                                          std::vector<std::vector<std::string>>{planned});
  const std::string name = planner.empty() ? arm.settings().defaultPlanner : planner;
  PlannerSettings settings;
  settings.setPlanner(name);
  settings.setParameter("_Max Planning Time", std::to_string(arm.settings().planningTimeSeconds));
  MotionPlanningOptions options;
  options.verificationResolution = arm.settings().verificationResolution;
  options.recordTreeEdges = arm.settings().recordTreeEdges;
  options.positionMargin = arm.settings().positionMargin;
  MotionPlanner motion(space, options);
  std::vector<VectorX> goalPoints;
  for (const VectorX& goal : goals) goalPoints.push_back(valuesOf(variables, goal));
  if (stop.shouldStop()) return failedMotion("motion", label + ": stopped before planning");
  MotionResult result;
  result.plannerCalls = 1;
  MotionPlan plan;
  try {
    plan = motion.solve(valuesOf(variables, start), goalPoints, settings, stop);
  } catch (const InputError& error) {
    return failedMotion("motion", std::string(label) + ": " + error.what());
  }
  if (!plan.solved()) {
    MotionResult failure = failedMotion("motion", label + ": " + motionPlanStatusName(plan.status) + ": " + plan.message);
    failure.plannerCalls = 1;
    failure.collisionChecks = plan.statistics.stateChecks;
    return failure;
  }
  MotionSegment segment;
  segment.label = label;
  segment.world = world;
  segment.planner = settings.planner();
  segment.plannedLength = plan.statistics.lengthBeforeSimplification;
  segment.simplifiedLength = plan.statistics.lengthAfterSimplification;
  result.plannerSolved = 1;
  result.collisionChecks = plan.statistics.stateChecks;
  for (const VectorX& x : plan.path) segment.waypoints.push_back(withValues(variables, start, x));
  for (const VectorX& x : plan.tree.vertices) segment.tree.vertices.push_back(withValues(variables, start, x));
  segment.tree.edges = std::move(plan.tree.edges);
  segment.tree.omittedEdges = plan.tree.omittedEdges;
  result.segment = std::move(segment);
  return result;
}

bool nearlyEqual(const VectorX& a, const VectorX& b) { return (a - b).cwiseAbs().maxCoeff() < 1e-6; }

/// start -> home -> goals, when home is free and differs from both ends.
MotionResult planTransitThroughHome(const ArmContext& arm, const Scene& world, const VectorX& start,
                                    const std::vector<VectorX>& goals, const std::string& planner, const std::string& label,
                                    const StopCondition& stop, MotionResult direct) {
  const VectorX home = arm.withArm(start, *arm.homeArm());
  if (nearlyEqual(home, start) || std::any_of(goals.begin(), goals.end(), [&](const VectorX& g) { return nearlyEqual(armValues(arm, g), *arm.homeArm()); })) {
    return direct;
  }
  MotionResult first = planDirectTransit(arm, world, start, {home}, planner, label + " (to home)", stop);
  if (!first.ok()) {
    first.plannerCalls += direct.plannerCalls;
    first.plannerSolved = 0;
    first.collisionChecks += direct.collisionChecks;
    first.reason = direct.reason + "; through home: " + first.reason;
    return first;
  }
  MotionResult second = planDirectTransit(arm, world, first.segment->waypoints.back(), goals, planner, label + " (from home)", stop);
  second.plannerCalls += first.plannerCalls + direct.plannerCalls;
  second.plannerSolved += first.plannerSolved;
  second.collisionChecks += first.collisionChecks + direct.collisionChecks;
  if (!second.ok()) {
    second.reason = direct.reason + "; through home: " + second.reason;
    return second;
  }
  auto& waypoints = first.segment->waypoints;
  waypoints.insert(waypoints.end(), second.segment->waypoints.begin() + 1, second.segment->waypoints.end());
  second.segment->waypoints = std::move(waypoints);
  second.segment->label = label + " (through home)";
  second.segment->plannedLength += first.segment->plannedLength;
  second.segment->simplifiedLength += first.segment->simplifiedLength;
  return second;
}

/// The straight tool motion planCartesian() follows, in the arm's base frame.
struct CartesianLine {
  const ArmContext& arm;
  Pose X_WB;
  Pose from;
  Pose to;
  const std::string& label;
  int steps;

  [[nodiscard]] Pose at(double t) const {
    Pose X_WG = Pose::Identity();
    X_WG.linear() = Quaternion(from.linear()).slerp(t, Quaternion(to.linear())).toRotationMatrix();
    X_WG.translation() = from.translation() + t * (to.translation() - from.translation());
    return X_WG;
  }
};

/// A step whose joints would move more than the limit is halved up to this many times: near a
/// singularity the joints move fast and smaller steps keep them continuous, while a change of IK
/// branch jumps however small the step.
constexpr int kCartesianHalvings = 3;

/// Appends the IK solution of the line at `t1` (seeded from the last waypoint), halving the step
/// from `t0` while the joints would jump; false with `result` failed otherwise.
bool appendCartesianStep(const CartesianLine& line, double t0, double t1, int halvings, std::vector<VectorX>& waypoints,
                         MotionResult& result) {
  const ExecutionSettings& s = line.arm.settings();
  IkRequest request;
  request.model = &line.arm.model();
  request.manipulator = line.arm.manipulator().name;
  request.target = IkTarget::pose(line.X_WB.inverse() * line.at(t1) * line.arm.gripper().graspFrame.inverse());
  request.seed = waypoints.back();
  request.timeoutSeconds = s.reach.ikTimeoutSeconds;
  request.randomSeed = s.seed;
  ++result.ikCalls;
  const IkResult ik = line.arm.ik()->solve(request);
  const int step = static_cast<int>(std::ceil(t1 * line.steps - 1e-9));
  const std::string where = " at step " + std::to_string(step) + " of " + std::to_string(line.steps);
  if (ik.status != IkStatus::kSuccess) {
    const int calls = result.ikCalls;
    result = failedMotion("ik", line.label + ": no IK solution" + where + " (" + ikStatusName(ik.status) + ")");
    result.ikCalls = calls;
    return false;
  }
  const VectorX& q = ik.solutions.front();
  const double jump = (armValues(line.arm, q) - armValues(line.arm, waypoints.back())).cwiseAbs().maxCoeff();
  if (jump <= s.maxJointStep) {
    waypoints.push_back(q);
    return true;
  }
  if (halvings > 0) {
    const double middle = 0.5 * (t0 + t1);
    return appendCartesianStep(line, t0, middle, halvings - 1, waypoints, result) &&
           appendCartesianStep(line, middle, t1, halvings - 1, waypoints, result);
  }
  char text[160];
  std::snprintf(text, sizeof text, ": the arm would jump %.2f rad%s (limit %.2f)", jump, where.c_str(), s.maxJointStep);
  const int calls = result.ikCalls;
  result = failedMotion("ik", line.label + text);
  result.ikCalls = calls;
  return false;
}

}  // namespace

MotionResult planTransit(const ArmContext& arm, const Scene& world, const VectorX& start,
                         const std::vector<VectorX>& goals, const std::string& planner, const std::string& label,
                         const StopCondition& stop, const std::vector<std::string>& joints) {
  MotionResult direct = planDirectTransit(arm, world, start, goals, planner, label, stop, joints);
  if (direct.ok() || !joints.empty() || direct.stage != "motion" || !arm.homeArm() || stop.shouldStop()) return direct;
  return planTransitThroughHome(arm, world, start, goals, planner, label, stop, std::move(direct));
}

MotionResult planCartesian(const ArmContext& arm, const Scene& world, const VectorX& start, const Pose& X_WG_goal,
                           const std::string& label, const CartesianAllowance& allowance) {
  const ExecutionSettings& s = arm.settings();
  const Pose X_WG_start = arm.toolPose(world, start);
  const double distance = (X_WG_goal.translation() - X_WG_start.translation()).norm();
  const Quaternion from(X_WG_start.linear()), to(X_WG_goal.linear());
  const double angle = from.angularDistance(to);
  const int steps = std::max(1, static_cast<int>(std::ceil(std::max(distance / s.cartesianStep, angle / s.cartesianAngleStep))));
  const SceneRobot& robot = world.robot(arm.robotName());
  const Pose X_WB = robot.basePose * computeLinkPose(arm.model(), start, arm.manipulator().baseLink);
  MotionResult result;
  MotionSegment segment;
  segment.label = label;
  segment.world = world;
  segment.allowedContacts = allowance.allowedContacts;
  segment.carried = allowance.carried;
  segment.carriedStart = allowance.carriedStart;
  segment.carriedDisplacement = allowance.carriedDisplacement;
  segment.waypoints.push_back(start);
  const auto began = std::chrono::steady_clock::now();
  const CartesianLine line{arm, X_WB, X_WG_start, X_WG_goal, label, steps};
  for (int i = 1; i <= steps; ++i) {
    if (!appendCartesianStep(line, static_cast<double>(i - 1) / steps, static_cast<double>(i) / steps, kCartesianHalvings,
                             segment.waypoints, result)) {
      return result;
    }
  }
  result.ikSeconds = secondsSince(began);
  const SegmentCheck check = checkSegment(arm, segment, s.verificationResolution);
  result.collisionChecks = check.checks;
  if (!check.collision.empty()) {
    MotionResult failure = failedMotion("motion", label + ": " + check.collision);
    failure.ikCalls = result.ikCalls;
    failure.ikSeconds = result.ikSeconds;
    failure.collisionChecks = check.checks;
    return failure;
  }
  result.segment = std::move(segment);
  return result;
}

std::vector<std::pair<std::string, std::string>> fingerContacts(const ArmContext& arm, const std::string& object) {
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const std::string& link : arm.gripper().fingerLinks) pairs.emplace_back(object, arm.robotName() + "/" + link);
  return pairs;
}

CartesianAllowance fingersMayTouch(const ArmContext& arm, const std::string& object) {
  CartesianAllowance allowance;
  allowance.allowedContacts = fingerContacts(arm, object);
  return allowance;
}

MotionSegment gripperMotion(const ArmContext& arm, const Scene& world, const VectorX& start, double width,
                            const std::string& label, std::vector<std::pair<std::string, std::string>> allowedContacts) {
  MotionSegment segment;
  segment.label = label;
  segment.world = world;
  segment.allowedContacts = std::move(allowedContacts);
  segment.waypoints = {start, withGripperOpening(arm.model(), arm.gripper(), start, width)};
  return segment;
}

namespace {

/// Whether a finger of the arm touches `object` at configuration `q`.
bool fingersTouch(const ArmContext& arm, const FclCollisionChecker& checker, CollisionContext& context, const VectorX& q,
                  const std::string& object) {
  const CollisionReport report = checker.checkState(checker.robotIndex(arm.robotName()), q, {}, context);
  for (const CollisionContact& contact : report.contacts) {
    const std::string& other = contact.first == object ? contact.second : contact.second == object ? contact.first : object;
    for (const std::string& finger : arm.gripper().fingerLinks) {
      if (other == arm.robotName() + "/" + finger) return true;
    }
  }
  return false;
}

}  // namespace

MotionResult closeGripperOn(const ArmContext& arm, const Scene& world, const VectorX& start, const std::string& object,
                            const std::string& label) {
  constexpr int kBisections = 12;
  const auto checker = arm.checkerFor(world);
  const auto context = checker->makeContext();
  const GripperGeometry& gripper = arm.gripper();
  double free = gripperFraction(arm.model(), gripper, start);
  double touching = 0.0;
  MotionResult result;
  result.collisionChecks = 1;
  if (!fingersTouch(arm, *checker, *context, withGripperFraction(arm.model(), gripper, start, touching), object)) {
    return failedMotion("grasp", label + ": the fingers close fully without touching " + object);
  }
  for (int i = 0; i < kBisections && free > touching; ++i) {
    const double middle = 0.5 * (free + touching);
    ++result.collisionChecks;
    (fingersTouch(arm, *checker, *context, withGripperFraction(arm.model(), gripper, start, middle), object) ? touching : free) =
        middle;
  }
  MotionSegment segment;
  segment.label = label;
  segment.world = world;
  segment.gripperEvent = GripperEvent::kGrasp;
  segment.allowedContacts = fingerContacts(arm, object);
  segment.waypoints = {start, withGripperFraction(arm.model(), gripper, start, free)};
  result.segment = std::move(segment);
  return result;
}

SegmentStateChecker::SegmentStateChecker(const ArmContext& arm, const MotionSegment& segment)
    : segment_(&segment), checker_(arm.checkerFor(robotCheckWorld(segment))),
      robot_(checker_->robotIndex(arm.robotName())), context_(checker_->makeContext()) {}

std::string SegmentStateChecker::forbiddenContacts(const VectorX& q) {
  ++checks_;
  if (checker_->isStateValid(robot_, q, *context_)) return {};
  return contactsText(lang2manip::forbiddenContacts(*checker_, robot_, q, *segment_, *context_));
}

std::string carriedSweepCollision(const MotionSegment& segment) {
  if (segment.carried.empty()) return {};
  std::string carried = findCarriedCollision(segment);
  return carried.empty() ? carried : segment.label + ": " + carried;
}

SegmentCheck checkSegment(const ArmContext& arm, const MotionSegment& segment, double resolution) {
  SegmentCheck result;
  if (std::string carried = carriedSweepCollision(segment); !carried.empty()) return {carried, 0};
  SegmentStateChecker checker(arm, segment);
  for (std::size_t w = 0; w + 1 < segment.waypoints.size() || (w == 0 && segment.waypoints.size() == 1); ++w) {
    const VectorX& q0 = segment.waypoints[w];
    const VectorX& q1 = segment.waypoints[std::min(w + 1, segment.waypoints.size() - 1)];
    const double span = (q1 - q0).cwiseAbs().maxCoeff();
    const int steps = std::max(1, static_cast<int>(std::ceil(span / resolution)));
    for (int i = 0; i <= steps; ++i) {
      const VectorX q = q0 + (q1 - q0) * (static_cast<double>(i) / steps);
      std::string contacts = checker.forbiddenContacts(q);
      if (contacts.empty()) continue;
      result.checks = checker.checks();
      result.collision = segment.label + ", waypoint " + std::to_string(w) + " " + armPart(armValues(arm, q)) + ": " + contacts;
      return result;
    }
  }
  result.checks = checker.checks();
  return result;
}

}  // namespace lang2manip
