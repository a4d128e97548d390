#include "lang2manip/model/moveit_scene_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <optional>
#include <string_view>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/model/geometry.hpp"
#include "lang2manip/model/moveit_yaml.hpp"

namespace lang2manip {
namespace {

using moveit_yaml::joined;
using moveit_yaml::optionalText;
using moveit_yaml::readBasePose;
using moveit_yaml::readPose;
using moveit_yaml::readYamlFile;
using moveit_yaml::rejectNonEmpty;
using moveit_yaml::texts;
using moveit_yaml::YamlValue;

// ---------------------------------------------------------------------------------------------
// Collision objects

/// SolidPrimitive type: a name or the message's number (1 box, 2 sphere, 3 cylinder, 4 cone).
std::string primitiveType(const YamlValue& type) {
  static const std::array<std::string, 5> kNumbered = {"", "box", "sphere", "cylinder", "cone"};
  std::string name = lowercase(type.text("a primitive type"));
  if (name.size() == 1 && name[0] >= '1' && name[0] <= '4') name = kNumbered.at(name[0] - '0');
  if (name == "cone") type.fail("cone primitives are not supported (only box, sphere, cylinder)");
  if (name != "box" && name != "sphere" && name != "cylinder") {
    type.fail("unknown primitive type '" + name + "' (valid: box, sphere, cylinder)");
  }
  return name;
}

/// Exactly `count` positive dimensions (`layout` names them in the message).
std::vector<double> dimensions(const YamlValue& value, std::size_t count,
                               const std::string& layout) {
  const std::vector<YamlValue> items = value.items();
  if (items.size() != count) {
    value.fail("expected " + std::to_string(count) + (count == 1 ? " dimension " : " dimensions ") +
               layout + ", got " + std::to_string(items.size()));
  }
  std::vector<double> result;
  for (const YamlValue& item : items) {
    result.push_back(item.number());
    if (result.back() <= 0.0) item.fail("a dimension must be positive");
    const std::string problem = dimensionRangeProblem(result.back());
    if (!problem.empty()) item.fail("dimension " + problem);
  }
  return result;
}

Geometry readPrimitive(const YamlValue& primitive) {
  const std::string type = primitiveType(primitive.child("type"));
  const YamlValue value = primitive.child("dimensions");
  if (type == "box") {
    const std::vector<double> d = dimensions(value, 3, "[x, y, z] for a box");
    return Box{Vector3(d[0], d[1], d[2])};
  }
  if (type == "sphere") return Sphere{dimensions(value, 1, "[radius] for a sphere")[0]};
  const std::vector<double> d = dimensions(value, 2, "[height, radius] for a cylinder");
  return Cylinder{.radius = d[1], .length = d[0]};
}

std::vector<Shape> readPrimitives(const YamlValue& object) {
  const YamlValue poseList = object.child("primitive_poses");
  const std::vector<YamlValue> primitives = object.child("primitives").items();
  const std::vector<YamlValue> poses = poseList.items();
  if (primitives.empty()) object.child("primitives").fail("an object needs at least one primitive");
  if (poses.size() != primitives.size()) {
    poseList.fail("expected " + std::to_string(primitives.size()) +
                  " poses (one per primitive), got " + std::to_string(poses.size()));
  }
  std::vector<Shape> shapes;
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    Shape shape;
    shape.geometry = readPrimitive(primitives[i]);
    shape.origin = readPose(poses[i], "position", "orientation");
    shapes.push_back(std::move(shape));
  }
  return shapes;
}

/// CollisionObject operation: absent or ADD (0) only.
void requireAddOperation(const YamlValue& object) {
  static const std::array<std::string, 4> kNumbered = {"add", "remove", "append", "move"};
  const std::optional<YamlValue> operation = object.find("operation");
  if (!operation) return;
  std::string name = lowercase(operation->text("an operation"));
  if (name.size() == 1 && name[0] >= '0' && name[0] <= '3') name = kNumbered.at(name[0] - '0');
  if (name != "add") {
    operation->fail("operation '" + name + "' is not supported (only ADD)");
  }
}

/// Objects must be given in the planning frame (an empty frame_id or "world").
void requireWorldFrame(const YamlValue& object) {
  const std::optional<YamlValue> header = object.find("header");
  const std::optional<YamlValue> frame = header ? header->find("frame_id") : std::nullopt;
  if (!frame) return;
  const std::string name = frame->text("a frame name");
  if (!name.empty() && name != "world") {
    frame->fail("frame '" + name + "' is not supported (objects must be given in \"world\")");
  }
}

std::string objectKind(const std::vector<Shape>& shapes) {
  const std::string first = geometryKindName(shapes.front().geometry);
  for (const Shape& shape : shapes) {
    if (geometryKindName(shape.geometry) != first) return "obstacle";
  }
  return first;
}

/// Chooses the object frame so that no pose is recomputed (see the header).
void placeShapes(SceneObject& object, std::vector<Shape> shapes, const std::optional<Pose>& frame) {
  if (frame) {
    object.pose = *frame;
  } else if (shapes.size() == 1) {
    object.pose = shapes.front().origin;
    shapes.front().origin = Pose::Identity();
  }
  object.collisions = std::move(shapes);
}

SceneObject readCollisionObject(const YamlValue& object) {
  requireAddOperation(object);
  requireWorldFrame(object);
  rejectNonEmpty(object, "meshes", "mesh collision objects are not supported (only primitives)");
  rejectNonEmpty(object, "planes", "plane collision objects are not supported (only primitives)");
  SceneObject result;
  result.name = object.child("id").text("an object id");
  if (result.name.empty()) object.child("id").fail("an object id must not be empty");
  std::vector<Shape> shapes = readPrimitives(object);
  result.kind = objectKind(shapes);
  const std::optional<YamlValue> pose = object.find("pose");
  placeShapes(
      result, std::move(shapes),
      pose ? std::optional<Pose>(readPose(*pose, "position", "orientation")) : std::nullopt);
  return result;
}

void addCollisionObjects(const YamlValue& scene, Scene& target) {
  const std::optional<YamlValue> world = scene.find("world");
  const std::optional<YamlValue> list = world ? world->find("collision_objects") : std::nullopt;
  if (!list) return;
  for (const YamlValue& object : list->items()) {
    SceneObject read = readCollisionObject(object);
    if (target.findObject(read.name) != nullptr || target.findRobot(read.name) != nullptr) {
      object.child("id").fail("duplicate name '" + read.name + "'");
    }
    target.addObject(std::move(read));
  }
}

// ---------------------------------------------------------------------------------------------
// Allowed collision matrix

std::vector<std::vector<bool>> readFlagMatrix(const YamlValue& values, std::size_t size) {
  const std::vector<YamlValue> rows = values.items();
  if (rows.size() != size) {
    values.fail("expected " + std::to_string(size) + " rows (one per entry name), got " +
                std::to_string(rows.size()));
  }
  std::vector<std::vector<bool>> matrix;
  for (const YamlValue& row : rows) {
    const std::vector<YamlValue> cells = row.items();
    if (cells.size() != size) {
      row.fail("expected " + std::to_string(size) + " values (the matrix must be square), got " +
               std::to_string(cells.size()));
    }
    matrix.emplace_back();
    for (const YamlValue& cell : cells) matrix.back().push_back(cell.flag());
  }
  return matrix;
}

std::vector<std::pair<std::string, std::string>> readAllowedCollisions(const YamlValue& scene) {
  const std::optional<YamlValue> acm = scene.find("allowed_collision_matrix");
  const std::optional<YamlValue> names = acm ? acm->find("entry_names") : std::nullopt;
  if (!names) return {};
  const std::vector<std::string> entries = texts(*names, "an entry name");
  const YamlValue values = acm->child("entry_values");
  const std::vector<std::vector<bool>> matrix = readFlagMatrix(values, entries.size());
  std::vector<std::pair<std::string, std::string>> pairs;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    for (std::size_t j = i + 1; j < entries.size(); ++j) {
      if (matrix[i][j] != matrix[j][i]) {
        values.fail("not symmetric: [" + std::to_string(i) + "][" + std::to_string(j) + "] and [" +
                    std::to_string(j) + "][" + std::to_string(i) + "] (" + entries[i] + ", " +
                    entries[j] + ") differ");
      }
      if (matrix[i][j]) pairs.emplace_back(entries[i], entries[j]);
    }
  }
  return pairs;
}

