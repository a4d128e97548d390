#include <nlohmann/json.hpp>

#include "lang2manip/cli/commands.hpp"
#include "lang2manip/model/builtin_data.hpp"

namespace lang2manip {
namespace {

void printProblems(bool asJson, std::ostream& out) {
  const std::vector<BuiltinProblem> problems = builtinProblems();
  if (asJson) {
    nlohmann::json list = nlohmann::json::array();
    for (const BuiltinProblem& problem : problems) {
      list.push_back({{"name", problem.shortName}, {"title", problem.description},
                      {"file", problem.file.string()},
                      {"default", problem.shortName == defaultProblemName()}});
    }
    out << list.dump(2) << '\n';
    return;
  }
  for (const BuiltinProblem& problem : problems) {
    out << problem.shortName << (problem.shortName == defaultProblemName() ? " (default)" : "")
        << "\t" << problem.description << "\t" << problem.file.string() << '\n';
  }
}

}  // namespace

void addProblemsCommand(CLI::App& app, std::ostream& out) {
  CLI::App* command = app.add_subcommand("problems", "List the built-in problems");
  auto asJson = std::make_shared<bool>(false);
  command->add_flag("--json", *asJson, "Print JSON");
  command->callback([asJson, &out] { printProblems(*asJson, out); });
}

}  // namespace lang2manip
