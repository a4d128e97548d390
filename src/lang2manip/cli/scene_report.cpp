#include "lang2manip/cli/scene_report.hpp"

#include <cstdio>

#include "lang2manip/cli/collision_queries.hpp"
#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/core/rotation.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

json poseJson(const Pose& pose) {
  const Quaternion q(pose.linear());
  const Vector3& t = pose.translation();
  return {{"position", {t.x(), t.y(), t.z()}}, {"quaternion_wxyz", {q.w(), q.x(), q.y(), q.z()}}};
}

json vectorJson(const VectorX& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

json robotJson(const SceneRobot& robot) {
  const RobotModel& model = *robot.model;
  json joints = json::array();
  for (int v = 0; v < model.variableCount(); ++v) {
    const Joint& joint = model.joints()[static_cast<std::size_t>(model.variableJoints()[static_cast<std::size_t>(v)])];
    const std::optional<double> acceleration = model.accelerationLimit(v);
    joints.push_back({{"name", joint.name}, {"type", jointTypeName(joint.type)},
                      {"lower", model.lowerLimits()[v]}, {"upper", model.upperLimits()[v]},
                      {"velocity", model.velocityLimits()[v]},
                      {"acceleration", acceleration ? json(*acceleration) : json(nullptr)},
                      {"soft_limits", joint.limits.soft}, {"value", robot.configuration[v]}});
  }
  json manipulators = json::array();
  for (const Manipulator& arm : model.semantics().manipulators) {
    manipulators.push_back({{"name", arm.name}, {"arm_joints", arm.armJoints},
                            {"tool_frame", arm.toolFrame}, {"gripper_joints", arm.gripperJoints}});
  }
  return {{"name", robot.name}, {"model", model.name()}, {"urdf", model.source()},
          {"dofs", model.variableCount()}, {"links", model.links().size()},
          {"base_pose", poseJson(robot.basePose)}, {"joints", joints},
          {"manipulators", manipulators},
          {"semantics", model.semantics().inferred ? "inferred" : model.semantics().source}};
}

json objectJson(const SceneObject& object, const std::vector<ObjectSemanticsDecision>& decisions) {
  const Vector3 size = object.dimensions();
  json report{{"name", object.name}, {"kind", object.kind}, {"pose", poseJson(object.pose)},
              {"size", {size.x(), size.y(), size.z()}}, {"movable", object.movable},
              {"role", objectRoleName(object.role)}, {"semantics", semanticsSourceName(object.semantics)},
              {"collision_enabled", object.collisionEnabled}, {"shapes", object.collisions.size()}};
  for (const ObjectSemanticsDecision& decision : decisions) {
    if (decision.object == object.name && decision.source != SemanticsSource::kGiven) report["semantics_reason"] = decision.reason;
  }
  if (object.cavity) {
    report["cavity"] = {{"min", {object.cavity->min().x(), object.cavity->min().y(), object.cavity->min().z()}},
                        {"max", {object.cavity->max().x(), object.cavity->max().y(), object.cavity->max().z()}}};
  }
  return report;
}

json controlsJson(const ControlSet& controls) {
  json list = json::array();
  for (const Control& control : controls.controls) {
    json dofs = json::array();
    for (const auto& [dof, coefficient] : control.coefficients) {
      dofs.push_back({{"dof", controls.dofs[static_cast<std::size_t>(dof)].fullName()},
                      {"coefficient", coefficient}});
    }
    list.push_back({{"name", control.name}, {"eig_value", control.eigValue}, {"dofs", dofs}});
  }
  return {{"file", controls.source.empty() ? "(default controls)" : controls.source}, {"controls", list}};
}

json queriesJson(const LoadedProblem& loaded) {
  json queries = json::array();
  const auto& robots = loaded.problem.scene.robots();
  const std::vector<QueryCollisions> collisions =
      checkQueries(loaded, FclCollisionChecker(loaded.problem.scene));
  for (std::size_t q = 0; q < loaded.queries.size(); ++q) {
    const auto& [start, goal] = loaded.queries[q];
    json perRobot = json::array();
    for (std::size_t r = 0; r < robots.size(); ++r) {
      json entry{{"robot", robots[r].name}, {"start", vectorJson(start.configurations[r])},
                 {"goal", vectorJson(goal.configurations[r])}};
      if (robots[r].baseLimits.x || robots[r].baseLimits.y || robots[r].baseLimits.z) {
        entry["start_base_pose"] = poseJson(start.basePoses[r]);
        entry["goal_base_pose"] = poseJson(goal.basePoses[r]);
      }
      perRobot.push_back(entry);
    }
    const QueryCollisions& result = collisions[q];
    const bool free = result.start.valid && result.goal.valid;
    queries.push_back({{"robots", perRobot},
                       {"collision_free", free},
                       {"start_collision", collisionReportJson(result.start)},
                       {"goal_collision", collisionReportJson(result.goal)},
                       {"collision_check", "start " + collisionSummary(result.start) + "; goal " +
                                               collisionSummary(result.goal)}});
  }
  return queries;
}

std::string fixed4(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.4f", value);
  return buffer;
}

std::string numbers(const json& values) {
  std::string text;
  for (const json& value : values) text += (text.empty() ? "" : " ") + fixed4(value.get<double>());
  return text;
}

std::string poseText(const json& pose) {
  return "xyz [" + numbers(pose["position"]) + "] quat(wxyz) [" + numbers(pose["quaternion_wxyz"]) + "]";
}

std::string robotsText(const json& robots) {
  std::string text;
  for (const json& robot : robots) {
    text += "robot " + robot["name"].get<std::string>() + " (" + robot["model"].get<std::string>() +
            ", " + std::to_string(robot["dofs"].get<int>()) + " DOFs, base " +
            poseText(robot["base_pose"]) + ")\n";
    for (const json& joint : robot["joints"]) {
      text += "  " + joint["name"].get<std::string>() + " " + joint["type"].get<std::string>() +
              " [" + fixed4(joint["lower"]) + ", " + fixed4(joint["upper"]) +
              "] value " + fixed4(joint["value"]) + "\n";
    }
    for (const json& arm : robot["manipulators"]) {
      text += "  manipulator " + arm["name"].get<std::string>() + ": tool frame " +
              arm["tool_frame"].get<std::string>() + ", " +
              std::to_string(arm["arm_joints"].size()) + " arm joints, " +
              std::to_string(arm["gripper_joints"].size()) + " gripper joints\n";
    }
  }
  return text;
}

std::string objectsText(const json& objects) {
  std::string text = objects.empty() ? "objects: none\n" : "objects:\n";
  for (const json& object : objects) {
    text += "  " + object["name"].get<std::string>() + " (" + object["kind"].get<std::string>() +
            (object["movable"].get<bool>() ? ", movable" : ", fixed") +
            (object["role"] == "none" ? "" : ", " + object["role"].get<std::string>()) + ") " +
            poseText(object["pose"]) + " size [" + numbers(object["size"]) + "]\n";
    if (object.contains("semantics_reason")) {
      text += "    " + object["semantics"].get<std::string>() + ": " + object["semantics_reason"].get<std::string>() + "\n";
    }
  }
  return text;
}

std::string controlsText(const json& controls) {
  std::string text = "controls (" + controls["file"].get<std::string>() + "):";
  for (const json& control : controls["controls"]) text += " " + control["name"].get<std::string>();
  return text + "\n";
}

std::string queriesText(const json& queries) {
  std::string text;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    text += "query " + std::to_string(i + 1) + ": (" + queries[i]["collision_check"].get<std::string>() + ")\n";
    for (const json& robot : queries[i]["robots"]) {
      text += "  " + robot["robot"].get<std::string>() + " start [" + numbers(robot["start"]) + "]\n";
      text += "  " + robot["robot"].get<std::string>() + " goal  [" + numbers(robot["goal"]) + "]\n";
      if (robot.contains("start_base_pose")) {
        text += "  " + robot["robot"].get<std::string>() + " start base " + poseText(robot["start_base_pose"]) + "\n";
        text += "  " + robot["robot"].get<std::string>() + " goal  base " + poseText(robot["goal_base_pose"]) + "\n";
      }
    }
  }
  return text;
}

}  // namespace

