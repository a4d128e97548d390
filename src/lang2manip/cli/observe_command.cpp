#include "lang2manip/cli/commands.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/symbolic/observation.hpp"

namespace lang2manip {
namespace {

struct ObserveOptions {
  std::string problem;
  std::string robot;  ///< empty: the Panda for MoveIt scenes
  SceneOptions scene;
  std::string arm;
  bool json = false;
};

}  // namespace

void addObserveCommand(CLI::App& app, std::ostream& out) {
  auto options = std::make_shared<ObserveOptions>();
  CLI::App* command = app.add_subcommand(
      "observe", "Print the environment state as task planners see it (robots, objects, relations)");
  command->add_option("PROBLEM", options->problem,
                      "Built-in problem name, Kautham problem .xml, or MoveIt scene .yaml (default: " +
                          defaultProblemName() + ")");
  command->add_option("--robot", options->robot, "Robot of a MoveIt scene: a built-in name or a .urdf/.xacro file (default: panda)");
  addSceneOptions(*command, options->scene);
  command->add_option("--arm", options->arm, "The arm that will act: regions are of the part of a top it reaches (default: every arm)");
  command->add_flag("--json", options->json, "Print the observation as JSON");
  command->callback([options, &out] {
    const LoadedProblem loaded = loadProblem(options->problem, options->robot, options->scene);
    ObservationOptions observing;
    observing.arm = options->arm;
    const nlohmann::json observation = observeEnvironment(loaded.problem.scene, observing);
    out << (options->json ? observation.dump(2) + "\n" : observationText(observation));
  });
}

}  // namespace lang2manip
