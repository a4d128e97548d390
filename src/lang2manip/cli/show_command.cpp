#include "lang2manip/cli/commands.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/cli/scene_report.hpp"
#include "lang2manip/model/builtin_data.hpp"

namespace lang2manip {
namespace {

struct ShowOptions {
  std::string problem;
  std::string robot = "panda";
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
  command->add_option("--robot", options->robot, "Built-in robot for MoveIt scenes")
      ->capture_default_str();
  addSceneOptions(*command, options->scene);
  command->add_flag("--json", options->json, "Print JSON");
  command->callback([options, &out] {
    const nlohmann::json report = problemReport(loadProblem(options->problem, options->robot, options->scene));
    out << (options->json ? report.dump(2) + "\n" : problemReportText(report));
  });
}

}  // namespace lang2manip