// ---------------------------------------------------------------------------------------------
// Joint values

/// The variable of the joint named by `name`; fails listing the variables when there is none.
int variableIndexAt(const RobotModel& model, const YamlValue& name) {
  const std::string joint = name.text("a joint name");
  try {
    return model.variableIndex(joint);
  } catch (const InputError&) {
    const std::string problem =
        model.findJoint(joint) ? "joint '" + joint + "' is not a variable (a fixed or mimic joint)"
                               : "unknown joint '" + joint + "'";
    name.fail(problem + " (robot '" + model.name() +
              "' has the joint variables: " + joined(model.variableNames()) + ")");
  }
}

bool isMimicJoint(const RobotModel& model, const std::string& joint) {
  const std::optional<int> index = model.findJoint(joint);
  return index && model.joints().at(static_cast<std::size_t>(*index)).mimic.has_value();
}

bool isGripperJoint(const RobotModel& model, const std::string& joint) {
  for (const Manipulator& manipulator : model.semantics().manipulators) {
    const std::vector<std::string>& gripper = manipulator.gripperJoints;
    if (std::find(gripper.begin(), gripper.end(), joint) != gripper.end()) return true;
  }
  return false;
}

/// Clamps a gripper joint's value to its limits and records it (see the header).
void clampGripperJoint(const RobotModel& model, const std::string& joint, int variable,
                       MoveItProblem& problem) {
  if (!isGripperJoint(model, joint)) return;
  double& value = problem.start[variable];
  const double used =
      std::clamp(value, model.lowerLimits()[variable], model.upperLimits()[variable]);
  if (used == value) return;
  problem.clampedJoints.push_back({joint, value, used});
  value = used;
}

