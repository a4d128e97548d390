#include "lang2manip/symbolic/spatial_relations.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/model/scene.hpp"
#include "lang2manip/symbolic/arrangement_check.hpp"
#include "lang2manip/symbolic/object_heading.hpp"
#include "lang2manip/symbolic/plan_validation.hpp"
#include "lang2manip/symbolic/surface_region.hpp"

namespace lang2manip {
namespace {

const SceneObject& objectNamed(const Scene& scene, const std::string& name, const std::string& role) {
  const SceneObject* object = scene.findObject(name);
  if (object == nullptr) {
    std::string names;
    for (const SceneObject& o : scene.objects()) names += (names.empty() ? "" : ", ") + o.name;
    throw InputError("goal " + role + ": unknown object \"" + name + "\" (objects: " + names + ")");
  }
  return *object;
}

/// Offset of `a`'s centre from `b`'s centre in the base frame.
Vector3 centreOffset(const Pose& base, const SceneObject& a, const SceneObject& b) {
  return base.linear().transpose() * (a.worldBounds().center() - b.worldBounds().center());
}

/// The signed offset along the side a relation names (positive when on that side).
double offsetAlong(SpatialRelation relation, const Vector3& offset) {
  switch (relation) {
    case SpatialRelation::kLeftOf: return offset.y();
    case SpatialRelation::kRightOf: return -offset.y();
    case SpatialRelation::kInFrontOf: return offset.x();
    case SpatialRelation::kBehind: return -offset.x();
    default: return 0.0;
  }
}

/// The offset across that side (horizontal, unsigned): how far the object stands off the line
/// through the reference along the side.
double offsetAcross(SpatialRelation relation, const Vector3& offset) {
  const bool sideways = relation == SpatialRelation::kLeftOf || relation == SpatialRelation::kRightOf;
  return std::abs(sideways ? offset.x() : offset.y());
}


GoalCheck checkSide(const Goal& goal, const Vector3& offset, const SpatialOptions& options) {
  const double along = offsetAlong(*goal.relation, offset);
  const std::string words = goal.object + " is " + metresText(along) + " " + spatialRelationWords(*goal.relation) + " " + goal.target;
  if (goal.distance) {  // "10 cm to the right of X": the whole offset, not its component alone
    const double across = offsetAcross(*goal.relation, offset);
    const bool holds = std::abs(along - *goal.distance) <= options.distanceTolerance && across <= options.distanceTolerance;
    return {holds, words + " and " + metresText(across) + " off the line through it (wanted " + metresText(*goal.distance) + " and 0)"};
  }
  return {along > options.directionMargin, words};
}

GoalCheck checkNextTo(const Goal& goal, const SceneObject& a, const SceneObject& b, const SpatialOptions& options) {
  const double gap = boxGap(a.worldBounds(), b.worldBounds());
  const double limit = goal.distance ? *goal.distance + options.distanceTolerance : options.nearDistance;
  return {gap <= limit, goal.object + " is " + metresText(gap) + " from " + goal.target + " (at most " + metresText(limit) + ")"};
}

GoalCheck checkDisplaced(const Scene& scene, const Goal& goal, const GoalCheckOptions& options) {
  if (options.initialScene == nullptr) {
    throw InputError("goal \"" + describeGoal(goal) + "\": a displacement needs the initial scene");
  }
  const Pose base = robotBaseFrame(scene, options.robot);
  const Vector3 before = objectNamed(*options.initialScene, goal.object, "object").pose.translation();
  const Vector3 after = objectNamed(scene, goal.object, "object").pose.translation();
  const Vector3 moved = base.linear().transpose() * (after - before);
  const double error = (moved - goal.displacement).norm();
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "%s moved by (%.3f, %.3f, %.3f) m, %.3f m from the wanted displacement",
                goal.object.c_str(), moved.x(), moved.y(), moved.z(), error);
  return {error <= options.spatial.distanceTolerance, buffer};
}

/// The object frame's origin within distanceTolerance of the wanted position (x and y in the
/// base frame).
GoalCheck checkAtPosition(const Scene& scene, const Goal& goal, const GoalCheckOptions& options) {
  if (!goal.position) throw InputError("goal \"" + describeGoal(goal) + "\": no position");
  const Pose base = robotBaseFrame(scene, options.robot);
  const Vector3 at = base.inverse() * objectNamed(scene, goal.object, "object").pose.translation();
  const double off = (at - *goal.position).head<2>().norm();
  if (scene.findAttachment(goal.object) != nullptr) return {false, goal.object + " is held, not standing anywhere"};
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "%s stands at (%.3f, %.3f), %.3f m from the wanted position", goal.object.c_str(), at.x(), at.y(),
                off);
  return {off <= options.spatial.distanceTolerance, buffer};
}

