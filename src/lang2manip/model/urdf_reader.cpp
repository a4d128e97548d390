#include "lang2manip/model/urdf_reader.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <sstream>

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include "lang2manip/core/file_checks.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/core/rotation.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/model/joint_limits_reader.hpp"
#include "lang2manip/model/mesh_loader.hpp"
#include "lang2manip/model/srdf_reader.hpp"
#include "lang2manip/model/urdf_structure_check.hpp"
#include "lang2manip/model/xacro.hpp"
#include "lang2manip/model/xml_document.hpp"

namespace lang2manip {
namespace {

// Collects urdfdom's console_bridge messages instead of letting them reach the terminal.
class CapturingOutputHandler final : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level < console_bridge::CONSOLE_BRIDGE_LOG_ERROR) return;
    messages += (messages.empty() ? "" : "; ") + text;
  }
  std::string messages;
};

urdf::ModelInterfaceSharedPtr parseWithUrdfdom(const std::string& xml, const std::string& source) {
  static std::mutex consoleMutex;
  const std::scoped_lock lock(consoleMutex);
  CapturingOutputHandler handler;
  console_bridge::useOutputHandler(&handler);
  urdf::ModelInterfaceSharedPtr model;
  std::string failure;
  try {
    model = urdf::parseURDF(xml);
  } catch (const std::exception& error) {
    failure = error.what();
  }
  console_bridge::restorePreviousOutputHandler();
  // urdfdom logs an error and drops the rest of a link when one element fails: treat any error
  // as fatal rather than load a robot with missing geometry.
  if (!model || !failure.empty() || !handler.messages.empty()) {
    const std::string reason = !failure.empty() ? failure : handler.messages;
    throw InputError(SourceLocation{source, 0},
                     "urdfdom rejected the URDF: " + (reason.empty() ? "unknown reason" : reason));
  }
  return model;
}

// urdfdom rejects a visual whose <material> has no name, which Kautham's models use; name them
// here (the colour is kept) so urdfdom reads the URDF the way Kautham does.
std::string textForUrdfdom(const XmlDocument& document) {
  const pugi::xpath_node_set unnamed = document.root().select_nodes("//visual/material[not(@name)]");
  if (unnamed.empty()) return document.text();
  pugi::xml_document copy;
  for (const pugi::xml_node& child : document.root().parent().children()) copy.append_copy(child);
  int counter = 0;
  for (const pugi::xpath_node& node : copy.select_nodes("//visual/material[not(@name)]")) {
    node.node().append_attribute("name") = ("lang2manip_unnamed_material_" + std::to_string(counter++)).c_str();
  }
  std::ostringstream text;
  copy.save(text);
  return text.str();
}

Pose poseFromUrdf(const urdf::Pose& pose, double scale) {
  const Quaternion rotation(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
  return makePose(scale * Vector3(pose.position.x, pose.position.y, pose.position.z), rotation);
}

struct ConversionContext {
  const urdf::ModelInterface& urdf;
  std::filesystem::path directory;
  const UrdfReadOptions& options;
  std::vector<std::filesystem::path> packagePaths;
  std::string source;
};

Geometry geometryFromUrdf(const urdf::Geometry& geometry, const ConversionContext& context,
                          const std::string& linkName) {
  const double s = context.options.scale;
  switch (geometry.type) {
    case urdf::Geometry::BOX: {
      const auto& box = dynamic_cast<const urdf::Box&>(geometry);
      return Box{s * Vector3(box.dim.x, box.dim.y, box.dim.z)};
    }
    case urdf::Geometry::SPHERE:
      return Sphere{s * dynamic_cast<const urdf::Sphere&>(geometry).radius};
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = dynamic_cast<const urdf::Cylinder&>(geometry);
      return Cylinder{s * cylinder.radius, s * cylinder.length};
    }
    case urdf::Geometry::MESH:
      break;
  }
  const auto& mesh = dynamic_cast<const urdf::Mesh&>(geometry);
  MeshGeometry result;
  result.reference = mesh.filename;
  result.scale = s * Vector3(mesh.scale.x, mesh.scale.y, mesh.scale.z);
  if (context.options.loadMeshes) {
    const SourceLocation where{context.source + " (link \"" + linkName + "\")", 0};
    const std::filesystem::path file =
        resolveMeshReference(mesh.filename, context.directory, context.packagePaths, where);
    result.mesh = MeshCache::global().get(file.string());
  }
  return result;
}

std::optional<Material> materialFromUrdf(const urdf::Visual& visual,
                                         const urdf::ModelInterface& urdf) {
  urdf::MaterialSharedPtr material = visual.material;
  if (!material && !visual.material_name.empty()) material = urdf.getMaterial(visual.material_name);
  if (!material) return std::nullopt;
  Material result;
  result.name = material->name;
  result.rgba = Vector4(material->color.r, material->color.g, material->color.b, material->color.a);
  result.texture = material->texture_filename;
  return result;
}

