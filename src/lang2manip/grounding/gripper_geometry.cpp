#include "lang2manip/grounding/gripper_geometry.hpp"

#include <algorithm>
#include <cmath>

#include "lang2manip/core/error.hpp"
#include "lang2manip/grounding/object_geometry.hpp"

namespace lang2manip {
namespace {

/// Joints driven by gripper variable joint `source` (itself and its mimics).
std::vector<int> drivenJoints(const RobotModel& model, int source) {
  std::vector<int> joints{source};
  const int variable = model.variableOfJoint(source);
  for (int j = 0; j < static_cast<int>(model.joints().size()); ++j) {
    if (j != source && model.mimicSource(j) == variable && variable >= 0) joints.push_back(j);
  }
  return joints;
}

/// Every link below `joint` (its child and the child's descendants).
void collectSubtree(const RobotModel& model, int joint, std::vector<int>& links) {
  const int child = model.childLinkOf(joint);
  links.push_back(child);
  for (int j = 0; j < static_cast<int>(model.joints().size()); ++j) {
    if (model.parentLinkOf(j) == child) collectSubtree(model, j, links);
  }
}

double openingOf(const RobotModel& model, const Manipulator& manipulator) {
  double opening = 0.0;
  for (std::size_t i = 0; i < manipulator.gripperJoints.size(); ++i) {
    const int source = model.jointIndex(manipulator.gripperJoints[i]);
    const double travel = std::abs(manipulator.gripperOpen[i] - manipulator.gripperClosed[i]);
    for (int joint : drivenJoints(model, source)) {
      const Joint& j = model.joints()[static_cast<std::size_t>(joint)];
      if (j.type != JointType::kPrismatic) continue;
      opening += travel * (j.mimic ? std::abs(j.mimic->multiplier) : 1.0);
    }
  }
  return opening;
}

void checkHasGripper(const Manipulator& manipulator, const RobotModel& model) {
  if (manipulator.gripperJoints.empty()) {
    throw InputError("gripper of " + model.name() + "/" + manipulator.name + ": the manipulator has no gripper joint");
  }
}

}  // namespace

const Manipulator& findManipulator(const RobotModel& model, const std::string& name) {
  const auto& manipulators = model.semantics().manipulators;
  if (manipulators.empty()) throw InputError("robot " + model.name() + ": no manipulator (arm with a tool frame)");
  if (name.empty()) return manipulators.front();
  std::string names;
  for (const Manipulator& m : manipulators) {
    if (m.name == name) return m;
    names += (names.empty() ? "" : ", ") + m.name;
  }
  throw InputError("robot " + model.name() + ": unknown manipulator \"" + name + "\" (manipulators: " + names + ")");
}

GripperGeometry describeGripper(const RobotModel& model, const std::string& manipulatorName) {
  const Manipulator& manipulator = findManipulator(model, manipulatorName);
  checkHasGripper(manipulator, model);
  GripperGeometry gripper;
  gripper.manipulator = manipulator.name;
  gripper.toolFrame = manipulator.toolFrame;
  gripper.gripperJoints = manipulator.gripperJoints;
  gripper.openValues = manipulator.gripperOpen;
  gripper.closedValues = manipulator.gripperClosed;
  gripper.maxOpening = openingOf(model, manipulator);
  if (!(gripper.maxOpening > 0.0)) {
    throw InputError("gripper of " + model.name() + "/" + manipulator.name + ": it does not open (open == closed)");
  }
  const VectorX q = withGripperOpening(model, gripper, model.middleConfiguration(), gripper.maxOpening);
  const std::vector<Pose> poses = model.linkPoses(q);
  const Pose X_GR = poses[static_cast<std::size_t>(model.linkIndex(gripper.toolFrame))].inverse();
  std::vector<int> fingers;
  for (const std::string& name : manipulator.gripperJoints) {
    for (int joint : drivenJoints(model, model.jointIndex(name))) collectSubtree(model, joint, fingers);
  }
  const int firstJoint = model.jointIndex(manipulator.gripperJoints.front());
  const Pose& X_RP = poses[static_cast<std::size_t>(model.parentLinkOf(firstJoint))];
  const Joint& joint = model.joints()[static_cast<std::size_t>(firstJoint)];
  gripper.closingAxis = (X_GR.linear() * X_RP.linear() * joint.origin.linear() * joint.axis).normalized();
  for (int link : fingers) {
    const Link& l = model.links()[static_cast<std::size_t>(link)];
    gripper.fingerLinks.push_back(l.name);
    const Pose X_GL = X_GR * poses[static_cast<std::size_t>(link)];
    for (const Shape& shape : l.collisions) gripper.fingerBounds.extend(transformedBox(shapeBounds(shape), X_GL));
  }
  if (gripper.fingerBounds.isEmpty()) gripper.fingerBounds = AlignedBox3(Vector3::Zero(), Vector3::Zero());
  return gripper;
}

VectorX withGripperOpening(const RobotModel& model, const GripperGeometry& gripper, VectorX q, double width) {
  const double fraction = std::clamp(width / gripper.maxOpening, 0.0, 1.0);
  for (std::size_t i = 0; i < gripper.gripperJoints.size(); ++i) {
    const int variable = model.variableIndex(gripper.gripperJoints[i]);
    q[variable] = gripper.closedValues[i] + fraction * (gripper.openValues[i] - gripper.closedValues[i]);
  }
  return q;
}

}  // namespace lang2manip
