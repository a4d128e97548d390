// `lang2manip describe`: what lang2manip understood of each robot (groups, arms, tool frames,
// grippers measured by forward kinematics, named states) and of the objects, with --write-srdf.

#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "lang2manip/cli/commands.hpp"
#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/output_files.hpp"
#include "lang2manip/grounding/gripper_geometry.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/srdf_writer.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

struct DescribeOptions {
  std::string problem;
  std::string robot;  ///< empty: the Panda for MoveIt scenes
  SceneOptions scene;
  std::string writeSrdf;
  bool json = false;
};

json vector3(const Vector3& v) { return {v.x(), v.y(), v.z()}; }

/// How the gripper was measured and how sure that is: high when every pad's contact face was
/// found and the approach axis lies along a tool axis (or was given), low when neither holds.
void addMeasurement(const Manipulator& arm, const GripperGeometry& gripper, json& report) {
  constexpr double kAlongAxis = 0.999;
  const auto pads = static_cast<int>(gripper.padLinks.size());
  const Vector3 approach = gripper.graspFrame.linear() * gripper.approachAxis;
  const bool alongToolAxis = arm.approachAxis.has_value() || approach.cwiseAbs().maxCoeff() >= kAlongAxis;
  const bool facesFound = gripper.padsWithContactFace == pads;
  report["measured"] = std::to_string(gripper.padsWithContactFace) + " of " + std::to_string(pads) +
                       " pads' contact faces found on their collision surfaces" +
                       (facesFound ? "" : " (the others count whole)") + "; approach axis " +
                       (arm.approachAxis ? "given" : alongToolAxis ? "along a tool frame axis" : "oblique to the tool frame");
  report["confidence"] = facesFound && alongToolAxis ? "high" : facesFound || alongToolAxis ? "medium" : "low";
}

json gripperJson(const RobotModel& model, const Manipulator& arm) {
  json report{{"joints", json::array()}};
  GripperGeometry gripper;
  try {
    gripper = describeGripper(model, arm.name);
  } catch (const InputError& error) {
    report["error"] = error.what();
    return report;
  }
  for (std::size_t i = 0; i < gripper.gripperJoints.size(); ++i) {
    report["joints"].push_back({{"name", gripper.gripperJoints[i]}, {"open", gripper.openValues[i]}, {"closed", gripper.closedValues[i]}});
  }
  report["idle_joints"] = arm.idleHandJoints;
  const Matrix3 R = gripper.graspFrame.linear();
  report["approach_axis_in_tool_frame"] = vector3(R * gripper.approachAxis);
  report["approach_axis_source"] = arm.approachAxis ? "given"
                                   : gripper.hasGripper() ? "measured from the fingers"
                                                          : "the tool frame's +z";
  if (!gripper.hasGripper()) {
    report["kind"] = "none (moves and pushes; cannot pick)";
    return report;
  }
  report["kind"] = gripper.fixedJaw ? "one jaw against a fixed jaw"
                   : gripper.fingerCount == 2 ? "parallel"
                                              : std::to_string(gripper.fingerCount) + " fingers";
  report["opening"] = {{"max", gripper.maxOpening}, {"min", gripper.minOpening}};
  report["pads"] = gripper.padLinks;
  report["pad_depth"] = gripper.padDepth;
  report["finger_length"] = gripper.fingerLength;
  report["closing_axis_in_tool_frame"] = vector3(R * gripper.closingAxis);
  report["grasp_frame_in_tool_frame"] = vector3(gripper.graspFrame.translation());
  report["finger_bounds_in_grasp_frame"] = {{"min", vector3(gripper.fingerBounds.min())}, {"max", vector3(gripper.fingerBounds.max())}};
  addMeasurement(arm, gripper, report);
  return report;
}

