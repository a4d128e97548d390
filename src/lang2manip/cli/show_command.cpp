#include "lang2manip/cli/commands.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/cli/scene_report.hpp"
#include "lang2manip/model/builtin_data.hpp"

namespace lang2manip {
namespace {

struct ShowOptions {
  std::string problem;
  std::string robot;  ///< empty: the Panda for MoveIt scenes
  SceneOptions scene;
  bool json = false;
};

}  // namespace

void addShowCommand(CLI::App& app, std::ostream& out) {
  auto options = std::make_shared<ShowOptions>();
  CLI::App* command =
      app.add_subcommand("show", "Print a problem's robots, controls, objects and queries");
  command->add_option("PROBLEM", options->problem,
                      "Built-in problem name, Kautham problem .xml, or MoveIt scene .yaml (default: " +
                          defaultProblemName() + ")");
  command->add_option("--robot", options->robot, "Robot of a MoveIt scene: a built-in name or a .urdf/.xacro file (default: panda)");
  addSceneOptions(*command, options->scene);
  command->add_flag("--json", options->json, "Print JSON");
  command->callback([options, &out] {
    const nlohmann::json report = problemReport(loadProblem(options->problem, options->robot, options->scene));
    out << (options->json ? report.dump(2) + "\n" : problemReportText(report));
  });
}

}  // namespace lang2manip