/// Turned by the wanted angle about the vertical (up to the object's symmetry and
/// kTurnTolerance), not tilted, and standing where it stood (within distanceTolerance).
GoalCheck checkTurned(const Scene& scene, const Goal& goal, const GoalCheckOptions& options) {
  if (options.initialScene == nullptr) throw InputError("goal \"" + describeGoal(goal) + "\": a turn needs the initial scene");
  const SceneObject& before = objectNamed(*options.initialScene, goal.object, "object");
  const SceneObject& after = objectNamed(scene, goal.object, "object");
  if (scene.findAttachment(goal.object) != nullptr) return {false, goal.object + " is held, not standing turned"};
  const TurnBetween turn = turnBetween(before.pose.linear(), after.pose.linear());
  const double symmetry = turnSymmetry(before);
  const double error = std::abs(reducedAngle(turn.yaw - goal.angle, symmetry == 0.0 ? 2.0 * 3.14159265358979323846 : symmetry));
  // Where it stands: where it stood, or where the instruction put it before turning it.
  const Vector3 origin = robotBaseFrame(scene, options.robot).inverse() * after.pose.translation();
  const double shift = goal.position ? (origin - *goal.position).head<2>().norm()
                                     : (after.pose.translation() - before.pose.translation()).head<2>().norm();
  const bool holds = error <= kTurnTolerance && turn.tilt <= kTurnTolerance && shift <= options.spatial.distanceTolerance;
  return {holds, goal.object + " turned by " + degreesText(turn.yaw) + " (" + degreesText(error) + " from the wanted turn), tilted by " +
                     degreesText(turn.tilt) + ", moved " + metresText(shift)};
}

/// The object's centre (x, y, base frame) within the region of the target's reachable top face,
/// up to half the distance tolerance.
GoalCheck checkRegion(const Scene& scene, const Goal& goal, const GoalCheckOptions& options) {
  std::string why;
  const auto box = regionOnSupport(scene, goal.target, *goal.region, options.robot, &why, options.arm);
  const std::string name = surfaceRegionName(*goal.region);
  if (!box) return {false, goal.target + " has no " + name + ": " + why};
  const Pose base = robotBaseFrame(scene, options.robot);
  const Vector3 centre = base.inverse() * objectNamed(scene, goal.object, "object").worldBounds().center();
  const double slack = options.spatial.distanceTolerance / 2.0;
  const Vector3 outside = (box->min() - centre).cwiseMax(centre - box->max()).cwiseMax(0.0);
  const double off = outside.head<2>().norm();
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "%s stands at (%.3f, %.3f), %.3f m from the %s of %s", goal.object.c_str(), centre.x(),
                centre.y(), off, name.c_str(), goal.target.c_str());
  return {off <= slack, buffer};
}

/// The long side's line passes within kTurnTolerance of the target's centre (seen from above), or
/// lies along the wanted heading (base frame).
GoalCheck checkFacing(const Scene& scene, const Goal& goal, const GoalCheckOptions& options) {
  const SceneObject& object = objectNamed(scene, goal.object, "object");
  if (goal.target.empty()) {
    if (scene.findAttachment(goal.object) != nullptr) return {false, goal.object + " is held, not standing pointed"};
    const Matrix3 toBase = robotBaseFrame(scene, options.robot).linear().transpose();
    const std::optional<double> side = longSideYaw(object, toBase * object.pose.linear());
    if (!side) return {false, goal.object + " has no long side to point with"};
    const double error = std::abs(reducedAngle(goal.angle - *side, 3.14159265358979323846));
    return {error <= kTurnTolerance, goal.object + "'s long side is " + degreesText(error) + " off the wanted direction"};
  }
  const SceneObject& target = objectNamed(scene, goal.target, "target");
  if (scene.findAttachment(goal.object) != nullptr) return {false, goal.object + " is held, not standing pointed"};
  const std::optional<double> side = longSideYaw(object, object.pose.linear());
  if (!side) return {false, goal.object + " has no long side to point with"};
  const Vector3 toward = target.worldBounds().center() - object.worldBounds().center();
  const double bearing = std::atan2(toward.y(), toward.x());
  const double error = std::abs(reducedAngle(bearing - *side, 3.14159265358979323846));
  return {error <= kTurnTolerance, goal.object + "'s long side is " + degreesText(error) + " off the direction to " + goal.target};
}

std::string locationWords(const std::string& object, const SymbolicState& state) {
  if (state.held == object) return "held";
  if (auto it = state.inside.find(object); it != state.inside.end()) return "in " + it->second;
  if (auto it = state.onTopOf.find(object); it != state.onTopOf.end()) return "on " + it->second;
  return "not on anything";
}