void applyStartState(const YamlValue& startState, const RobotModel& model, MoveItProblem& problem) {
  const std::optional<YamlValue> state = startState.find("joint_state");
  if (!state) return;
  const std::vector<YamlValue> names = state->child("name").items();
  const YamlValue positionList = state->child("position");
  const std::vector<YamlValue> positions = positionList.items();
  if (positions.size() != names.size()) {
    positionList.fail("expected " + std::to_string(names.size()) +
                      " positions (one per joint name), got " + std::to_string(positions.size()));
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string joint = names[i].text("a joint name");
    if (isMimicJoint(model, joint)) continue;
    const int variable = variableIndexAt(model, names[i]);
    problem.start[variable] = positions[i].number();
    clampGripperJoint(model, joint, variable, problem);
  }
}

void readGoal(const YamlValue& request, const RobotModel& model, MoveItProblem& problem) {
  const YamlValue list = request.child("goal_constraints");
  const std::vector<YamlValue> goals = list.items();
  if (goals.empty()) list.fail("there is no goal constraint");
  if (goals.size() > 1) goals[1].fail("several goal constraints are not supported (only one)");
  for (const char* kind : {"position", "orientation", "visibility"}) {
    rejectNonEmpty(goals[0], std::string(kind) + "_constraints",
                   std::string(kind) + " constraints are not supported (only joint constraints)");
  }
  const YamlValue jointList = goals[0].child("joint_constraints");
  const std::vector<YamlValue> joints = jointList.items();
  if (joints.empty()) jointList.fail("there is no joint constraint");
  problem.goal = problem.start;
  for (const YamlValue& constraint : joints) {
    const YamlValue name = constraint.child("joint_name");
    problem.goal[variableIndexAt(model, name)] = constraint.child("position").number();
    problem.goalJoints.push_back(name.text("a joint name"));
  }
}

