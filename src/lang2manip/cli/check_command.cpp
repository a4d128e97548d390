#include <memory>
#include <string>
#include <vector>

#include "lang2manip/cli/collision_queries.hpp"
#include "lang2manip/cli/commands.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/model/builtin_data.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

struct CheckOptions {
  std::string problem;
  std::string robot;  ///< empty: the Panda for MoveIt scenes
  SceneOptions scene;
  bool robotGiven = false;
  std::vector<double> config;
  bool json = false;
};

/// A checked state: valid when collision-free and within every joint's limits.
json checkEntry(const std::string& what, const CollisionReport& report,
                const std::vector<std::string>& limitViolations) {
  json entry = collisionReportJson(report);
  entry["state"] = what;
  entry["collision_free"] = report.valid;
  entry["limit_violations"] = limitViolations;
  entry["valid"] = report.valid && limitViolations.empty();
  return entry;
}

/// The given configuration of one robot (the others at the problem's scene state).
json checkConfiguration(const CheckOptions& options, const CollisionChecker& checker) {
  const int robot = options.robotGiven && !isMoveItSceneName(options.problem) ? checker.robotIndex(options.robot) : 0;
  const VectorX q = Eigen::Map<const VectorX>(options.config.data(), static_cast<Eigen::Index>(options.config.size()));
  const RobotModel& model = *checker.scene().robots()[static_cast<std::size_t>(robot)].model;
  model.checkConfiguration(q, "--config");
  const auto context = checker.makeContext();
  const CollisionReport report = checker.checkState(robot, q, CollisionRequest{true}, *context);
  json entry = checkEntry("configuration", report, model.limitViolations(q));
  entry["robot"] = checker.scene().robots()[static_cast<std::size_t>(robot)].name;
  entry["configuration"] = options.config;
  return json::array({entry});
}

json checkProblemQueries(const LoadedProblem& loaded, const CollisionChecker& checker) {
  json checks = json::array();
  const std::vector<QueryCollisions> results = checkQueries(loaded, checker);
  for (std::size_t i = 0; i < results.size(); ++i) {
    const std::string query = "query " + std::to_string(i + 1);
    const auto& [start, goal] = loaded.queries[i];
    checks.push_back(checkEntry(query + " start", results[i].start, limitViolations(checker.scene(), start)));
    checks.push_back(checkEntry(query + " goal", results[i].goal, limitViolations(checker.scene(), goal)));
  }
  return checks;
}

std::string checkText(const json& report) {
  std::string text = "problem " + report["problem"].get<std::string>() + ": " +
                     (report["valid"].get<bool>()
                          ? "all states valid (collision-free, within the joint limits)"
                          : "INVALID STATES") + "\n";
  for (const json& check : report["checks"]) {
    text += check["state"].get<std::string>() +
            (check.contains("robot") ? " of " + check["robot"].get<std::string>() : "") + ": " +
            (check["valid"].get<bool>() ? "valid" : "INVALID") + "\n";
    for (const json& contact : check["contacts"]) {
      char depth[64];
      std::snprintf(depth, sizeof depth, "%.4f", contact["penetration_depth"].get<double>());
      text += "  " + contact["first"].get<std::string>() + " - " + contact["second"].get<std::string>() +
              ": penetration " + depth + " m\n";
    }
    for (const json& violation : check["limit_violations"]) {
      text += "  outside the joint limits: " + violation.get<std::string>() + "\n";
    }
    if (check["collision_free"].get<bool>() && check.contains("closest")) {
      char distance[64];
      std::snprintf(distance, sizeof distance, "%.4f", check["minimum_distance"].get<double>());
      text += "  clearance " + std::string(distance) + " m (" + check["closest"][0].get<std::string>() +
              " - " + check["closest"][1].get<std::string>() + ")\n";
    }
  }
  return text;
}

void runCheck(const CheckOptions& options, std::ostream& out) {
  if (options.robotGiven && options.config.empty() && !isMoveItSceneName(options.problem)) {
    throw InputError("check: --robot " + options.robot + " names the robot whose --config is given; without --config every query of the problem is checked");
  }
  const LoadedProblem loaded = loadProblem(options.problem, isMoveItSceneName(options.problem) ? options.robot : "", options.scene);
  if (options.config.empty() && loaded.queries.empty()) {
    throw InputError("nothing was checked: problem " + loaded.name +
                     " has no query; give a configuration with --config");
  }
  const FclCollisionChecker checker(loaded.problem.scene);
  json report{{"problem", loaded.name}, {"file", loaded.file}, {"checker", "fcl"}};
  report["checks"] = options.config.empty() ? checkProblemQueries(loaded, checker)
                                            : checkConfiguration(options, checker);
  std::size_t invalid = 0;
  for (const json& check : report["checks"]) invalid += check["valid"].get<bool>() ? 0 : 1;
  report["valid"] = invalid == 0;
  out << (options.json ? report.dump(2) + "\n" : checkText(report));
  if (invalid > 0) {
    throw TaskFailedError("check: " + std::to_string(invalid) + " of " +
                          std::to_string(report["checks"].size()) + " checked states are invalid");
  }
}

}  // namespace

void addCheckCommand(CLI::App& app, std::ostream& out) {
  auto options = std::make_shared<CheckOptions>();
  CLI::App* command = app.add_subcommand(
      "check", "Check whether states are collision-free (each query's start and goal, or --config)");
  command->add_option("PROBLEM", options->problem,
                      "Built-in problem name, Kautham problem .xml, or MoveIt scene .yaml (default: " +
                          defaultProblemName() + ")");
  command->add_option("--robot", options->robot,
                      "Robot whose --config is given (default: the first); for a MoveIt scene, its robot: a built-in "
                      "name or a .urdf/.xacro file (default: panda)");
  addSceneOptions(*command, options->scene);
  command->add_option("--config", options->config, "Joint values of the robot (one per variable)");
  command->add_flag("--json", options->json, "Print JSON");
  command->callback([options, command, &out] {
    options->robotGiven = command->count("--robot") > 0;
    runCheck(*options, out);
  });
}

}  // namespace lang2manip