nlohmann::json problemReport(const LoadedProblem& loaded) {
  json robots = json::array();
  for (const SceneRobot& robot : loaded.problem.scene.robots()) robots.push_back(robotJson(robot));
  json objects = json::array();
  for (const SceneObject& object : loaded.problem.scene.objects()) objects.push_back(objectJson(object, loaded.objectSemantics));
  json attachments = json::array();
  for (const Attachment& attachment : loaded.problem.scene.attachments()) {
    attachments.push_back({{"object", attachment.object}, {"robot", attachment.robot}, {"link", attachment.link}});
  }
  json planner = {{"name", loaded.problem.planner.name}, {"parameters", json::object()}};
  for (const auto& [name, value] : loaded.problem.planner.parameters) planner["parameters"][name] = value;
  return {{"problem", loaded.name}, {"file", loaded.file}, {"format", loaded.format},
          {"robots", robots}, {"controls", controlsJson(loaded.problem.robotControls)},
          {"objects", objects}, {"attachments", attachments}, {"planner", planner},
          {"queries", queriesJson(loaded)}};
}

std::string problemReportText(const nlohmann::json& report) {
  std::string text = "problem " + report["problem"].get<std::string>() + " (" +
                     report["format"].get<std::string>() + ": " + report["file"].get<std::string>() + ")\n";
  text += robotsText(report["robots"]) + controlsText(report["controls"]) + objectsText(report["objects"]);
  for (const json& attachment : report["attachments"]) {
    text += "attached: " + attachment["object"].get<std::string>() + " to " +
            attachment["robot"].get<std::string>() + "/" + attachment["link"].get<std::string>() + "\n";
  }
  if (!report["planner"]["name"].get<std::string>().empty()) {
    text += "planner " + report["planner"]["name"].get<std::string>() + "\n";
  }
  return text + queriesText(report["queries"]);
}

}  // namespace lang2manip
