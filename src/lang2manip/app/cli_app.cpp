#include "lang2manip/app/cli_app.hpp"

#include <optional>
#include <string>
#include <vector>

#include "lang2manip/cli/commands.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/server/serve_command.hpp"

namespace lang2manip {
namespace {

/// The error for a first word that names no command (CLI11 would only say one is required).
std::optional<std::string> unknownCommand(const CLI::App& app, int argc, const char* const* argv) {
  if (argc < 2 || argv[1][0] == '-') return std::nullopt;
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (command->get_name() == argv[1]) return std::nullopt;
    names.push_back(command->get_name());
  }
  return "unknown command \"" + std::string(argv[1]) + "\" (commands: " + joinedNames(names) + ")";
}

}  // namespace

int runCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  setLogSink([&err](LogLevel level, std::string_view message) {
    err << "lang2manip " << logLevelName(level) << ": " << message << '\n';
  });
  CLI::App app{"lang2manip: natural-language instructions to collision-free robot trajectories"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "lang2manip 0.1.0");
  addProblemsCommand(app, out);
  addProblemCommand(app, out);
  addShowCommand(app, out);
  addCheckCommand(app, out);
  addSolveCommand(app, out);
  addObserveCommand(app, out);
  addPlanCommand(app, out);
  addRunCommand(app, out);
  addBenchCommand(app, out);
  addBenchApiCommand(*app.get_subcommand("bench"), out);
  addBenchAttacksCommand(*app.get_subcommand("bench"), out);
  addXacroCommand(app, out);
  addDescribeCommand(app, out);
  addGltfCommand(app, out);
  addRenderCommand(app, out);
  addServeCommand(app, out);
  if (const auto unknown = unknownCommand(app, argc, argv)) {
    err << "lang2manip: error: " << *unknown << "\nRun with --help for more information.\n";
    return 1;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // CLI11 prints help and usage errors; its own codes (105 and up) are not ours: a command line
    // that cannot be used is bad input like any other (exit 1), help and --version are success.
    return app.exit(error, out, err) == 0 ? 0 : 1;
  } catch (const TaskFailedError& error) {
    err << "lang2manip: " << error.what() << '\n';
    return 2;
  } catch (const std::exception& error) {
    err << "lang2manip: error: " << error.what() << '\n';
    return 1;
  }
  return 0;
}

}  // namespace lang2manip
