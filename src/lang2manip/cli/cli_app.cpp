#include "lang2manip/cli/cli_app.hpp"

#include <CLI/CLI.hpp>

#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/cli/scene_report.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/model/builtin_data.hpp"

namespace lang2manip {
namespace {

struct ShowOptions {
  std::string problem;
  std::string robot = "panda";
  bool json = false;
};

void runProblems(bool asJson, std::ostream& out) {
  const std::vector<BuiltinProblem> problems = builtinProblems();
  if (asJson) {
    nlohmann::json list = nlohmann::json::array();
    for (const BuiltinProblem& problem : problems) {
      list.push_back({{"name", problem.shortName}, {"title", problem.description},
                      {"file", problem.file.string()}, {"default", problem.shortName == defaultProblemName()}});
    }
    out << list.dump(2) << '\n';
    return;
  }
  for (const BuiltinProblem& problem : problems) {
    out << problem.shortName << (problem.shortName == defaultProblemName() ? " (default)" : "")
        << "\t" << problem.description << "\t" << problem.file.string() << '\n';
  }
}

void runShow(const ShowOptions& options, std::ostream& out) {
  const nlohmann::json report = problemReport(loadProblem(options.problem, options.robot));
  out << (options.json ? report.dump(2) + "\n" : problemReportText(report));
}

}  // namespace

int runCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  setLogSink([&err](LogLevel level, std::string_view message) {
    err << "lang2manip " << logLevelName(level) << ": " << message << '\n';
  });
  CLI::App app{"lang2manip: natural-language instructions to collision-free robot trajectories"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "lang2manip 0.1.0");

  bool problemsJson = false;
  CLI::App* problems = app.add_subcommand("problems", "List the built-in problems");
  problems->add_flag("--json", problemsJson, "Print JSON");

  ShowOptions show;
  CLI::App* showCommand = app.add_subcommand(
      "show", "Print a problem's robots, controls, objects and queries");
  showCommand->add_option("PROBLEM", show.problem,
                          "Built-in problem name, Kautham problem .xml, or MoveIt scene .yaml "
                          "(default: " + defaultProblemName() + ")");
  showCommand->add_option("--robot", show.robot, "Built-in robot for MoveIt scenes")
      ->capture_default_str();
  showCommand->add_flag("--json", show.json, "Print JSON");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error, out, err);
  }
  try {
    if (problems->parsed()) runProblems(problemsJson, out);
    if (showCommand->parsed()) runShow(show, out);
  } catch (const std::exception& error) {
    err << "lang2manip: error: " << error.what() << '\n';
    return 1;
  }
  return 0;
}

}  // namespace lang2manip
