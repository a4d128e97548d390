#include "lang2manip/model/srdf_reader.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/model/xml_document.hpp"

namespace lang2manip {
namespace {

bool isMovableJoint(const Joint& joint) {
  return joint.type == JointType::kRevolute || joint.type == JointType::kContinuous ||
         joint.type == JointType::kPrismatic;
}

// Name lookups over RobotModelData (the model is not built yet when its SRDF is read).
struct TreeIndex {
  explicit TreeIndex(const RobotModelData& robot) : data(robot) {
    for (const Link& link : robot.links) links.insert(link.name);
    for (const Joint& joint : robot.joints) {
      joints[joint.name] = &joint;
      parentJointOfLink[joint.childLink] = &joint;
      childJoints[joint.parentLink].push_back(&joint);
    }
  }

  // Joints from `base` down to `tip`, root first; empty optional when tip is not below base.
  std::optional<std::vector<const Joint*>> pathBetween(const std::string& base,
                                                       const std::string& tip) const {
    std::vector<const Joint*> path;
    std::string link = tip;
    while (link != base) {
      const auto parent = parentJointOfLink.find(link);
      if (parent == parentJointOfLink.end()) return std::nullopt;
      path.push_back(parent->second);
      link = parent->second->parentLink;
    }
    std::reverse(path.begin(), path.end());
    return path;
  }

  // Links in the subtree below `link` (itself included), depth first.
  std::vector<std::string> subtree(const std::string& link) const {
    std::vector<std::string> result{link};
    const auto children = childJoints.find(link);
    if (children == childJoints.end()) return result;
    for (const Joint* joint : children->second) {
      const std::vector<std::string> below = subtree(joint->childLink);
      result.insert(result.end(), below.begin(), below.end());
    }
    return result;
  }

  const RobotModelData& data;
  std::set<std::string> links;
  std::map<std::string, const Joint*> joints;
  std::map<std::string, const Joint*> parentJointOfLink;
  std::map<std::string, std::vector<const Joint*>> childJoints;
};

class SrdfParser {
 public:
  SrdfParser(const XmlDocument& document, const RobotModelData& robot)
      : document_(document), tree_(robot) {}

  RobotSemantics parse() {
    const pugi::xml_node root = document_.root();
    if (std::string(root.name()) != "robot") {
      throw InputError(document_.where(root), std::string("the root element is <") +
                                                  root.name() + ">, not <robot>: not an SRDF");
    }
    RobotSemantics semantics;
    semantics.inferred = false;
    semantics.source = document_.sourceName();
    for (const pugi::xml_node& node : root.children("group")) semantics.groups.push_back(group(node));
    for (const pugi::xml_node& node : root.children("end_effector")) {
      semantics.endEffectors.push_back(endEffector(node, semantics));
    }
    for (const pugi::xml_node& node : root.children("group_state")) {
      semantics.namedStates.push_back(namedState(node, semantics));
    }
    for (const pugi::xml_node& node : root.children("disable_collisions")) {
      semantics.disabledCollisions.push_back(
          {linkAttribute(node, "link1"), linkAttribute(node, "link2"),
           node.attribute("reason").value()});
    }
    for (const pugi::xml_node& node : root.children("disable_default_collisions")) {
      semantics.defaultCollisionsDisabled.push_back(linkAttribute(node, "link"));
    }
    for (const pugi::xml_node& node : root.children("enable_collisions")) {
      semantics.enabledCollisions.emplace_back(linkAttribute(node, "link1"), linkAttribute(node, "link2"));
    }
    return semantics;
  }

  /// Applies the <lang2manip_approach group="ARM" xyz="X Y Z"/> elements (our extension; other
  /// SRDF readers ignore it) to the resolved manipulators.
  void applyApproaches(RobotSemantics& semantics) const {
    for (const pugi::xml_node& node : document_.root().children("lang2manip_approach")) {
      const std::string group = document_.requiredAttribute(node, "group");
      const Vector3 axis = approachAxisFromText(document_.requiredAttribute(node, "xyz"), document_.where(node));
      std::string names;
      Manipulator* target = nullptr;
      for (Manipulator& manipulator : semantics.manipulators) {
        if (manipulator.name == group) target = &manipulator;
        names += (names.empty() ? "" : ", ") + manipulator.name;
      }
      if (target == nullptr) {
        throw InputError(document_.where(node), "<lang2manip_approach> names group \"" + group +
                                                    "\", which is not an arm with a tool frame (arms: " +
                                                    (names.empty() ? "none" : names) + ")");
      }
      target->approachAxis = axis;
    }
  }

