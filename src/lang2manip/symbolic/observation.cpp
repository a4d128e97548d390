#include "lang2manip/symbolic/observation.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "lang2manip/model/scene.hpp"
#include "lang2manip/symbolic/object_appearance.hpp"
#include "lang2manip/symbolic/surface_region.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

double rounded(double value) { return std::round(value * 1e4) / 1e4; }

json vectorJson(const Vector3& v) { return {rounded(v.x()), rounded(v.y()), rounded(v.z())}; }

json quaternionJson(const Quaternion& q) {
  return {rounded(q.w()), rounded(q.x()), rounded(q.y()), rounded(q.z())};
}

double yawOf(const Matrix3& rotation) { return std::atan2(rotation(1, 0), rotation(0, 0)); }

json poseJson(const Pose& pose) {
  return {{"position", vectorJson(pose.translation())},
          {"orientation_wxyz", quaternionJson(Quaternion(pose.linear()))},
          {"yaw", rounded(yawOf(pose.linear()))}};
}

double variableValue(const SceneRobot& robot, const std::string& joint) {
  const RobotModel& model = *robot.model;
  const auto index = model.findJoint(joint);
  if (!index) return 0.0;
  return model.jointValue(*index, robot.configuration);
}

json jointsJson(const SceneRobot& robot) {
  const RobotModel& model = *robot.model;
  json joints = json::array();
  for (int v = 0; v < model.variableCount(); ++v) {
    const Joint& joint = model.joints()[static_cast<std::size_t>(model.variableJoints()[static_cast<std::size_t>(v)])];
    joints.push_back({{"name", joint.name}, {"type", jointTypeName(joint.type)},
                      {"value", rounded(robot.configuration[v])},
                      {"lower", rounded(model.lowerLimits()[v])}, {"upper", rounded(model.upperLimits()[v])}});
  }
  return joints;
}

json linksJson(const RobotModel& model) {
  json links = json::array();
  for (std::size_t l = 0; l < model.links().size(); ++l) {
    const int joint = model.parentJoint(static_cast<int>(l));
    json link{{"name", model.links()[l].name}, {"parent", nullptr}, {"joint", nullptr}};
    if (joint >= 0) {
      link["parent"] = model.links()[static_cast<std::size_t>(model.parentLinkOf(joint))].name;
      link["joint"] = model.joints()[static_cast<std::size_t>(joint)].name;
    }
    links.push_back(link);
  }
  return links;
}

/// "open", "closed" or "partly open" from the first gripper joint's value.
std::string gripperState(const Manipulator& arm, const std::vector<double>& values) {
  if (values.empty() || arm.gripperOpen.empty() || arm.gripperClosed.empty()) return "none";
  const double open = arm.gripperOpen.front();
  const double closed = arm.gripperClosed.front();
  const double tolerance = 0.1 * std::abs(open - closed) + 1e-9;
  if (std::abs(values.front() - open) <= tolerance) return "open";
  if (std::abs(values.front() - closed) <= tolerance) return "closed";
  return "partly open";
}

json endEffectorJson(const SceneRobot& robot, const Manipulator& arm, const std::vector<Pose>& links,
                     const std::string& held) {
  const RobotModel& model = *robot.model;
  const auto tool = model.findLink(arm.toolFrame);
  const Pose inBase = tool ? links[static_cast<std::size_t>(*tool)] : Pose::Identity();
  std::vector<double> values;
  for (const std::string& joint : arm.gripperJoints) values.push_back(rounded(variableValue(robot, joint)));
  return {{"name", arm.name},
          {"tool_frame", arm.toolFrame},
          {"pose", poseJson(robot.basePose * inBase)},
          {"position_in_base", vectorJson(inBase.translation())},
          {"gripper", {{"joints", arm.gripperJoints}, {"values", values},
                       {"open", arm.gripperOpen}, {"closed", arm.gripperClosed},
                       {"state", gripperState(arm, values)}}},
          {"holding", held.empty() ? json(nullptr) : json(held)}};
}

/// True when `link` hangs below the last joint of `arm` (its hand or fingers).
bool belongsToArm(const RobotModel& model, const std::string& link, const Manipulator& arm) {
  if (arm.armJoints.empty()) return false;
  auto index = model.findLink(link);
  if (!index) return false;
  for (int joint = model.parentJoint(*index); joint >= 0; joint = model.parentJoint(model.parentLinkOf(joint))) {
    if (model.joints()[static_cast<std::size_t>(joint)].name == arm.armJoints.back()) return true;
  }
  return false;
}