json robotDescriptionJson(const SceneRobot& robot) {
  const RobotModel& model = *robot.model;
  const RobotSemantics& semantics = model.semantics();
  json report{{"name", robot.name}, {"model", model.name()},
              {"semantics", semantics.inferred ? "inferred from the kinematic tree (no SRDF)" : "SRDF " + semantics.source},
              {"manipulators", json::array()}, {"named_states", json::array()}};
  for (const Manipulator& arm : semantics.manipulators) {
    report["manipulators"].push_back({{"name", arm.name}, {"base_link", arm.baseLink}, {"tool_frame", arm.toolFrame},
                                      {"arm_joints", arm.armJoints}, {"gripper", gripperJson(model, arm)}});
  }
  for (const NamedState& state : semantics.namedStates) {
    json values = json::object();
    for (const auto& [joint, value] : state.values) values[joint] = value;
    report["named_states"].push_back({{"name", state.name}, {"group", state.group}, {"values", values}});
  }
  json pairs = json::array();
  for (const auto& [first, second] : semantics.enabledCollisions) pairs.push_back({first, second});
  report["collisions_off_by_default"] = semantics.defaultCollisionsDisabled;
  report["collisions_enabled"] = pairs;
  if (semantics.inferred && !semantics.defaultCollisionsDisabled.empty()) {
    report["collisions_off_by_default_reason"] =
        "self-collision envelopes: fixed links without a visual whose collision geometry covers their parent's; checked only "
        "against each other, three or more joints apart";
  }
  return report;
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

std::string triple(const json& v) { return "(" + number(v[0]) + ", " + number(v[1]) + ", " + number(v[2]) + ")"; }

std::string gripperText(const json& gripper) {
  if (gripper.contains("error")) return "    gripper: " + gripper["error"].get<std::string>() + "\n";
  std::string text = "    gripper: " + gripper["kind"].get<std::string>() + "\n";
  for (const json& joint : gripper["joints"]) {
    text += "      joint " + joint["name"].get<std::string>() + ": open " + number(joint["open"]) + ", closed " + number(joint["closed"]) + "\n";
  }
  for (const json& joint : gripper.value("idle_joints", json::array())) {
    text += "      joint " + joint.get<std::string>() +
            " turns without limits on the hand: no finger, not driven (its coupling to the fingers is not in the URDF)\n";
  }
  if (!gripper.contains("opening")) {
    return text + "      approach axis " + triple(gripper["approach_axis_in_tool_frame"]) + " in the tool frame (" +
           gripper["approach_axis_source"].get<std::string>() + ")\n";
  }
  std::string pads;
  for (const json& pad : gripper["pads"]) pads += (pads.empty() ? "" : ", ") + pad.get<std::string>();
  return text + "      opening " + number(gripper["opening"]["min"]) + " .. " + number(gripper["opening"]["max"]) + " m between pads " + pads +
         " (pad depth " + number(gripper["pad_depth"]) + " m, finger length " + number(gripper["finger_length"]) + " m)\n" +
         "      approach axis " + triple(gripper["approach_axis_in_tool_frame"]) + " (" +
         gripper["approach_axis_source"].get<std::string>() + "), closing axis " +
         triple(gripper["closing_axis_in_tool_frame"]) + " in the tool frame; grasp frame at " +
         triple(gripper["grasp_frame_in_tool_frame"]) + "\n" + "      measured: " + gripper["measured"].get<std::string>() +
         "; confidence " + gripper["confidence"].get<std::string>() + "\n";
}

std::string describeText(const json& report) {
  std::string text;
  for (const json& robot : report["robots"]) {
    text += "robot " + robot["name"].get<std::string>() + " (" + robot["model"].get<std::string>() + "): semantics " +
            robot["semantics"].get<std::string>() + "\n";
    for (const json& arm : robot["manipulators"]) {
      std::string joints;
      for (const json& joint : arm["arm_joints"]) joints += (joints.empty() ? "" : " ") + joint.get<std::string>();
      text += "  manipulator " + arm["name"].get<std::string>() + ": " + arm["base_link"].get<std::string>() + " -> tool frame " +
              arm["tool_frame"].get<std::string>() + ", arm joints " + joints + "\n" + gripperText(arm["gripper"]);
    }
    for (const json& state : robot["named_states"]) {
      text += "  named state " + state["name"].get<std::string>() + " (" + state["group"].get<std::string>() + ")\n";
    }
    if (!robot["collisions_off_by_default"].empty()) {
      std::string links;
      for (const json& link : robot["collisions_off_by_default"]) links += (links.empty() ? "" : ", ") + link.get<std::string>();
      text += "  collisions off by default: " + links + " (" + robot.value("collisions_off_by_default_reason", std::string("SRDF")) + "; " +
              std::to_string(robot["collisions_enabled"].size()) + " pairs checked)\n";
    }
    if (robot["semantics"].get<std::string>().rfind("inferred", 0) == 0) {
      text += "  (guessed from the tree: to change the arm, tool frame or gripper, write them as an SRDF with --write-srdf, edit it and\n"
              "   keep it beside the URDF under its name, e.g. robot.srdf for robot.urdf)\n";
    }
  }
  for (const json& object : report["objects"]) {
    text += "object " + object["name"].get<std::string>() + ": " + (object["movable"].get<bool>() ? "movable" : "fixed") + ", role " +
            object["role"].get<std::string>() + " (" +
            (object["source"] == "given" ? "" : object["source"].get<std::string>() + ": ") + object["reason"].get<std::string>() + ")\n";
  }
  return text;
}

/// The link pairs of the first robot that its allowed-collision matrix lets touch, with MoveIt's
/// reasons ("Adjacent", "Never", "Always"), added to `semantics` (those of an SRDF are there).
void addComputedDisabledPairs(const Scene& scene, RobotSemantics& semantics) {
  const FclCollisionChecker checker(scene);
  const AllowedCollisionMatrix& matrix = checker.allowedCollisions(0);
  const RobotModel& model = *scene.robots().front().model;
  const int links = matrix.linkCount();
  for (int a = 0; a < links; ++a) {
    for (int b = a + 1; b < links; ++b) {
      const std::vector<Link>& all = model.links();
      if (all[static_cast<std::size_t>(a)].collisions.empty() || all[static_cast<std::size_t>(b)].collisions.empty()) continue;
      const AllowedReason reason = matrix.reason(a, b);
      const char* name = reason == AllowedReason::kAdjacent ? "Adjacent" : reason == AllowedReason::kNever ? "Never"
                         : reason == AllowedReason::kAlways ? "Always" : reason == AllowedReason::kDefault ? "Default" : nullptr;
      if (name != nullptr) semantics.disabledCollisions.push_back({all[static_cast<std::size_t>(a)].name, all[static_cast<std::size_t>(b)].name, name});
    }
  }
}

void describe(const DescribeOptions& options, std::ostream& out) {
  const LoadedProblem loaded = loadProblem(options.problem, options.robot, options.scene);
  json report{{"robots", json::array()}, {"objects", json::array()}};
  for (const SceneRobot& robot : loaded.problem.scene.robots()) report["robots"].push_back(robotDescriptionJson(robot));
  for (const ObjectSemanticsDecision& decision : loaded.objectSemantics) {
    report["objects"].push_back({{"name", decision.object}, {"movable", decision.movable}, {"role", objectRoleName(decision.role)},
                                 {"source", semanticsSourceName(decision.source)}, {"reason", decision.reason}});
  }
  if (!options.writeSrdf.empty()) {
    if (loaded.problem.scene.robots().empty()) throw InputError("describe --write-srdf: the scene has no robot");
    const RobotModel& model = *loaded.problem.scene.robots().front().model;
    RobotSemantics semantics = model.semantics();
    for (Manipulator& arm : semantics.manipulators) {
      try {
        const GripperGeometry gripper = describeGripper(model, arm.name);
        arm.gripperOpen = gripper.openValues;
        arm.gripperClosed = gripper.closedValues;
        arm.approachAxis = gripper.graspFrame.linear() * gripper.approachAxis;
      } catch (const InputError&) {
        // Written as inferred; the printed description says why the gripper cannot grasp.
      }
    }
    addComputedDisabledPairs(loaded.problem.scene, semantics);
    writeFileAtomically(options.writeSrdf, srdfString(model, semantics), "describe: --write-srdf");
    report["srdf"] = options.writeSrdf;
  }
  out << (options.json ? report.dump(2) + "\n" : describeText(report));
  if (!options.json && report.contains("srdf")) out << "wrote " << options.writeSrdf << "\n";
}

}  // namespace

void addDescribeCommand(CLI::App& app, std::ostream& out) {
  auto options = std::make_shared<DescribeOptions>();
  CLI::App* command = app.add_subcommand(
      "describe", "Print what lang2manip understood of a robot or problem: arms, tool frames, grippers, named states, objects");
  command->add_option("PROBLEM", options->problem,
                      "Robot description (.urdf, .xacro), built-in problem name, Kautham problem .xml or MoveIt scene .yaml (default: " +
                          defaultProblemName() + ")");
  command->add_option("--robot", options->robot, "Robot of a MoveIt scene: a built-in name or a .urdf/.xacro file (default: panda)");
  addSceneOptions(*command, options->scene);
  command->add_option("--write-srdf", options->writeSrdf, "Write the first robot's semantics as an SRDF file to edit");
  command->add_flag("--json", options->json, "Print JSON");
  command->callback([options, &out] { describe(*options, out); });
}

}  // namespace lang2manip
