// `lang2manip gltf`: a problem's scene as a glTF binary file for any glTF viewer.

#include <fstream>
#include <memory>
#include <string>

#include "lang2manip/cli/commands.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/output_files.hpp"
#include "lang2manip/model/gltf_writer.hpp"

namespace lang2manip {
namespace {

struct GltfCommandOptions {
  std::string problem;
  std::string robot;  ///< empty: the Panda for MoveIt scenes
  std::string out;
  bool collision = false;
  bool goal = false;
  SceneOptions scene;
};

/// The scene with the robots at the first query's start (or goal), else as loaded.
Scene posedScene(const LoadedProblem& loaded, bool goal) {
  Scene scene = loaded.problem.scene;
  if (loaded.queries.empty()) return scene;
  const RobotStates& states = goal ? loaded.queries.front().second : loaded.queries.front().first;
  for (std::size_t r = 0; r < scene.robots().size() && r < states.configurations.size(); ++r) {
    scene.setConfiguration(scene.robots()[r].name, states.configurations[r]);
    scene.robot(scene.robots()[r].name).basePose = states.basePoses[r];
  }
  return scene;
}

void writeGltf(const GltfCommandOptions& options, std::ostream& out) {
  const LoadedProblem loaded = loadProblem(options.problem, options.robot, options.scene);
  GltfOptions gltf;
  gltf.geometry = options.collision ? GltfGeometry::kCollision : GltfGeometry::kVisual;
  GltfSummary summary;
  const std::string glb = sceneToGlb(posedScene(loaded, options.goal), gltf, &summary);
  writeFileAtomically(options.out, glb, "gltf: --out");
  out << "wrote " << options.out << ": " << summary.nodes << " shapes, " << summary.meshes << " meshes, " << summary.triangles
      << " triangles, " << glb.size() << " bytes\n";
}

}  // namespace

void addGltfCommand(CLI::App& app, std::ostream& out) {
  auto options = std::make_shared<GltfCommandOptions>();
  CLI::App* command = app.add_subcommand("gltf", "Write a problem's scene as a glTF binary (.glb) for any glTF viewer");
  command->add_option("PROBLEM", options->problem, "Built-in problem name, Kautham problem file, MoveIt scene or robot description");
  command->add_option("--robot", options->robot, "Robot of a MoveIt scene: a built-in name or a .urdf/.xacro file (default: panda)");
  command->add_option("-o,--out", options->out, "The .glb file to write")->required();
  command->add_flag("--collision", options->collision, "Draw the collision geometry instead of the visual one");
  command->add_flag("--goal", options->goal, "Robots at the first query's goal (default: its start)");
  addSceneOptions(*command, options->scene);
  command->callback([options, &out] { writeGltf(*options, out); });
}

}  // namespace lang2manip
