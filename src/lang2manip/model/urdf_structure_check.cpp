#include "lang2manip/model/urdf_structure_check.hpp"

#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {
namespace {

// Attributes that hold numbers, per element name.
const std::map<std::string, std::vector<const char*>>& numericAttributes() {
  static const std::map<std::string, std::vector<const char*>> attributes{
      {"origin", {"xyz", "rpy"}},
      {"axis", {"xyz"}},
      {"limit", {"lower", "upper", "effort", "velocity"}},
      {"safety_controller", {"soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"}},
      {"mimic", {"multiplier", "offset"}},
      {"box", {"size"}},
      {"cylinder", {"radius", "length"}},
      {"sphere", {"radius"}},
      {"mesh", {"scale"}},
      {"color", {"rgba"}},
      {"mass", {"value"}},
      {"inertia", {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}},
      {"dynamics", {"damping", "friction"}},
  };
  return attributes;
}

/// `name` with control characters shown as escapes (\t, \r, \n, \xNN), for messages.
std::string visibleName(const std::string& name) {
  std::string shown;
  for (const char c : name) {
    if (c == '\t') shown += "\\t";
    else if (c == '\r') shown += "\\r";
    else if (c == '\n') shown += "\\n";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      shown += escaped;
    } else {
      shown += c;
    }
  }
  return shown;
}

/// The value of a name attribute (a link, a joint, or a reference to one). urdfdom's XML reader
/// and pugixml normalise whitespace inside attributes differently (a tab is kept by one and
/// turned into a space by the other), so a name with whitespace or control characters would name
/// different things in the two: such names are rejected, with the file, line and name.
std::string checkedName(const XmlDocument& urdf, const pugi::xml_node& node, const char* attribute,
                        const std::string& what) {
  const std::string name = urdf.requiredAttribute(node, attribute);
  if (name.empty()) throw InputError(urdf.where(node), what + " is empty");
  for (const char c : name) {
    if (static_cast<unsigned char>(c) <= 0x20 || c == 0x7f) {
      throw InputError(urdf.where(node), what + " \"" + visibleName(name) +
                                             "\" contains whitespace or a control character; URDF "
                                             "names may not (urdfdom would read it differently)");
    }
  }
  return name;
}

void checkNumbers(const XmlDocument& urdf, const pugi::xml_node& element) {
  const auto found = numericAttributes().find(element.name());
  if (found != numericAttributes().end()) {
    for (const char* name : found->second) {
      const pugi::xml_attribute attribute = element.attribute(name);
      if (!attribute) continue;
      parseNumberList(attribute.value(),
                      std::string("<") + element.name() + "> attribute " + name,
                      urdf.where(element));
    }
  }
  for (const pugi::xml_node& child : element.children()) {
    if (child.type() == pugi::node_element) checkNumbers(urdf, child);
  }
}

void checkGeometry(const XmlDocument& urdf, const pugi::xml_node& element) {
  const pugi::xml_node geometry = element.child("geometry");
  if (!geometry) {
    throw InputError(urdf.where(element), std::string("<") + element.name() +
                                              "> has no <geometry>");
  }
  pugi::xml_node shape = geometry.first_child();
  while (shape && shape.type() != pugi::node_element) shape = shape.next_sibling();
  if (!shape) {
    throw InputError(urdf.where(geometry), "<geometry> has no shape element");
  }
  const std::string kind = shape.name();
  if (kind == "box") {
    parseVector3(urdf.requiredAttribute(shape, "size"), "<box> size", urdf.where(shape));
  } else if (kind == "sphere") {
    urdf.requiredNumberAttribute(shape, "radius");
  } else if (kind == "cylinder") {
    urdf.requiredNumberAttribute(shape, "radius");
    urdf.requiredNumberAttribute(shape, "length");
  } else if (kind == "mesh") {
    urdf.requiredAttribute(shape, "filename");
  } else {
    throw InputError(urdf.where(shape), "unknown geometry <" + kind +
                                            ">: a URDF geometry is a box, sphere, cylinder or mesh");
  }
}

struct JointLinks {
  std::string name;
  std::string parent;
  std::string child;
  int line = 0;
};