Link linkFromUrdf(const urdf::Link& urdfLink, const ConversionContext& context) {
  Link link;
  link.name = urdfLink.name;
  for (const urdf::VisualSharedPtr& visual : urdfLink.visual_array) {
    if (!visual || !visual->geometry) continue;
    link.visuals.push_back(Shape{geometryFromUrdf(*visual->geometry, context, link.name),
                                 poseFromUrdf(visual->origin, context.options.scale),
                                 materialFromUrdf(*visual, context.urdf), visual->name});
  }
  for (const urdf::CollisionSharedPtr& collision : urdfLink.collision_array) {
    if (!collision || !collision->geometry) continue;
    link.collisions.push_back(Shape{geometryFromUrdf(*collision->geometry, context, link.name),
                                    poseFromUrdf(collision->origin, context.options.scale),
                                    std::nullopt, collision->name});
  }
  return link;
}

JointType jointTypeFromUrdf(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE: return JointType::kRevolute;
    case urdf::Joint::CONTINUOUS: return JointType::kContinuous;
    case urdf::Joint::PRISMATIC: return JointType::kPrismatic;
    case urdf::Joint::FLOATING: return JointType::kFloating;
    case urdf::Joint::PLANAR: return JointType::kPlanar;
    default: return JointType::kFixed;
  }
}

Joint jointFromUrdf(const urdf::Joint& urdfJoint, double scale) {
  Joint joint;
  joint.name = urdfJoint.name;
  joint.type = jointTypeFromUrdf(urdfJoint.type);
  joint.parentLink = urdfJoint.parent_link_name;
  joint.childLink = urdfJoint.child_link_name;
  joint.origin = poseFromUrdf(urdfJoint.parent_to_joint_origin_transform, scale);
  joint.axis = Vector3(urdfJoint.axis.x, urdfJoint.axis.y, urdfJoint.axis.z);
  if (joint.type == JointType::kFixed && joint.axis.norm() == 0.0) joint.axis = Vector3::UnitX();
  const double limitScale = joint.type == JointType::kPrismatic ? scale : 1.0;
  if (urdfJoint.limits) {
    joint.limits = JointLimits{limitScale * urdfJoint.limits->lower,
                               limitScale * urdfJoint.limits->upper, urdfJoint.limits->velocity,
                               urdfJoint.limits->effort, false};
  }
  if (urdfJoint.safety && (joint.type == JointType::kRevolute ||
                           joint.type == JointType::kPrismatic)) {
    joint.limits.lower = limitScale * urdfJoint.safety->soft_lower_limit;
    joint.limits.upper = limitScale * urdfJoint.safety->soft_upper_limit;
    joint.limits.soft = true;
  }
  if (urdfJoint.mimic) {
    joint.mimic = JointMimic{urdfJoint.mimic->joint_name, urdfJoint.mimic->multiplier,
                             limitScale * urdfJoint.mimic->offset};
  }
  return joint;
}

std::vector<std::filesystem::path> packageSearchPaths(const UrdfReadOptions& options) {
  std::vector<std::filesystem::path> paths = options.packagePaths;
  for (const char* variable : {"LANG2MANIP_PACKAGE_PATH", "ROS_PACKAGE_PATH"}) {
    const char* value = std::getenv(variable);
    if (value == nullptr) continue;
    std::stringstream entries(value);
    std::string entry;
    while (std::getline(entries, entry, ':')) {
      if (!entry.empty()) paths.emplace_back(entry);
    }
  }
  return paths;
}

/// Every joint becomes its own variable (UrdfReadOptions::ignoreMimic). The gripper still closes
/// as the mimics said: each mimic of a gripper joint joins the gripper with the values its mimic
/// gave it when open and closed (within its limits).
void decoupleMimics(RobotModelData& data) {
  for (Manipulator& manipulator : data.semantics.manipulators) {
    const std::size_t sources = manipulator.gripperJoints.size();
    for (std::size_t i = 0; i < sources; ++i) {
      for (const Joint& joint : data.joints) {
        if (!joint.mimic || joint.mimic->sourceJoint != manipulator.gripperJoints[i]) continue;
        const auto follow = [&](double value) {
          return std::clamp(joint.mimic->multiplier * value + joint.mimic->offset, joint.limits.lower, joint.limits.upper);
        };
        manipulator.gripperJoints.push_back(joint.name);
        manipulator.gripperOpen.push_back(follow(manipulator.gripperOpen[i]));
        manipulator.gripperClosed.push_back(follow(manipulator.gripperClosed[i]));
      }
    }
  }
  for (Joint& joint : data.joints) joint.mimic.reset();
}