std::string heldBy(const Scene& scene, const SceneRobot& robot, const Manipulator& arm) {
  const bool single = robot.model->semantics().manipulators.size() == 1;
  for (const Attachment& attachment : scene.attachments()) {
    if (attachment.robot == robot.name && (single || belongsToArm(*robot.model, attachment.link, arm))) {
      return attachment.object;
    }
  }
  return {};
}

json robotJson(const Scene& scene, const SceneRobot& robot, const SymbolicState& state, bool observed) {
  const RobotModel& model = *robot.model;
  const std::vector<Pose> links = model.linkPoses(robot.configuration);
  json effectors = json::array();
  for (const Manipulator& arm : model.semantics().manipulators) {
    effectors.push_back(endEffectorJson(robot, arm, links, heldBy(scene, robot, arm)));
  }
  json named = json::array();
  if (observed) {
    for (const std::string& name : state.namedConfigurations) named.push_back(name);
  }
  return {{"name", robot.name}, {"model", model.name()}, {"dofs", model.variableCount()},
          {"joints", jointsJson(robot)}, {"links", linksJson(model)},
          {"base_pose", poseJson(robot.basePose)}, {"end_effectors", effectors},
          {"configuration", observed && !state.atConfiguration.empty() ? json(state.atConfiguration) : json(nullptr)},
          {"named_configurations", named}};
}

/// "front-left", "front-right", "front", "left", ...: where a base-frame position lies.
std::string sideOfRobot(const Vector3& p, double margin) {
  std::string side = p.x() > margin ? "front" : (p.x() < -margin ? "behind" : "");
  const std::string lateral = p.y() > margin ? "left" : (p.y() < -margin ? "right" : "");
  if (!side.empty() && !lateral.empty()) return side + "-" + lateral;
  return side.empty() ? (lateral.empty() ? "at the base" : lateral) : side;
}

json objectJson(const SceneObject& object, const Pose& base, const SymbolicState& state,
                const SpatialOptions& spatial) {
  const Vector3 centre = object.worldBounds().center();
  const Vector3 inBase = base.inverse() * object.pose.translation();
  const auto in = state.inside.find(object.name);
  const auto on = state.onTopOf.find(object.name);
  json report{{"name", object.name}, {"kind", object.kind},
              {"position", vectorJson(object.pose.translation())},
              {"orientation_wxyz", quaternionJson(Quaternion(object.pose.linear()))},
              {"yaw", rounded(yawOf(object.pose.linear()))},
              {"centre", vectorJson(centre)},
              {"dimensions", vectorJson(object.dimensions())},
              {"movable", object.movable}, {"role", objectRoleName(object.role)},
              {"in", in == state.inside.end() ? json(nullptr) : json(in->second)},
              {"on", on == state.onTopOf.end() ? json(nullptr) : json(on->second)},
              {"held", state.held == object.name}, {"clear", state.isClear(object.name)},
              {"position_in_base", vectorJson(inBase)},
              {"side_of_robot", sideOfRobot(inBase, spatial.directionMargin)},
              {"distance_from_robot", rounded(inBase.head<2>().norm())}};
  const std::vector<std::string> colours = objectColours(object);
  report["colour"] = colours.empty() ? json(nullptr) : json(colours.front());
  const std::string category = objectCategory(object);
  report["category"] = category.empty() ? json(nullptr) : json(category);
  if (object.cavity) {
    report["cavity"] = {{"min", vectorJson(object.cavity->min())}, {"max", vectorJson(object.cavity->max())}};
  }
  if (object.semantics != SemanticsSource::kGiven) report["semantics"] = semanticsSourceName(object.semantics);
  return report;
}

json areaJson(const AlignedBox3& box) {
  return {{"x", {rounded(box.min().x()), rounded(box.max().x())}}, {"y", {rounded(box.min().y()), rounded(box.max().y())}}};
}

/// The top face and its reachable part for every object that offers a flat top (base frame).
std::map<std::string, SupportArea> supportAreas(const Scene& scene, const std::string& robot, const std::string& arm) {
  std::map<std::string, SupportArea> areas;
  for (const SceneObject& object : scene.objects()) {
    if (object.role != ObjectRole::kSupport) continue;
    if (auto area = supportArea(scene, object.name, robot, nullptr, arm)) areas.emplace(object.name, *area);
  }
  return areas;
}