 private:
  std::string linkAttribute(const pugi::xml_node& node, const char* attribute) const {
    const std::string name = document_.requiredAttribute(node, attribute);
    if (!tree_.links.count(name)) {
      throw InputError(document_.where(node), "<" + std::string(node.name()) + "> names link \"" +
                                                  name + "\", which the robot \"" +
                                                  tree_.data.name + "\" does not have");
    }
    return name;
  }

  std::string jointAttribute(const pugi::xml_node& node) const {
    const std::string name = document_.requiredAttribute(node, "name");
    if (!tree_.joints.count(name)) {
      throw InputError(document_.where(node), "<" + std::string(node.name()) +
                                                  "> names joint \"" + name +
                                                  "\", which the robot \"" + tree_.data.name +
                                                  "\" does not have");
    }
    return name;
  }

  PlanningGroup group(const pugi::xml_node& node) const {
    PlanningGroup result;
    result.name = document_.requiredAttribute(node, "name");
    for (const pugi::xml_node& chain : node.children("chain")) {
      const std::string base = linkAttribute(chain, "base_link");
      const std::string tip = linkAttribute(chain, "tip_link");
      if (!tree_.pathBetween(base, tip)) {
        throw InputError(document_.where(chain), "chain of group \"" + result.name + "\": link \"" +
                                                     tip + "\" is not below link \"" + base + "\"");
      }
      result.chains.emplace_back(base, tip);
    }
    for (const pugi::xml_node& joint : node.children("joint")) {
      result.joints.push_back(jointAttribute(joint));
    }
    for (const pugi::xml_node& link : node.children("link")) {
      result.links.push_back(linkAttribute(link, "name"));
    }
    for (const pugi::xml_node& subgroup : node.children("group")) {
      result.subgroups.push_back(document_.requiredAttribute(subgroup, "name"));
    }
    return result;
  }

  void requireGroup(const pugi::xml_node& node, const std::string& name,
                    const RobotSemantics& semantics) const {
    for (const PlanningGroup& group : semantics.groups) {
      if (group.name == name) return;
    }
    throw InputError(document_.where(node), "<" + std::string(node.name()) +
                                                "> refers to unknown group \"" + name + "\"");
  }

  EndEffector endEffector(const pugi::xml_node& node, const RobotSemantics& semantics) const {
    EndEffector result{document_.requiredAttribute(node, "name"), linkAttribute(node, "parent_link"),
                       document_.requiredAttribute(node, "group"),
                       node.attribute("parent_group").value()};
    requireGroup(node, result.group, semantics);
    if (!result.parentGroup.empty()) requireGroup(node, result.parentGroup, semantics);
    return result;
  }

  NamedState namedState(const pugi::xml_node& node, const RobotSemantics& semantics) const {
    NamedState result{document_.requiredAttribute(node, "name"),
                      document_.requiredAttribute(node, "group"), {}};
    requireGroup(node, result.group, semantics);
    for (const pugi::xml_node& joint : node.children("joint")) {
      const std::string name = jointAttribute(joint);
      const double value = parseFiniteNumber(document_.requiredAttribute(joint, "value"),
                                             "value of joint \"" + name + "\"",
                                             document_.where(joint));
      result.values.emplace_back(name, value);
    }
    return result;
  }