RobotSemantics semanticsFor(const RobotModelData& data, const std::filesystem::path& urdfPath,
                            const UrdfReadOptions& options) {
  if (!options.srdf.empty()) return readSrdfFile(options.srdf, data);
  if (!urdfPath.empty()) {
    std::filesystem::path sibling = urdfPath;
    sibling.replace_extension(".srdf");
    std::error_code error;
    if (std::filesystem::is_regular_file(sibling, error)) return readSrdfFile(sibling, data);
  }
  return inferSemantics(data);
}

/// urdfdom's link or joint for the element `node` names; the two XML readers agree on every name
/// checkUrdfStructure accepts, so a miss is reported, never dereferenced.
template <typename Map>
const typename Map::mapped_type::element_type& urdfdomElement(const Map& elements,
                                                               const XmlDocument& document,
                                                               const pugi::xml_node& node,
                                                               const char* kind) {
  const auto found = elements.find(node.attribute("name").value());
  if (found == elements.end() || !found->second) {
    throw InputError(document.where(node), std::string("urdfdom read no ") + kind + " named \"" +
                                               node.attribute("name").value() + "\"");
  }
  return *found->second;
}

void applyApproachAxes(const std::map<std::string, Vector3>& axes, RobotModelData& data) {
  for (const auto& [name, axis] : axes) {
    if (!(axis.allFinite() && axis.norm() > 1e-9)) {
      throw InputError(SourceLocation{data.source, 0}, "approach axis of manipulator \"" + name + "\" has no direction");
    }
    std::string names;
    bool found = false;
    for (Manipulator& manipulator : data.semantics.manipulators) {
      names += (names.empty() ? "" : ", ") + manipulator.name;
      if (!name.empty() && manipulator.name != name) continue;
      manipulator.approachAxis = axis.normalized();
      found = true;
    }
    if (!found) {
      throw InputError(SourceLocation{data.source, 0}, "approach axis for manipulator \"" + name + "\": robot \"" + data.name +
                                                           "\" has " + (names.empty() ? "no manipulator" : "the manipulators " + names));
    }
  }
}

/// "<description without extension>.joint_limits.yaml": "robot.urdf", "robot.urdf.xacro" and
/// "robot.xacro" give "robot.joint_limits.yaml".
std::filesystem::path siblingJointLimitsFile(const std::filesystem::path& description) {
  std::filesystem::path base = description;
  if (!isXacroFile(base)) return base.replace_extension(".joint_limits.yaml");
  base.replace_extension();
  if (base.extension() == ".urdf") base.replace_extension();
  return base += ".joint_limits.yaml";
}

/// The joint limits file to apply: the option's, else the description's sibling if it exists.
std::optional<std::filesystem::path> jointLimitsFileFor(const std::filesystem::path& description,
                                                        const UrdfReadOptions& options) {
  if (!options.jointLimits.empty()) return options.jointLimits;
  if (description.empty()) return std::nullopt;
  const std::filesystem::path sibling = siblingJointLimitsFile(description);
  std::error_code error;
  if (std::filesystem::is_regular_file(sibling, error)) return sibling;
  return std::nullopt;
}

/// Said once per model read, not at each planner query.
void warnAboutDefaultVelocities(const RobotModel& model) {
  for (int v = 0; v < model.variableCount(); ++v) {
    if (model.velocityLimits()[v] > 0.0) continue;
    const Joint& joint = model.joints()[static_cast<std::size_t>(model.variableJoints()[static_cast<std::size_t>(v)])];
    char text[160];
    std::snprintf(text, sizeof text, "velocity limit %g (zero or absent in the URDF) is no limit; trajectories move it at most at %g %s",
                  model.velocityLimits()[v], kDefaultJointVelocityLimit, joint.type == JointType::kPrismatic ? "m/s" : "rad/s");
    logWarning(model.source() + ": robot \"" + model.name() + "\", joint \"" + joint.name + "\": " + text);
  }
}

/// The model of `data` with its joint limits file applied (`description` is the file read, empty
/// for text).
RobotModelPtr completedModel(RobotModelData data, const std::filesystem::path& description,
                             const UrdfReadOptions& options) {
  auto model = std::make_shared<RobotModel>(std::move(data));
  if (const auto limits = jointLimitsFileFor(description, options)) {
    applyJointLimits(readJointLimitsFile(*limits), *model, options.scale);
  }
  warnAboutDefaultVelocities(*model);
  return model;
}