std::vector<JointLinks> readJointLinks(const XmlDocument& urdf,
                                       const std::map<std::string, int>& links) {
  std::vector<JointLinks> joints;
  std::set<std::string> names;
  for (const pugi::xml_node& joint : urdf.root().children("joint")) {
    JointLinks entry{checkedName(urdf, joint, "name", "joint name"), "", "", urdf.lineOf(joint)};
    if (!names.insert(entry.name).second) {
      throw InputError(urdf.where(joint), "joint \"" + entry.name + "\" is defined twice");
    }
    urdf.requiredAttribute(joint, "type");
    const pugi::xml_node parent = joint.child("parent");
    const pugi::xml_node child = joint.child("child");
    if (!parent || !child) {
      throw InputError(urdf.where(joint),
                       "joint \"" + entry.name + "\" needs both <parent> and <child>");
    }
    entry.parent = checkedName(urdf, parent, "link", "joint \"" + entry.name + "\" parent link");
    entry.child = checkedName(urdf, child, "link", "joint \"" + entry.name + "\" child link");
    if (const pugi::xml_node mimic = joint.child("mimic")) {
      checkedName(urdf, mimic, "joint", "joint \"" + entry.name + "\" mimic joint");
    }
    for (const pugi::xml_node& end : {parent, child}) {
      const std::string link = end.attribute("link").value();
      if (!links.count(link)) {
        throw InputError(urdf.where(end), "joint \"" + entry.name + "\" refers to link \"" + link +
                                              "\", which is not defined");
      }
    }
    joints.push_back(entry);
  }
  for (const pugi::xml_node& joint : urdf.root().children("joint")) {
    const pugi::xml_node mimic = joint.child("mimic");
    if (mimic && !names.count(mimic.attribute("joint").value())) {
      throw InputError(urdf.where(mimic), "joint \"" + std::string(joint.attribute("name").value()) +
                                              "\" mimics joint \"" + mimic.attribute("joint").value() +
                                              "\", which is not defined");
    }
  }
  return joints;
}

void checkTree(const XmlDocument& urdf, const std::map<std::string, int>& links) {
  const std::vector<JointLinks> joints = readJointLinks(urdf, links);
  std::map<std::string, const JointLinks*> parentJoint;
  for (const JointLinks& joint : joints) {
    const auto [existing, inserted] = parentJoint.emplace(joint.child, &joint);
    if (!inserted) {
      throw InputError(SourceLocation{urdf.sourceName(), joint.line},
                       "link \"" + joint.child + "\" has two parent joints (\"" +
                           existing->second->name + "\" and \"" + joint.name + "\")");
    }
  }
  std::vector<std::string> roots;
  for (const auto& [name, line] : links) {
    if (!parentJoint.count(name)) roots.push_back(name);
  }
  if (roots.size() > 1) {
    std::string list;
    for (const std::string& root : roots) list += (list.empty() ? "" : ", ") + root;
    throw InputError(SourceLocation{urdf.sourceName(), links.at(roots[1])},
                     "the URDF has " + std::to_string(roots.size()) + " root links (" + list +
                         "); every link but one needs a parent joint");
  }
  // Each link is walked up from once (linear in the tree's size): a walk ends at the root or at a
  // link an earlier walk reached, and meeting its own path again is a cycle.
  std::map<std::string, std::size_t> walkOf;
  for (std::size_t walk = 1; walk <= joints.size(); ++walk) {
    std::string link = joints[walk - 1].child;
    while (walkOf.emplace(link, walk).second) {
      const auto parent = parentJoint.find(link);
      if (parent == parentJoint.end()) break;
      link = parent->second->parent;
      if (const auto reached = walkOf.find(link); reached != walkOf.end() && reached->second == walk) {
        throw InputError(SourceLocation{urdf.sourceName(), parent->second->line},
                         "joint \"" + parent->second->name + "\" closes a cycle through link \"" + link +
                             "\"; a URDF must be a tree");
      }
    }
  }
  if (roots.empty()) {
    throw InputError(SourceLocation{urdf.sourceName(), urdf.lineOf(urdf.root())},
                     "the URDF has no root link: its joints form a cycle");
  }
}

}  // namespace

void checkUrdfStructure(const XmlDocument& urdf) {
  const pugi::xml_node robot = urdf.root();
  if (std::string(robot.name()) != "robot") {
    throw InputError(urdf.where(robot), std::string("the root element is <") + robot.name() +
                                            ">, not <robot>: not a URDF");
  }
  urdf.requiredAttribute(robot, "name");
  checkNumbers(urdf, robot);
  std::map<std::string, int> links;
  for (const pugi::xml_node& link : robot.children("link")) {
    if (links.size() == static_cast<std::size_t>(kMaxRobotLinks)) {
      throw InputError(urdf.where(link), "the URDF has more than " + std::to_string(kMaxRobotLinks) + " links");
    }
    const std::string name = checkedName(urdf, link, "name", "link name");
    if (!links.emplace(name, urdf.lineOf(link)).second) {
      throw InputError(urdf.where(link), "link \"" + name + "\" is defined twice");
    }
    for (const char* kind : {"visual", "collision"}) {
      for (const pugi::xml_node& element : link.children(kind)) checkGeometry(urdf, element);
    }
  }
  if (links.empty()) throw InputError(urdf.where(robot), "the URDF defines no <link>");
  checkTree(urdf, links);
}

}  // namespace lang2manip
