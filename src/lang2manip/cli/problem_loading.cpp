#include "lang2manip/cli/problem_loading.hpp"

#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/moveit_scene_reader.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "lang2manip/model/xacro.hpp"

#include <map>

namespace lang2manip {
namespace {

using XacroArguments = std::map<std::string, std::string>;

bool isRobotDescription(const std::filesystem::path& file) {
  return file.extension() == ".urdf" || isXacroFile(file);
}

RobotModelPtr loadRobot(const std::string& robot, const XacroArguments& arguments) {
  UrdfReadOptions options;
  options.xacroArguments = arguments;
  return readUrdfFile(isRobotDescription(robot) ? std::filesystem::path(robot) : builtinRobotUrdf(robot), options);
}

LoadedProblem loadRobotOnly(const std::filesystem::path& file, const XacroArguments& arguments) {
  const RobotModelPtr model = loadRobot(file.string(), arguments);
  Scene scene;
  scene.addRobot(SceneRobot{model->name(), model, Pose::Identity(), model->middleConfiguration(), {}});
  LoadedProblem loaded;
  loaded.name = model->name();
  loaded.file = file.string();
  loaded.format = "robot";
  loaded.problem = kauthamProblemFromScene(scene, loaded.name);
  return loaded;
}

LoadedProblem loadMoveIt(const std::filesystem::path& sceneFile, const std::string& robot, const XacroArguments& arguments) {
  const RobotModelPtr model = loadRobot(robot, arguments);
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

LoadedProblem loadKautham(const std::filesystem::path& file, const XacroArguments& arguments) {
  LoadedProblem loaded;
  KauthamReadOptions options;
  options.xacroArguments = arguments;
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

LoadedProblem loadProblemFile(const std::string& nameOrPath, const std::string& robot,
                              const std::vector<std::string>& xacroArguments) {
  XacroArguments arguments;
  for (const std::string& argument : xacroArguments) {
    const auto [name, value] = parseXacroArgument(argument);
    arguments[name] = value;
  }
  if (isRobotDescription(nameOrPath)) return loadRobotOnly(nameOrPath, arguments);
  const std::filesystem::path file = resolveProblem(nameOrPath.empty() ? defaultProblemName() : nameOrPath);
  const std::string extension = file.extension().string();
  if (extension == ".yaml" || extension == ".yml") return loadMoveIt(file, robot, arguments);
  if (extension != ".xml") {
    throw InputError(SourceLocation{file.string(), 0},
                     "not a problem file: expected a Kautham problem (.xml), a MoveIt planning scene "
                     "(.yaml) or a robot description (.urdf, .xacro)");
  }
  return loadKautham(file, arguments);
}

}  // namespace

LoadedProblem loadProblem(const std::string& nameOrPath, const std::string& robot, const SceneOptions& options) {
  LoadedProblem loaded = loadProblemFile(nameOrPath, robot, options.xacroArguments);
  loaded.problem.scene.setContactTolerance(options.contactTolerance);
  loaded.objectSemantics = inferObjectSemantics(loaded.problem.scene, {options.movable, options.fixed});
  return loaded;
}

void addSceneOptions(CLI::App& command, SceneOptions& options) {
  command.add_option("--xacro-arg", options.xacroArguments,
                     "NAME:=VALUE for the <xacro:arg>s of .xacro robots (repeatable; over a problem's <XacroArg>s)");
  command.add_option("--movable", options.movable, "Objects to treat as movable (comma-separated; over the model and inference)")
      ->delimiter(',');
  command.add_option("--fixed", options.fixed, "Objects to treat as fixed (comma-separated; over the model and inference)")
      ->delimiter(',');
  command.add_option("--contact-tolerance", options.contactTolerance,
                     "Penetration (m) up to which a robot base or a held object rests on a fixed object "
                     "instead of colliding with it (0 to 0.01; default 0.0005)");
}

}  // namespace lang2manip