RobotModelPtr readUrdf(const XmlDocument& document, const std::filesystem::path& urdfPath,
                       const std::filesystem::path& description, const std::filesystem::path& directory,
                       const UrdfReadOptions& options) {
  requireFinite(options.scale, "URDF scale", SourceLocation{document.sourceName(), 0});
  if (options.scale <= 0.0) {
    throw InputError(SourceLocation{document.sourceName(), 0}, "URDF scale must be positive");
  }
  checkUrdfStructure(document);
  const urdf::ModelInterfaceSharedPtr urdf = parseWithUrdfdom(textForUrdfdom(document), document.sourceName());
  const ConversionContext context{*urdf, directory, options, packageSearchPaths(options),
                                  document.sourceName()};
  RobotModelData data;
  data.name = urdf->getName();
  data.source = document.sourceName();
  // Links in file order (urdfdom keeps a map; the file order is what users recognise).
  for (const pugi::xml_node& node : document.root().children("link")) {
    data.links.push_back(linkFromUrdf(urdfdomElement(urdf->links_, document, node, "link"), context));
    requireLinkInRange(data.links.back(), document.where(node));
  }
  for (const pugi::xml_node& node : document.root().children("joint")) {
    data.joints.push_back(jointFromUrdf(urdfdomElement(urdf->joints_, document, node, "joint"),
                                        options.scale));
    requirePositionInRange(data.joints.back().origin.translation(),
                           "joint \"" + data.joints.back().name + "\" origin", document.where(node));
  }
  data.semantics = semanticsFor(data, urdfPath, options);
  applyApproachAxes(options.approachAxes, data);
  if (options.ignoreMimic) decoupleMimics(data);
  return completedModel(std::move(data), description, options);
}

}  // namespace

std::filesystem::path resolveMeshReference(const std::string& reference,
                                           const std::filesystem::path& urdfDirectory,
                                           const std::vector<std::filesystem::path>& packagePaths,
                                           const SourceLocation& where) {
  std::vector<std::filesystem::path> candidates;
  const std::string packagePrefix = "package://";
  const std::string filePrefix = "file://";
  if (reference.rfind(packagePrefix, 0) == 0) {
    const std::string rest = reference.substr(packagePrefix.size());
    const std::size_t slash = rest.find('/');
    if (slash == std::string::npos || slash == 0) {
      throw InputError(where, "mesh reference \"" + reference + "\" names no package");
    }
    const std::string package = rest.substr(0, slash);
    const std::string relative = rest.substr(slash + 1);
    for (const std::filesystem::path& directory : packagePaths) {
      candidates.push_back(directory / package / relative);
    }
    for (std::filesystem::path ancestor = urdfDirectory; !ancestor.empty();
         ancestor = ancestor.parent_path()) {
      if (ancestor.filename() == package) candidates.push_back(ancestor / relative);
      if (ancestor == ancestor.parent_path()) break;
    }
  } else if (reference.rfind(filePrefix, 0) == 0) {
    candidates.emplace_back(reference.substr(filePrefix.size()));
  } else if (std::filesystem::path(reference).is_absolute()) {
    candidates.emplace_back(reference);
    // Kautham resolves "/meshes/x.stl" against the URDF's directory when no such absolute file
    // exists; so do we, with a warning.
    const std::filesystem::path besideUrdf = urdfDirectory / std::filesystem::path(reference).relative_path();
    std::error_code missing;
    if (!std::filesystem::is_regular_file(reference, missing) && std::filesystem::is_regular_file(besideUrdf, missing)) {
      logWarning(where.toString() + ": mesh \"" + reference + "\" is absolute but does not exist; read " +
                 besideUrdf.lexically_normal().string() + " beside the URDF, as Kautham does");
      candidates.push_back(besideUrdf);
    }
  } else {
    candidates.push_back(urdfDirectory / reference);
  }
  std::error_code error;
  for (const std::filesystem::path& candidate : candidates) {
    if (std::filesystem::is_regular_file(candidate, error)) return candidate.lexically_normal();
  }
  throw InputError(where, "mesh \"" + reference + "\" resolves to no readable file (" +
                              (candidates.empty() ? "no package search path given"
                                                  : triedCandidates(candidates)) + ")");
}

RobotModelPtr readUrdfFile(const std::filesystem::path& path, const UrdfReadOptions& options) {
  if (isXacroFile(path)) {
    const XmlDocument document = XmlDocument::loadString(
        expandXacroFile(path, XacroOptions{options.xacroArguments, options.packagePaths}),
        path.string() + " (expanded)", "URDF expanded from xacro");
    return readUrdf(document, {}, path, path.parent_path(), options);
  }
  const XmlDocument document = XmlDocument::loadFile(path, "URDF file");
  return readUrdf(document, path, path, path.parent_path(), options);
}

RobotModelPtr readUrdfString(const std::string& xml, const std::string& sourceName,
                             const std::filesystem::path& baseDirectory,
                             const UrdfReadOptions& options) {
  const XmlDocument document = XmlDocument::loadString(xml, sourceName, "URDF");
  return readUrdf(document, {}, {}, baseDirectory, options);
}

}  // namespace lang2manip
