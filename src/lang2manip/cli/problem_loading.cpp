#include "lang2manip/cli/problem_loading.hpp"

#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/moveit_scene_reader.hpp"
#include "lang2manip/model/srdf_reader.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "lang2manip/model/xacro.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace lang2manip {
namespace {

/// How the robots of a problem are read: xacro arguments and approach axes from the command line.
struct RobotReading {
  std::map<std::string, std::string> xacroArguments;
  std::map<std::string, Vector3> approachAxes;
};

/// "[MANIPULATOR=]AXIS" with AXIS one of +x -x +y -y +z -z (x for +x) or "X,Y,Z".
std::pair<std::string, Vector3> parseApproachAxisOption(const std::string& option) {
  const std::size_t equals = option.find('=');
  const std::string name = equals == std::string::npos ? "" : option.substr(0, equals);
  std::string axis = equals == std::string::npos ? option : option.substr(equals + 1);
  const SourceLocation where{"--approach-axis \"" + option + "\"", 0};
  static const std::map<std::string, Vector3> named{
      {"+x", Vector3::UnitX()}, {"x", Vector3::UnitX()}, {"-x", -Vector3::UnitX()},
      {"+y", Vector3::UnitY()}, {"y", Vector3::UnitY()}, {"-y", -Vector3::UnitY()},
      {"+z", Vector3::UnitZ()}, {"z", Vector3::UnitZ()}, {"-z", -Vector3::UnitZ()}};
  if (const auto found = named.find(lowercase(axis)); found != named.end()) return {name, found->second};
  if (axis.find(',') == std::string::npos) {
    throw InputError(where, "expected [MANIPULATOR=]AXIS with AXIS one of +x, -x, +y, -y, +z, -z or X,Y,Z");
  }
  std::replace(axis.begin(), axis.end(), ',', ' ');
  return {name, approachAxisFromText(axis, where)};
}

RobotReading robotReading(const SceneOptions& options) {
  RobotReading reading;
  for (const std::string& argument : options.xacroArguments) {
    const auto [name, value] = parseXacroArgument(argument);
    reading.xacroArguments[name] = value;
  }
  for (const std::string& option : options.approachAxes) {
    const auto [name, axis] = parseApproachAxisOption(option);
    reading.approachAxes[name] = axis;
  }
  return reading;
}

bool isRobotDescription(const std::filesystem::path& file) {
  return file.extension() == ".urdf" || isXacroFile(file);
}

RobotModelPtr loadRobot(const std::string& robot, const RobotReading& reading) {
  UrdfReadOptions options;
  options.xacroArguments = reading.xacroArguments;
  options.approachAxes = reading.approachAxes;
  return readUrdfFile(isRobotDescription(robot) ? std::filesystem::path(robot) : builtinRobotUrdf(robot), options);
}

LoadedProblem loadRobotOnly(const std::filesystem::path& file, const RobotReading& reading) {
  const RobotModelPtr model = loadRobot(file.string(), reading);
  Scene scene;
  scene.addRobot(SceneRobot{model->name(), model, Pose::Identity(), model->middleConfiguration(), {}});
  LoadedProblem loaded;
  loaded.name = model->name();
  loaded.file = file.string();
  loaded.format = "robot";
  loaded.problem = kauthamProblemFromScene(scene, loaded.name);
  return loaded;
}

LoadedProblem loadMoveIt(const std::filesystem::path& sceneFile, const std::string& robot, const RobotReading& reading) {
  const RobotModelPtr model = loadRobot(robot, reading);
  const MoveItProblem moveit = readMoveItProblem(sceneFile, requestFileForScene(sceneFile), model);
  LoadedProblem loaded;
  loaded.name = sceneFile.parent_path().filename().string() + "/" + sceneFile.stem().string();
  loaded.file = sceneFile.string();
  loaded.format = "moveit";
  loaded.problem = kauthamProblemFromScene(moveit.scene, loaded.name);
  loaded.problem.queries.push_back(kauthamQueryFromStates(loaded.problem, {moveit.start}, {moveit.goal}));
  const Pose base = moveit.scene.robots().front().basePose;
  loaded.queries.push_back({RobotStates{{moveit.start}, {base}}, RobotStates{{moveit.goal}, {base}}});
  return loaded;
}

LoadedProblem loadKautham(const std::filesystem::path& file, const RobotReading& reading) {
  LoadedProblem loaded;
  KauthamReadOptions options;
  options.xacroArguments = reading.xacroArguments;
  options.approachAxes = reading.approachAxes;
  loaded.problem = readKauthamProblem(file, options);
  loaded.name = loaded.problem.name;
  loaded.file = file.string();
  loaded.format = "kautham";
  for (std::size_t i = 0; i < loaded.problem.queries.size(); ++i) {
    const KauthamQuery& query = loaded.problem.queries[i];
    const std::string what = "query " + std::to_string(i + 1);
    loaded.queries.push_back(
        {robotStatesFromControls(loaded.problem, query.init, what + " init"),
         robotStatesFromControls(loaded.problem, query.goal, what + " goal")});
  }
  return loaded;
}

/// Refuses a robot chosen for a problem that names its own robots.
void refuseRobotChoice(const std::string& robot, const std::string& problem) {
  if (robot.empty()) return;
  throw InputError(SourceLocation{problem, 0}, "robot \"" + robot +
                                                   "\" was chosen, but a robot is chosen only for a MoveIt scene (which names "
                                                   "none): this problem names its own robots (see lang2manip describe)");
}

LoadedProblem loadProblemFile(const std::string& nameOrPath, const std::string& robot, const RobotReading& reading) {
  if (isRobotDescription(nameOrPath)) {
    refuseRobotChoice(robot, nameOrPath);
    return loadRobotOnly(nameOrPath, reading);
  }
  const std::filesystem::path file = resolveProblem(nameOrPath.empty() ? defaultProblemName() : nameOrPath);
  const std::string extension = file.extension().string();
  if (extension == ".yaml" || extension == ".yml") return loadMoveIt(file, robot.empty() ? "panda" : robot, reading);
  if (extension != ".xml") {
    throw InputError(SourceLocation{file.string(), 0},
                     "not a problem file: expected a Kautham problem (.xml), a MoveIt planning scene "
                     "(.yaml) or a robot description (.urdf, .xacro)");
  }
  refuseRobotChoice(robot, file.string());
  return loadKautham(file, reading);
}

}  // namespace