GoalCheck checkSymbolic(const Scene& scene, const Goal& goal, const GoalCheckOptions& options) {
  const SymbolicState state = observeSymbolicState(scene, options.tolerances, options.robot, options.arm);
  const bool holds = goalHolds(state, goal).value_or(false);
  std::string explanation = describeGoal(goal) + (holds ? ": holds" : ": does not hold");
  if (!holds && goal.kind == GoalKind::kRelation) explanation += " (" + goal.object + " is " + locationWords(goal.object, state) + ")";
  if (!holds && goal.kind == GoalKind::kHolding) explanation += state.held.empty() ? " (the gripper is empty)" : " (holding " + state.held + ")";
  if (!holds && goal.kind == GoalKind::kAtConfiguration) {
    explanation += state.atConfiguration.empty() ? " (at no named configuration)" : " (at " + state.atConfiguration + ")";
  }
  return {holds, explanation};
}

}  // namespace

std::string spatialConventions(const SpatialOptions& spatial, const SymbolicStateTolerances& tolerances) {
  return "directions are in the robot's base frame: front = +x (away from the robot), left = +y, up = +z; "
         "A left_of/right_of/in_front_of/behind B when the centre of A's bounding box is more than " +
         metresText(spatial.directionMargin) + " further that way than B's centre; A next_to B when their boxes come within " +
         metresText(spatial.nearDistance) + "; A on B when A's bottom rests within " + metresText(tolerances.contactGap) +
         " of B's top (flat tops only: nothing rests on a round top or on a container, which takes things in); A in B when A's "
         "centre lies in B's cavity; explicit distances, displacements and positions are met within " +
         metresText(spatial.distanceTolerance) + "; turns are about the vertical, positive counter-clockwise seen from above "
         "(toward the left), met within " + degreesText(kTurnTolerance) + "; a turn that leaves an object looking the same "
         "(its shape's symmetry) is no turn; regions of a support's top (region of an on relation) are of the part of it the arm "
         "reaches, split in thirds along x (near = bottom = back, toward the robot; far = top = front) and y (right, left): a "
         "corner is a corner third, an edge (side) the middle third along that edge, the centre the middle third; halves and "
         "quadrants split it in two; an object is in a region when its centre is, within " +
         metresText(spatial.distanceTolerance / 2.0);
}

Pose robotBaseFrame(const Scene& scene, const std::string& robot) {
  if (!robot.empty()) return scene.robot(robot).basePose;
  return scene.robots().empty() ? Pose::Identity() : scene.robots().front().basePose;
}

double boxGap(const AlignedBox3& a, const AlignedBox3& b) {
  const Vector3 separation = (a.min() - b.max()).cwiseMax(b.min() - a.max()).cwiseMax(0.0);
  return separation.norm();
}

std::vector<SpatialRelation> directionalRelations(const Vector3& offset, double margin) {
  std::vector<SpatialRelation> relations;
  if (offset.y() > margin) relations.push_back(SpatialRelation::kLeftOf);
  if (offset.y() < -margin) relations.push_back(SpatialRelation::kRightOf);
  if (offset.x() > margin) relations.push_back(SpatialRelation::kInFrontOf);
  if (offset.x() < -margin) relations.push_back(SpatialRelation::kBehind);
  return relations;
}

GoalCheck checkGoalInScene(const Scene& scene, const Goal& goal, const GoalCheckOptions& options) {
  if (goal.kind == GoalKind::kDisplaced) return checkDisplaced(scene, goal, options);
  if (goal.kind == GoalKind::kAtPosition) return checkAtPosition(scene, goal, options);
  if (goal.kind == GoalKind::kTurned) return checkTurned(scene, goal, options);
  if (goal.kind == GoalKind::kFacing) return checkFacing(scene, goal, options);
  if (goal.kind == GoalKind::kArranged) return checkArranged(scene, goal, options);
  if (goal.kind == GoalKind::kHandedOver) {
    throw InputError("goal \"" + describeGoal(goal) + "\": where the tool is needs the robot's kinematics (verifyExecution checks it)");
  }
  if (goal.kind != GoalKind::kRelation) {
    if (goal.kind == GoalKind::kHolding) objectNamed(scene, goal.object, "object");
    return checkSymbolic(scene, goal, options);
  }
  const SceneObject& a = objectNamed(scene, goal.object, "object");
  const SceneObject& b = objectNamed(scene, goal.target, "target");
  if (!goal.relation) throw InputError("goal \"" + describeGoal(goal) + "\": no relation");
  switch (*goal.relation) {
    case SpatialRelation::kIn:
      return checkSymbolic(scene, goal, options);
    case SpatialRelation::kOn: {
      Goal resting = goal;
      resting.region.reset();
      GoalCheck on = checkSymbolic(scene, resting, options);
      if (!on.holds || !goal.region) return on;
      return checkRegion(scene, goal, options);
    }
    case SpatialRelation::kNextTo:
      return checkNextTo(goal, a, b, options.spatial);
    default:
      return checkSide(goal, centreOffset(robotBaseFrame(scene, options.robot), a, b), options.spatial);
  }
}

}  // namespace lang2manip
