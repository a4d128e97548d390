#include "lang2manip/cli/problem_loading.hpp"

#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/moveit_scene_reader.hpp"
#include "lang2manip/model/urdf_reader.hpp"

namespace lang2manip {
namespace {

LoadedProblem loadMoveIt(const std::filesystem::path& sceneFile, const std::string& robot) {
  const RobotModelPtr model = readUrdfFile(builtinRobotUrdf(robot));
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

LoadedProblem loadKautham(const std::filesystem::path& file) {
  LoadedProblem loaded;
  loaded.problem = readKauthamProblem(file);
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

}  // namespace

LoadedProblem loadProblem(const std::string& nameOrPath, const std::string& robot) {
  const std::filesystem::path file = resolveProblem(nameOrPath.empty() ? defaultProblemName() : nameOrPath);
  const std::string extension = file.extension().string();
  if (extension == ".yaml" || extension == ".yml") return loadMoveIt(file, robot);
  if (extension != ".xml") {
    throw InputError(SourceLocation{file.string(), 0},
                     "not a problem file: expected a Kautham problem (.xml) or a MoveIt "
                     "planning scene (.yaml)");
  }
  return loadKautham(file);
}

}  // namespace lang2manip