double readPlanningTime(const YamlValue& request) {
  const std::optional<YamlValue> value = request.find("allowed_planning_time");
  if (!value) return 0.0;
  const double seconds = value->number();
  if (seconds < 0.0) value->fail("must not be negative");
  return seconds;
}

// ---------------------------------------------------------------------------------------------
// Request and scene

/// Reads the request; returns its start state's base pose, if any.
std::optional<Pose> readRequest(const YamlValue& request, const RobotModel& model,
                                MoveItProblem& problem) {
  problem.group = optionalText(request, "group_name");
  problem.plannerId = optionalText(request, "planner_id");
  problem.allowedPlanningTime = readPlanningTime(request);
  problem.start = model.middleConfiguration();
  const std::optional<YamlValue> startState = request.find("start_state");
  if (startState) applyStartState(*startState, model, problem);
  readGoal(request, model, problem);
  return startState ? readBasePose(*startState) : std::nullopt;
}

Pose sceneBasePose(const YamlValue& scene) {
  const std::optional<YamlValue> state = scene.find("robot_state");
  const std::optional<Pose> pose = state ? readBasePose(*state) : std::nullopt;
  return pose.value_or(Pose::Identity());
}

void readScene(const YamlValue& scene, const RobotModelPtr& model,
               const std::optional<Pose>& requestBase, MoveItProblem& problem) {
  SceneRobot robot;
  robot.name = optionalText(scene, "robot_model_name");
  if (robot.name.empty()) robot.name = model->name();
  robot.model = model;
  const Pose sceneBase = sceneBasePose(scene);
  robot.basePose = requestBase.value_or(sceneBase);
  robot.configuration = problem.start;
  problem.robot = robot.name;
  problem.scene.addRobot(std::move(robot));
  addCollisionObjects(scene, problem.scene);
  problem.allowedCollisions = readAllowedCollisions(scene);
}

}  // namespace

MoveItProblem readMoveItProblem(const std::filesystem::path& sceneFile,
                                const std::filesystem::path& requestFile, RobotModelPtr robot) {
  if (!robot) throw InputError("readMoveItProblem: no robot model given");
  MoveItProblem problem;
  problem.sceneFile = sceneFile;
  problem.requestFile = requestFile;
  std::optional<Pose> requestBase;
  readYamlFile(requestFile, [&](const YamlValue& request) {
    requestBase = readRequest(request, *robot, problem);
  });
  readYamlFile(sceneFile,
               [&](const YamlValue& scene) { readScene(scene, robot, requestBase, problem); });
  return problem;
}

std::filesystem::path requestFileForScene(const std::filesystem::path& sceneFile) {
  const std::string name = sceneFile.filename().string();
  constexpr std::string_view kPrefix = "scene";
  constexpr std::string_view kSuffix = ".yaml";
  const bool matches = name.size() > kPrefix.size() + kSuffix.size() && name.starts_with(kPrefix) &&
                       name.ends_with(kSuffix) &&
                       std::all_of(name.begin() + kPrefix.size(), name.end() - kSuffix.size(),
                                   [](unsigned char c) { return std::isdigit(c) != 0; });
  if (!matches) {
    throw InputError(SourceLocation{sceneFile.string(), 0},
                     "not a MotionBenchMaker scene file name (expected sceneNNNN.yaml)");
  }
  const std::string digits =
      name.substr(kPrefix.size(), name.size() - kPrefix.size() - kSuffix.size());
  return sceneFile.parent_path() / ("request" + digits + std::string(kSuffix));
}

}  // namespace lang2manip
