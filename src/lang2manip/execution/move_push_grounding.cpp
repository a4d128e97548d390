// Move and push (see action_grounding.hpp).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/execution/action_grounding.hpp"
#include "lang2manip/grounding/object_geometry.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"

namespace lang2manip {
namespace {

/// The fingertips pass this far above the support while pushing, at most, and at most this
/// fraction of the object's height.
constexpr double kFingertipClearance = 0.005;
constexpr double kFingertipHeightFraction = 0.4;

std::optional<GroundingAttempt> finish(GroundingAttempt attempt, ActionExecution& record) {
  if (attempt.stage.empty()) return attempt;
  return refuse(record, attempt.stage, attempt.reason);
}

/// R_WG with the tool's approach axis along world `approach` and its closing axis along world
/// `closing` (both unit, perpendicular).
Matrix3 toolOrientation(const GripperGeometry& gripper, const Vector3& approach, const Vector3& closing) {
  const Vector3 a = gripper.approachAxis.normalized();
  const Vector3 c = (gripper.closingAxis - gripper.closingAxis.dot(a) * a).normalized();
  Matrix3 inGripper;
  inGripper << a, c, a.cross(c);
  Matrix3 inWorld;
  inWorld << approach, closing, approach.cross(closing);
  return inWorld * inGripper.transpose();
}

/// How far `box` (in H) reaches from H along world direction `direction` with H at rotation
/// R_WG (its support function).
double boxReachAlong(const AlignedBox3& box, const Matrix3& R_WG, const Vector3& direction) {
  const Vector3 d = R_WG.transpose() * direction;
  double reach = 0.0;
  for (int i = 0; i < 3; ++i) reach += std::max(box.min()[i] * d[i], box.max()[i] * d[i]);
  return reach;
}

/// How far the hand (fingers and every shape of the hand) reaches from H along `direction`.
double handReachAlong(const GripperGeometry& gripper, const Matrix3& R_WG, const Vector3& direction) {
  double reach = boxReachAlong(gripper.fingerBounds, R_WG, direction);
  for (const AlignedBox3& box : gripper.closedHandBounds) reach = std::max(reach, boxReachAlong(box, R_WG, direction));
  return reach;
}

/// How far the parts of the hand that meet a pushed object reach from H along `direction` (the
/// push), with H at height `z`: the fingers, and the shapes of the hand and the wrist that come
/// lower than `objectTop` (the others pass over the object).
double pushingReachAlong(const GripperGeometry& gripper, const Matrix3& R_WG, const Vector3& direction, double z, double objectTop) {
  const Vector3 down = -Vector3::UnitZ();
  double reach = boxReachAlong(gripper.fingerBounds, R_WG, direction);
  for (const auto* boxes : {&gripper.closedHandBounds, &gripper.wristBounds}) {
    for (const AlignedBox3& box : *boxes) {
      if (z - boxReachAlong(box, R_WG, down) < objectTop) reach = std::max(reach, boxReachAlong(box, R_WG, direction));
    }
  }
  return reach;
}

/// The tool pose behind `object` that pushes it along `direction` (horizontal, unit): first with
/// the approach axis pointing down and the fingertips just above the support, then with the
/// approach axis along the push (the tool's face pushes, for arms that cannot reach over the
/// object pointing down), closing axis across and then vertical; each also turned half a turn
/// about the approach axis (a tool is symmetric enough to push alike).
std::vector<Pose> pushContacts(const ArmContext& arm, const Scene& world, const SceneObject& object, const Vector3& direction) {
  const SceneObject* support = currentSupport(world, object, kSupportTolerance);
  const AlignedBox3 bounds = object.worldBounds();
  const double supportTop = support != nullptr ? support->worldBounds().max().z() : bounds.min().z();
  const double height = bounds.max().z() - supportTop;
  const Vector3 down = -Vector3::UnitZ();
  const Vector3 across = Vector3::UnitZ().cross(direction).normalized();
  const double halfExtent = halfExtentAlong(object, object.pose, direction);
  const Vector3 centre = objectCentre(object, object.pose);
  std::vector<Pose> contacts;
  const auto add = [&](const Matrix3& R_WG, double z) {
    for (const Matrix3& R : {R_WG, Matrix3(R_WG * Eigen::AngleAxisd(M_PI, arm.gripper().approachAxis).toRotationMatrix())}) {
      Pose contact = Pose::Identity();
      contact.linear() = R;
      const double reach = pushingReachAlong(arm.gripper(), R, direction, z, bounds.max().z());
      contact.translation() = centre - direction * (halfExtent + reach + arm.settings().pushStandoff);
      contact.translation().z() = z;
      contacts.push_back(contact);
    }
  };
  const Matrix3 topDown = toolOrientation(arm.gripper(), down, across);
  add(topDown, supportTop + std::min(kFingertipClearance, kFingertipHeightFraction * height) + arm.gripper().fingertipOffset());
  for (const Vector3& closing : {across, Vector3(Vector3::UnitZ())}) {
    const Matrix3 R_WG = toolOrientation(arm.gripper(), direction, closing);
    const double below = handReachAlong(arm.gripper(), R_WG, down);
    const double z = std::max(centre.z(), supportTop + kFingertipClearance + below);
    // The face must meet the object below its top, not pass over it.
    if (z - below <= bounds.max().z() - kFingertipHeightFraction * height) add(R_WG, z);
  }
  return contacts;
}

Pose raised(const Pose& pose, double height) {
  Pose result = pose;
  result.translation().z() += height;
  return result;
}

Pose shifted(const Pose& pose, const Vector3& offset) {
  Pose result = pose;
  result.translation() += offset;
  return result;
}

/// The joints a named configuration sets, but the executing arm's gripper (a held object stays
/// held); for a robot with several arms "home" moves all of them.
std::vector<std::string> namedConfigurationJoints(const ArmContext& arm, const std::string& name) {
  std::vector<std::string> joints = arm.manipulator().armJoints;
  const auto& gripper = arm.gripper().gripperJoints;
  for (const NamedState& state : arm.model().semantics().namedStates) {
    if (state.name != name) continue;
    for (const auto& [joint, value] : state.values) {
      const auto index = arm.model().findJoint(joint);
      const bool variable = index && arm.model().variableOfJoint(*index) >= 0;
      if (variable && std::find(joints.begin(), joints.end(), joint) == joints.end() &&
          std::find(gripper.begin(), gripper.end(), joint) == gripper.end()) {
        joints.push_back(joint);
      }
    }
  }
  return joints;
}

std::optional<GroundingAttempt> moveToConfiguration(const GroundingContext& c, const Scene& world, const SymbolicAction& action,
                                                    ActionExecution& record) {
  const ArmContext& arm = c.arm;
  const std::string& name = action.params.configuration;
  const VectorX named = arm.model().namedConfiguration(name);
  const std::vector<std::string> joints = namedConfigurationJoints(arm, name);
  GroundingAttempt a(arm, world);
  VectorX goal = a.q;
  for (const std::string& joint : joints) goal[arm.model().variableIndex(joint)] = named[arm.model().variableIndex(joint)];
  record.choice = name;
  a.add(arm, planTransit(arm, a.world, a.q, {goal}, action.planner, "transit to " + name, c.stop,
                         joints.size() == arm.manipulator().armJoints.size() ? std::vector<std::string>{} : joints),
        c.counters, record.times);
  return finish(std::move(a), record);
}

std::optional<GroundingAttempt> moveToPose(const GroundingContext& c, const Scene& world, const SymbolicAction& action,
                                           ActionExecution& record) {
  const ArmContext& arm = c.arm;
  GroundingAttempt a(arm, world);
  const Pose X_WB = robotBaseFrame(world, arm.robotName());
  const Pose current = X_WB.inverse() * arm.toolPose(world, a.q);
  Pose X_BG = Pose::Identity();
  X_BG.linear() = action.params.orientation ? action.params.orientation->normalized().toRotationMatrix() : current.linear();
  X_BG.translation() = *action.params.position;
  const ReachabilityChecker reach = arm.reachIn(world);
  const ReachResult goals = reach.reach(X_WB * X_BG, a.q, arm.gripperWidth(a.q));
  c.counters.ikCalls += reach.statistics().ikCalls;
  c.counters.collisionChecks += reach.statistics().collisionChecks;
  if (!goals.reachable()) return refuse(record, "ik", "move to the tool pose: " + goals.reason);
  record.choice = "tool pose";
  a.add(arm, planTransit(arm, a.world, a.q, goals.solutions, action.planner, "transit to the tool pose", c.stop), c.counters,
        record.times);
  return finish(std::move(a), record);
}

/// One push with the tool at `contact` (see action_grounding.hpp); the attempt says why not.
GroundingAttempt tryPush(const GroundingContext& c, const Scene& world, const SceneObject& object, const Vector3& direction,
                         double distance, const Pose& contact, const SymbolicAction& action, ActionExecution& record) {
  const ArmContext& arm = c.arm;
  const Pose above = raised(contact, arm.settings().pushApproachHeight);
  const Pose end = shifted(contact, direction * (distance + arm.settings().pushStandoff));
  GroundingAttempt a(arm, world);
  if (arm.gripperWidth(a.q) > 1e-4 && !a.add(arm, gripperMotion(arm, a.world, a.q, 0.0, "close gripper to push"), c.counters)) {
    return a;
  }
  const ReachabilityChecker reach = arm.reachIn(a.world);
  const ReachResult start = reach.reach(above, a.q, 0.0);
  c.counters.ikCalls += reach.statistics().ikCalls;
  c.counters.collisionChecks += reach.statistics().collisionChecks;
  if (!start.reachable()) {
    a.stage = "ik";
    a.reason = "the pose above the contact: " + start.reason;
    return a;
  }
  if (!a.add(arm, planTransit(arm, a.world, a.q, start.solutions, action.planner, "transit above " + object.name, c.stop),
             c.counters, record.times) ||
      !a.add(arm, planCartesian(arm, a.world, a.q, contact, "descend behind " + object.name), c.counters, record.times)) {
    return a;
  }
  CartesianAllowance carry;
  carry.carried = object.name;
  carry.carriedStart = object.pose;
  carry.carriedDisplacement = direction * distance;
  if (!a.add(arm, planCartesian(arm, a.world, a.q, end, "push " + object.name + " " + metresText(distance), carry), c.counters,
             record.times)) {
    a.stage = "push";
    return a;
  }
  a.world.object(object.name).pose = shifted(object.pose, direction * distance);
  const double rise = arm.settings().pushRetreat;
  addFirstCartesian(c, a,
                    {raised(end, rise), raised(shifted(end, -direction * rise * std::sqrt(0.5)), rise * std::sqrt(0.5)),
                     raised(end, rise / 2.0)},
                    "retreat from " + object.name, fingersMayTouch(arm, object.name), record.times);
  return a;
}

}  // namespace

std::optional<GroundingAttempt> groundMove(const GroundingContext& c, const Scene& world, const SymbolicAction& action,
                                           ActionExecution& record) {
  if (!action.object.empty()) {
    const Attachment* held = world.findAttachment(action.object);
    if (held == nullptr || held->robot != c.arm.robotName()) {
      return refuse(record, "precondition", "cannot move " + action.object + ": it is not held");
    }
  }
  if (!action.params.configuration.empty()) return moveToConfiguration(c, world, action, record);
  if (action.params.position) return moveToPose(c, world, action, record);
  return refuse(record, "precondition", "move needs a named configuration or a tool position");
}

std::optional<GroundingAttempt> groundPush(const GroundingContext& c, const Scene& world, const SymbolicAction& action,
                                           ActionExecution& record) {
  const ArmContext& arm = c.arm;
  const SceneObject& object = world.object(action.object);
  if (world.findAttachment(object.name) != nullptr) return refuse(record, "precondition", "cannot push " + object.name + ": it is held");
  if (!object.movable) return refuse(record, "precondition", "cannot push " + object.name + ": it is not movable");
  if (const Attachment* held = heldByRobot(world, arm.robotName())) {
    return refuse(record, "precondition", "cannot push " + object.name + ": the gripper holds " + held->object);
  }
  if (!action.params.direction || !action.params.distance || !(*action.params.distance > 0.0)) {
    return refuse(record, "precondition", "push of " + object.name + " needs a direction and a positive distance");
  }
  Vector3 direction = robotBaseFrame(world, arm.robotName()).linear() * *action.params.direction;
  direction.z() = 0.0;
  if (direction.norm() < 1e-6) return refuse(record, "precondition", "push of " + object.name + ": the direction is vertical");
  direction.normalize();
  const double distance = *action.params.distance;
  std::string failures, stage;
  for (const Pose& contact : pushContacts(arm, world, object, direction)) {
    GroundingAttempt a = tryPush(c, world, object, direction, distance, contact, action, record);
    if (a.stage.empty()) {
      record.choice = "contact behind " + object.name + ", " + metresText(distance);
      return a;
    }
    if (stage.empty() || stage == "ik") stage = a.stage;
    if (failures.find(a.reason) == std::string::npos) failures += (failures.empty() ? "" : "; ") + a.reason;
  }
  return refuse(record, stage, "push of " + object.name + ": " + failures);
}

}  // namespace lang2manip
