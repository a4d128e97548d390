#include <cctype>
#include <memory>
#include <nlohmann/json.hpp>

#include "lang2manip/cli/commands.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/output_files.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"

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

struct ProblemWriteOptions {
  std::string problem;
  std::string robot;
  SceneOptions scene;
  std::string out;
  std::string name;
  bool force = false;
};

/// `name`, or the problem's name made fit for a file name.
std::string problemFileStem(const ProblemWriteOptions& options, const std::string& problemName) {
  if (!options.name.empty()) {
    if (options.name.front() == '.' || options.name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.-") != std::string::npos) {
      throw InputError("problem write: --name \"" + options.name + "\" must be letters, digits, '_', '-' and '.' (not first)");
    }
    return options.name;
  }
  std::string stem;
  for (const char c : problemName) stem += std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' ? c : '_';
  return stem.empty() ? "problem" : stem;
}

void writeProblem(const ProblemWriteOptions& options, std::ostream& out) {
  const LoadedProblem loaded = loadProblem(options.problem, options.robot, options.scene);
  const std::string stem = problemFileStem(options, loaded.name);
  OutputDirectory set(options.out, "problem write: --out", options.force);
  const std::filesystem::path file = writeKauthamProblem(loaded.problem, set.stagingDirectory(), stem);
  set.commit();
  out << "wrote " << (set.target() / file.filename()).string() << ": Kautham problem \"" << loaded.problem.name << "\" of "
      << loaded.name << " (" << loaded.problem.scene.robots().size() << " robot(s), " << loaded.problem.scene.objects().size()
      << " object(s), " << loaded.problem.queries.size() << " query(ies)), with its controls and models beside it\n";
}

}  // namespace

void addProblemCommand(CLI::App& app, std::ostream& out) {
  CLI::App* command = app.add_subcommand("problem", "Work with problem files");
  command->require_subcommand(1);
  auto options = std::make_shared<ProblemWriteOptions>();
  CLI::App* write = command->add_subcommand(
      "write", "Write a problem (built-in, Kautham .xml, MoveIt scene .yaml or robot description) as a Kautham problem: "
               "DIR/NAME.xml, its controls under DIR/controls/ and models built in code under DIR/models/");
  write->add_option("PROBLEM", options->problem, "The problem to write (default: " + defaultProblemName() + ")");
  write->add_option("--robot", options->robot, "Robot of a MoveIt scene: a built-in name or a .urdf/.xacro file (default: panda)");
  addSceneOptions(*write, options->scene);
  write->add_option("-o,--out", options->out, "The directory to write (replaced whole; a directory lang2manip did not write needs --force)")
      ->required();
  write->add_option("--name", options->name, "File name of the problem, without .xml (default: from the problem's name)");
  write->add_flag("--force", options->force, "Replace a directory lang2manip did not write (its contents are kept as DIR.previous)");
  write->callback([options, &out] { writeProblem(*options, out); });
}

void addProblemsCommand(CLI::App& app, std::ostream& out) {
  CLI::App* command = app.add_subcommand("problems", "List the built-in problems");
  auto asJson = std::make_shared<bool>(false);
  command->add_flag("--json", *asJson, "Print JSON");
  command->callback([asJson, &out] { printProblems(*asJson, out); });
}

}  // namespace lang2manip
