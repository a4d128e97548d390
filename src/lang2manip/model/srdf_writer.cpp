#include "lang2manip/model/srdf_writer.hpp"

#include "lang2manip/model/xml_document.hpp"

namespace lang2manip {
namespace {

std::string attribute(const char* name, const std::string& value) { return std::string(" ") + name + "=\"" + xmlEscaped(value) + "\""; }

std::string groupState(const std::string& name, const std::string& group, const std::vector<std::string>& joints,
                       const std::vector<double>& values) {
  std::string xml = "  <group_state" + attribute("name", name) + attribute("group", group) + ">\n";
  for (std::size_t i = 0; i < joints.size(); ++i) {
    xml += "    <joint" + attribute("name", joints[i]) + attribute("value", exactNumber(values[i])) + "/>\n";
  }
  return xml + "  </group_state>\n";
}

std::string manipulatorXml(const Manipulator& arm, bool single) {
  const std::string gripperGroup = single ? "gripper" : arm.name + "_gripper";
  std::string xml = "  <group" + attribute("name", arm.name) + ">\n    <chain" + attribute("base_link", arm.baseLink) +
                    attribute("tip_link", arm.toolFrame) + "/>\n  </group>\n";
  if (arm.approachAxis) {
    const Vector3& a = *arm.approachAxis;
    xml += "  <lang2manip_approach" + attribute("group", arm.name) +
           attribute("xyz", exactNumber(a.x()) + " " + exactNumber(a.y()) + " " + exactNumber(a.z())) + "/>\n";
  }
  if (arm.gripperJoints.empty()) return xml;
  xml += "  <group" + attribute("name", gripperGroup) + ">\n";
  for (const std::string& joint : arm.gripperJoints) xml += "    <joint" + attribute("name", joint) + "/>\n";
  xml += "  </group>\n";
  xml += groupState("open", gripperGroup, arm.gripperJoints, arm.gripperOpen);
  xml += groupState("closed", gripperGroup, arm.gripperJoints, arm.gripperClosed);
  return xml + "  <end_effector" + attribute("name", gripperGroup) + attribute("parent_link", arm.toolFrame) +
         attribute("group", gripperGroup) + attribute("parent_group", arm.name) + "/>\n";
}

}  // namespace

std::string srdfString(const RobotModel& model, const RobotSemantics& semantics) {
  std::string xml = "<?xml version=\"1.0\"?>\n<!-- Semantics of " + xmlEscaped(model.name()) +
                    " as lang2manip understood them (lang2manip describe --write-srdf); edit and keep it beside the URDF. -->\n"
                    "<robot" + attribute("name", model.name()) + ">\n";
  for (const Manipulator& arm : semantics.manipulators) xml += manipulatorXml(arm, semantics.manipulators.size() == 1);
  for (const NamedState& state : semantics.namedStates) {
    if (state.name == "open" || state.name == "closed" || state.name == "close" || state.name == "opened") continue;
    std::vector<std::string> joints;
    std::vector<double> values;
    for (const auto& [joint, value] : state.values) {
      joints.push_back(joint);
      values.push_back(value);
    }
    xml += groupState(state.name, state.group, joints, values);
  }
  for (const DisabledCollision& pair : semantics.disabledCollisions) {
    xml += "  <disable_collisions" + attribute("link1", pair.link1) + attribute("link2", pair.link2) +
           (pair.reason.empty() ? std::string() : attribute("reason", pair.reason)) + "/>\n";
  }
  for (const std::string& link : semantics.defaultCollisionsDisabled) {
    xml += "  <disable_default_collisions" + attribute("link", link) + "/>\n";
  }
  for (const auto& [first, second] : semantics.enabledCollisions) {
    xml += "  <enable_collisions" + attribute("link1", first) + attribute("link2", second) + "/>\n";
  }
  return xml + "</robot>\n";
}

}  // namespace lang2manip