  const XmlDocument& document_;
  TreeIndex tree_;
};

const PlanningGroup* findGroup(const RobotSemantics& semantics, const std::string& name) {
  for (const PlanningGroup& group : semantics.groups) {
    if (group.name == name) return &group;
  }
  return nullptr;
}

std::vector<std::string> movableJointsOf(const PlanningGroup& group, const TreeIndex& tree) {
  std::vector<std::string> joints;
  for (const auto& [base, tip] : group.chains) {
    const std::vector<const Joint*> path = tree.pathBetween(base, tip).value_or(std::vector<const Joint*>{});
    for (const Joint* joint : path) {
      if (isMovableJoint(*joint) && !joint->mimic) joints.push_back(joint->name);
    }
  }
  for (const std::string& name : group.joints) {
    const Joint* joint = tree.joints.at(name);
    if (isMovableJoint(*joint) && !joint->mimic) joints.push_back(name);
  }
  return joints;
}

/// The value of `joint` in the first of the group's states named `names`, and that state's name;
/// `fallback` and an empty name when none gives it.
std::pair<double, std::string> namedValue(const RobotSemantics& semantics, const std::string& group,
                                          std::initializer_list<const char*> names, const std::string& joint, double fallback) {
  for (const char* name : names) {
    for (const NamedState& state : semantics.namedStates) {
      if (state.group != group || state.name != name) continue;
      for (const auto& [stateJoint, value] : state.values) {
        if (stateJoint == joint) return {value, name};
      }
    }
  }
  return {fallback, {}};
}

void addGripper(Manipulator& arm, const EndEffector& effector, const RobotSemantics& semantics,
                const TreeIndex& tree) {
  const PlanningGroup* gripper = findGroup(semantics, effector.group);
  for (const std::string& joint : movableJointsOf(*gripper, tree)) {
    const JointLimits& limits = tree.joints.at(joint)->limits;
    arm.gripperJoints.push_back(joint);
    const auto [open, openState] = namedValue(semantics, gripper->name, {"open", "opened"}, joint, limits.upper);
    const auto [closed, closedState] = namedValue(semantics, gripper->name, {"close", "closed"}, joint, limits.lower);
    arm.gripperOpen.push_back(open);
    arm.gripperClosed.push_back(closed);
    if (!openState.empty()) arm.gripperOpenState = openState;
    if (!closedState.empty()) arm.gripperClosedState = closedState;
  }
}

}  // namespace

void resolveManipulators(RobotSemantics& semantics, const RobotModelData& robot) {
  const TreeIndex tree(robot);
  semantics.manipulators.clear();
  for (const EndEffector& effector : semantics.endEffectors) {
    const PlanningGroup* arm = findGroup(semantics, effector.parentGroup);
    if (arm == nullptr || arm->chains.empty()) continue;
    Manipulator manipulator;
    manipulator.name = arm->name;
    manipulator.armJoints = movableJointsOf(*arm, tree);
    manipulator.baseLink = arm->chains.front().first;
    manipulator.toolFrame = arm->chains.back().second;
    addGripper(manipulator, effector, semantics, tree);
    semantics.manipulators.push_back(std::move(manipulator));
  }
  if (semantics.manipulators.empty()) {
    semantics.manipulators = inferSemantics(robot).manipulators;
  }
}

namespace {

RobotSemantics readSrdf(const XmlDocument& document, const RobotModelData& robot) {
  SrdfParser parser(document, robot);
  RobotSemantics semantics = parser.parse();
  resolveManipulators(semantics, robot);
  parser.applyApproaches(semantics);
  return semantics;
}

}  // namespace

Vector3 approachAxisFromText(std::string_view text, const SourceLocation& where) {
  const Vector3 axis = parseVector3(text, "approach axis", where);
  if (!(axis.norm() > 1e-9)) throw InputError(where, "approach axis \"" + std::string(text) + "\" has no direction");
  return axis.normalized();
}

RobotSemantics readSrdfFile(const std::filesystem::path& path, const RobotModelData& robot) {
  return readSrdf(XmlDocument::loadFile(path, "SRDF file"), robot);
}

RobotSemantics readSrdfString(const std::string& xml, const std::string& sourceName,
                              const RobotModelData& robot) {
  return readSrdf(XmlDocument::loadString(xml, sourceName, "SRDF"), robot);
}

}  // namespace lang2manip