LoadedProblem loadProblem(const std::string& nameOrPath, const std::string& robot, const SceneOptions& options) {
  LoadedProblem loaded = loadProblemFile(nameOrPath, robot, robotReading(options));
  loaded.problem.scene.setContactTolerance(options.contactTolerance);
  loaded.objectSemantics = inferObjectSemantics(loaded.problem.scene, {options.movable, options.fixed});
  return loaded;
}

bool isMoveItSceneName(const std::string& nameOrPath) {
  const std::string extension = std::filesystem::path(nameOrPath).extension().string();
  return extension == ".yaml" || extension == ".yml";
}

void addSceneOptions(CLI::App& command, SceneOptions& options) {
  command.add_option("--xacro-arg", options.xacroArguments,
                     "NAME:=VALUE for the <xacro:arg>s of .xacro robots (repeatable; over a problem's <XacroArg>s)");
  command.add_option("--movable", options.movable, "Objects to treat as movable (comma-separated; over the model and inference)")
      ->delimiter(',');
  command.add_option("--fixed", options.fixed, "Objects to treat as fixed (comma-separated; over the model and inference)")
      ->delimiter(',');
  command.add_option("--approach-axis", options.approachAxes,
                     "[MANIPULATOR=]AXIS: the direction the tool moves into an object, in its tool frame (+x, -x, +y, "
                     "-y, +z, -z or X,Y,Z; repeatable; over the SRDF and what is measured from the fingers)");
  command.add_option("--contact-tolerance", options.contactTolerance,
                     "Penetration (m) up to which a robot base or a held object rests on a fixed object "
                     "instead of colliding with it (0 to 0.01; default 0.0005)");
}

}  // namespace lang2manip
