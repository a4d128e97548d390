#include <cstdio>

#include "lang2manip/symbolic/observation.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

std::string number(const json& value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3f", value.get<double>());
  return buffer;
}

std::string numbers(const json& values) {
  std::string text;
  for (const json& value : values) text += (text.empty() ? "" : ", ") + number(value);
  return "(" + text + ")";
}

std::string degrees(const json& radians) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.0f deg", radians.get<double>() * 180.0 / 3.14159265358979323846);
  return buffer;
}

std::string orNothing(const json& value, const std::string& nothing) {
  return value.is_null() ? nothing : value.get<std::string>();
}

std::string list(const json& values) {
  std::string text;
  for (const json& value : values) text += (text.empty() ? "" : ", ") + value.get<std::string>();
  return text;
}

std::string jointsText(const json& joints) {
  std::string text = "  joints (name type value [lower, upper]):\n";
  for (const json& joint : joints) {
    text += "    " + joint["name"].get<std::string>() + " " + joint["type"].get<std::string>() + " " +
            number(joint["value"]) + " [" + number(joint["lower"]) + ", " + number(joint["upper"]) + "]\n";
  }
  return text;
}

std::string linksText(const json& links) {
  std::string text;
  for (const json& link : links) {
    if (link["parent"].is_null()) continue;
    text += (text.empty() ? "" : ", ") + link["parent"].get<std::string>() + " > " + link["name"].get<std::string>();
  }
  return "  link tree (parent > child): " + (text.empty() ? std::string("single link") : text) + "\n";
}

std::string effectorText(const json& effector) {
  const json& gripper = effector["gripper"];
  std::string text = "  end effector " + effector["name"].get<std::string>() + ": tool frame " +
                     effector["tool_frame"].get<std::string>() + " at " +
                     numbers(effector["pose"]["position"]) + " world, " +
                     numbers(effector["position_in_base"]) + " in the base frame; gripper " +
                     gripper["state"].get<std::string>();
  if (!gripper["joints"].empty()) {
    text += " (" + list(gripper["joints"]) + " = " + numbers(gripper["values"]) + ", open " +
            numbers(gripper["open"]) + ", closed " + numbers(gripper["closed"]) + ")";
  }
  return text + ", holding " + orNothing(effector["holding"], "nothing") + "\n";
}

std::string robotText(const json& robot) {
  std::string text = "Robot " + robot["name"].get<std::string>() + " (model " + robot["model"].get<std::string>() +
                     ", " + std::to_string(robot["dofs"].get<int>()) + " DOFs), base at " +
                     numbers(robot["base_pose"]["position"]) + " facing yaw " + degrees(robot["base_pose"]["yaw"]) +
                     " in the world\n";
  text += jointsText(robot["joints"]) + linksText(robot["links"]);
  for (const json& effector : robot["end_effectors"]) text += effectorText(effector);
  text += "  configuration: " + orNothing(robot["configuration"], "no named configuration");
  if (!robot["named_configurations"].empty()) text += " (named configurations: " + list(robot["named_configurations"]) + ")";
  return text + "\n";
}

std::string regionText(const json& object) {
  const auto region = object.find("region");
  if (region == object.end()) return "";
  return " in its " + region->get<std::string>();
}

std::string objectState(const json& object) {
  std::string text;
  if (object["held"].get<bool>()) text = "held by the robot";
  if (!object["in"].is_null()) text = "in " + object["in"].get<std::string>();
  if (!object["on"].is_null()) text = "on " + object["on"].get<std::string>() + regionText(object);
  if (text.empty()) text = "not on any object";
  return text + (object["clear"].get<bool>() ? ", clear" : ", not clear");
}

std::string span(const json& range) { return "[" + number(range[0]) + ", " + number(range[1]) + "]"; }

/// "; top at z 0.000, x [0.100, 0.900] y [-0.600, 0.600], reachable x [...] y [...]".
std::string topText(const json& object) {
  const auto top = object.find("top");
  if (top == object.end()) return "";
  const json& area = (*top)["area"];
  const json& reach = (*top)["reachable"];
  std::string text = "; flat top at z " + number((*top)["height"]) + " (base frame), x " + span(area["x"]) + " y " + span(area["y"]);
  if ((*top)["clipped"].get<bool>()) {
    text += ", of which the arm reaches x " + span(reach["x"]) + " y " + span(reach["y"]) + " (its regions are of that part)";
  }
  return text;
}

std::string objectText(const json& object) {
  std::string role = object["movable"].get<bool>() ? "movable" : "fixed";
  if (object["role"] != "none") role += " " + object["role"].get<std::string>();
  if (object.contains("semantics")) role += " (" + object["semantics"].get<std::string>() + ")";
  const json& d = object["dimensions"];
  std::string looks;
  if (object.contains("category") && object["category"].is_string()) looks += " (a " + object["category"].get<std::string>() + ")";
  if (object.contains("colour") && object["colour"].is_string()) looks += ", " + object["colour"].get<std::string>();
  return "  " + object["name"].get<std::string>() + ": kind " + object["kind"].get<std::string>() + looks + ", " + role +
         "; at " + numbers(object["position"]) + " world, " + numbers(object["position_in_base"]) +
         " in the base frame (" + object["side_of_robot"].get<std::string>() + " of the robot, " +
         number(object["distance_from_robot"]) + " m away); yaw " + degrees(object["yaw"]) + "; size " +
         number(d[0]) + " x " + number(d[1]) + " x " + number(d[2]) + " m; " + objectState(object) + topText(object) + "\n";
}

}  // namespace

std::string observationText(const nlohmann::json& observation) {
  std::string text = "Frames: " + observation["frames"].get<std::string>() + ".\n";
  if (const auto conventions = observation.find("conventions"); conventions != observation.end() && conventions->is_string()) {
    text += "Conventions: " + conventions->get<std::string>() + ".\n";
  }
  for (const json& robot : observation["robots"]) text += robotText(robot);
  text += "Objects (position = origin of the object frame):\n";
  for (const json& object : observation["objects"]) text += objectText(object);
  text += "Relations:\n";
  for (const json& relation : observation["relations"]) {
    text += "  " + relation["subject"].get<std::string>() + " " + relation["relation"].get<std::string>() + " " +
            relation["object"].get<std::string>() + "\n";
  }
  return text;
}

}  // namespace lang2manip