/// Adds to the objects' reports the top faces of supports and the region of their top each object
/// on one stands in.
void addRegions(json& objects, const std::map<std::string, SupportArea>& areas, const Scene& scene, const Pose& base) {
  for (json& report : objects) {
    const std::string name = report["name"].get<std::string>();
    if (const auto area = areas.find(name); area != areas.end()) {
      report["top"] = {{"height", rounded(area->second.top.max().z())}, {"area", areaJson(area->second.top)},
                       {"reachable", areaJson(area->second.reachable)}, {"clipped", area->second.clipped}};
    }
    if (!report["on"].is_string()) continue;
    const auto support = areas.find(report["on"].get<std::string>());
    if (support == areas.end()) continue;
    const Vector3 centre = base.inverse() * scene.object(name).worldBounds().center();
    const AlignedBox3& reachable = support->second.reachable;
    const bool inside = centre.x() >= reachable.min().x() && centre.x() <= reachable.max().x() &&
                        centre.y() >= reachable.min().y() && centre.y() <= reachable.max().y();
    report["region"] = inside ? json(surfaceRegionName(cellOfPoint(reachable, centre))) : json("out_of_reach");
  }
}

json fact(const std::string& subject, const std::string& relation, const std::string& object) {
  return {{"subject", subject}, {"relation", relation}, {"object", object}};
}

bool related(const std::string& a, const std::string& b, const SymbolicState& state) {
  for (const auto* facts : {&state.inside, &state.onTopOf}) {
    const auto ia = facts->find(a);
    const auto ib = facts->find(b);
    if ((ia != facts->end() && ia->second == b) || (ib != facts->end() && ib->second == a)) return true;
  }
  return false;
}

json relationsJson(const Scene& scene, const Pose& base, const SymbolicState& state,
                   const SpatialOptions& spatial) {
  json relations = json::array();
  if (!state.held.empty()) relations.push_back(fact("robot", "holding", state.held));
  for (const auto& [item, container] : state.inside) relations.push_back(fact(item, "in", container));
  for (const auto& [item, support] : state.onTopOf) relations.push_back(fact(item, "on", support));
  const auto& objects = scene.objects();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    for (std::size_t j = i + 1; j < objects.size(); ++j) {
      const SceneObject& a = objects[i];
      const SceneObject& b = objects[j];
      if (a.role == ObjectRole::kSupport || b.role == ObjectRole::kSupport) continue;
      if (state.held == a.name || state.held == b.name || related(a.name, b.name, state)) continue;
      const Vector3 offset = base.linear().transpose() * (a.worldBounds().center() - b.worldBounds().center());
      for (SpatialRelation relation : directionalRelations(offset, spatial.directionMargin)) {
        relations.push_back(fact(a.name, spatialRelationName(relation), b.name));
      }
      if (boxGap(a.worldBounds(), b.worldBounds()) <= spatial.nearDistance) {
        relations.push_back(fact(a.name, "near", b.name));
      }
    }
  }
  return relations;
}

}  // namespace

nlohmann::json observeEnvironment(const Scene& scene, const ObservationOptions& options) {
  const SymbolicState state = observeSymbolicState(scene, options.tolerances, options.robot, options.arm);
  const Pose base = robotBaseFrame(scene, options.robot);
  const std::string mainRobot = !options.robot.empty() ? options.robot
                                : scene.robots().empty() ? std::string() : scene.robots().front().name;
  json robots = json::array();
  for (const SceneRobot& robot : scene.robots()) {
    robots.push_back(robotJson(scene, robot, state, robot.name == mainRobot));
  }
  json objects = json::array();
  for (const SceneObject& object : scene.objects()) objects.push_back(objectJson(object, base, state, options.spatial));
  addRegions(objects, supportAreas(scene, options.robot, options.arm), scene, base);
  return {{"frames", "world frame z up; relations and base-frame positions use the base frame of robot " +
                         (mainRobot.empty() ? std::string("(none)") : mainRobot) +
                         ": x front, y left, z up; lengths in metres, angles in radians"},
          {"conventions", spatialConventions(options.spatial, options.tolerances)},
          {"robot", mainRobot.empty() ? json(nullptr) : json(mainRobot)},
          {"robots", robots}, {"objects", objects},
          {"relations", relationsJson(scene, base, state, options.spatial)}};
}

}  // namespace lang2manip
