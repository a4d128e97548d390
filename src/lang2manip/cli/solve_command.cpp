#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <ompl/util/RandomNumbers.h>

#include "lang2manip/cli/collision_queries.hpp"
#include "lang2manip/cli/commands.hpp"
#include "lang2manip/cli/parameter_assignment.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/cli/run_page.hpp"
#include "lang2manip/cli/solve_scene.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/output_files.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/planning/motion_plan_json.hpp"
#include "lang2manip/planning/planning_session.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

struct SolveOptions {
  std::string problem;
  std::string robot;  ///< empty: the Panda for MoveIt scenes
  SceneOptions scene;
  std::string planner;
  std::vector<std::string> parameters;
  double timeLimit = 0.0;
  int query = 0;
  long seed = 1;
  double resolution = MotionPlanningOptions{}.resolution;
  bool json = false;
  std::string out;
  std::string html;
  bool recordTree = false;
};

void configurePlanner(PlanningSession& session, const SolveOptions& options) {
  if (!options.planner.empty()) session.setPlanner(options.planner);
  for (const std::string& parameter : options.parameters) {
    const auto [name, value] = parseParameterAssignment(parameter);
    session.setPlannerParameter(name, value);
  }
  if (options.timeLimit > 0.0) session.setPlannerParameter("_Max Planning Time", std::to_string(options.timeLimit));
}

json queryJson(std::size_t index, const PlanningSession& session, const MotionPlan& plan) {
  return {{"query", index + 1},
          {"status", motionPlanStatusName(plan.status)},
          {"message", plan.message},
          {"planner", session.plannerSettings().planner()},
          {"statistics", motionPlanStatisticsToJson(plan.statistics)},
          {"path_dof_names", session.pathDofNames()},
          {"path", pathToJson(plan.path)},
          {"trajectory", trajectoryToJson(plan.trajectory)}, {"trajectory_joint_robots", trajectoryJointRobots(plan.trajectory)},
          {"duration", plan.trajectory.duration()}};
}


/// Why query `q` cannot be planned (a start or goal outside the joint limits or in collision),
/// or empty after making it the session's query.
std::string queryRejection(const LoadedProblem& loaded, PlanningSession& session, std::size_t q) {
  const Scene& scene = session.problem().scene;
  // With several robots, each violation names its robot.
  const std::string ofRobot = scene.robots().size() == 1 ? " of \"" + scene.robots()[0].name + "\"" : "";
  const auto& [start, goal] = loaded.queries[q];
  for (const auto& [states, what] : {std::pair{&start, "start"}, std::pair{&goal, "goal"}}) {
    const std::vector<std::string> violations = limitViolations(scene, *states);
    if (!violations.empty()) {
      return std::string(what) + " is outside the joint limits" + ofRobot + ": " + violations.front() +
             (violations.size() > 1 ? " (and " + std::to_string(violations.size() - 1) + " more)" : "");
    }
  }
  try {
    const KauthamQuery& query = session.problem().queries[q];
    session.setQuery(query.init, query.goal);
  } catch (const InputError& error) {
    return error.what();
  }
  return {};
}

json rejectedQueryJson(std::size_t index, const PlanningSession& session, const std::string& reason) {
  return {{"query", index + 1},
          {"status", "invalid_query"},
          {"message", reason},
          {"planner", session.plannerSettings().planner()},
          {"statistics", motionPlanStatisticsToJson(MotionPlanStatistics{})},
          {"path_dof_names", session.pathDofNames()},
          {"path", json::array()},
          {"trajectory", json()},
          {"duration", 0.0}};
}

/// The CSV files of an earlier solve written beside `file` (FILE.csv, FILE_query<N>.csv).
std::vector<std::filesystem::path> earlierTrajectoryFiles(const std::filesystem::path& file) {
  namespace fs = std::filesystem;
  std::vector<fs::path> found;
  const fs::path directory = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  const std::string stem = file.stem().string();
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory, error)) {
    const std::string name = entry.path().filename().string();
    const bool single = name == stem + ".csv";
    const std::size_t digits = stem.size() + 6;  // after "<stem>_query"
    const bool perQuery = name.rfind(stem + "_query", 0) == 0 && entry.path().extension() == ".csv" &&
                          name.size() > digits + 4 && name.find_first_not_of("0123456789", digits) == name.size() - 4;
    if ((single || perQuery) && entry.is_regular_file(error)) found.push_back(entry.path());
  }
  return found;
}

/// Writes the report and the trajectory of each solved query as CSV, each file whole (never
/// through a link); CSV files of an earlier solve beside it are removed, so the files beside the
/// report are all of this solve. The files written.
std::vector<std::string> writeOutputs(const std::string& out, const json& report, const std::vector<JointTrajectory>& trajectories) {
  const std::filesystem::path file(out);
  writeFileAtomically(file, report.dump(2) + "\n", "solve: --out");
  std::vector<std::string> written{file.string()};
  std::vector<std::filesystem::path> stale = earlierTrajectoryFiles(file);
  for (std::size_t q = 0; q < trajectories.size(); ++q) {
    if (trajectories[q].points.empty()) continue;
    std::filesystem::path csv = file;
    csv.replace_extension(trajectories.size() == 1 ? ".csv" : "_query" + std::to_string(q + 1) + ".csv");
    writeFileAtomically(csv, trajectoryToCsv(trajectories[q]), "solve: --out");
    written.push_back(csv.string());
    std::erase(stale, csv);
  }
  std::error_code error;
  for (const std::filesystem::path& path : stale) std::filesystem::remove(path, error);
  return written;
}

/// solve --html: the page of the solved queries.
void writeSolvePage(const std::string& file, const std::string& name, const KauthamProblem& problem, const json& report,
                    const std::vector<SolvedQuery>& queries, const std::string& viewer) {
  writeFileAtomically(file, runPageHtml(solveViewerDocument(name, report, queries), solveSceneGlb(problem, queries), viewer),
                      "solve: --html");
}

void runSolve(const SolveOptions& options, std::ostream& out) {
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(options.seed));
  LoadedProblem loaded = loadProblem(options.problem, options.robot, options.scene);
  // Before the long work: a missing viewer is an error now, not after solving.
  const std::string viewer = options.html.empty() ? "" : viewerScript();
  MotionPlanningOptions planningOptions;
  planningOptions.resolution = options.resolution;
  if (options.recordTree) planningOptions.recordTreeEdges = kRecordedTreeEdges;
  const KauthamProblem problem = loaded.problem;
  PlanningSession session(planningOptions);
  session.openProblem(std::move(loaded.problem));
  configurePlanner(session, options);
  const std::vector<KauthamQuery> queries = session.problem().queries;
  if (queries.empty()) throw InputError(loaded.file + ": the problem has no query to solve");
  if (options.query < 0 || options.query > static_cast<int>(queries.size())) {
    throw InputError("--query " + std::to_string(options.query) + ": the problem has " +
                     std::to_string(queries.size()) + " queries (1.." + std::to_string(queries.size()) + ")");
  }
  json report{{"problem", loaded.name}, {"file", loaded.file}, {"queries", json::array()}};
  std::vector<JointTrajectory> trajectories;
  std::vector<SolvedQuery> solved_;
  for (std::size_t q = 0; q < queries.size(); ++q) {
    if (options.query != 0 && static_cast<int>(q) + 1 != options.query) continue;
    const std::string rejection = queryRejection(loaded, session, q);
    if (!rejection.empty()) {
      report["queries"].push_back(rejectedQueryJson(q, session, rejection));
      trajectories.emplace_back();
      solved_.push_back({q, "invalid_query", {}, {}});
      continue;
    }
    const MotionPlan& plan = session.solve();
    report["queries"].push_back(queryJson(q, session, plan));
    trajectories.push_back(plan.trajectory);
    solved_.push_back({q, motionPlanStatusName(plan.status), plan.trajectory, plan.tree});
  }
  bool solved = true;
  for (const json& query : report["queries"]) solved = solved && query["status"] == "solved";
  report["solved"] = solved;
  report["ignored_parameters"] = json::array();
  for (const IgnoredParameter& ignored : session.plannerSettings().ignoredParameters()) {
    report["ignored_parameters"].push_back({{"name", ignored.name}, {"value", ignored.value}, {"reason", ignored.reason}});
  }
  report["valid_state_sampler"] = validStateSamplerName(session.plannerSettings().validStateSampler());
  std::vector<std::string> written;
  if (!options.out.empty()) written = writeOutputs(options.out, report, trajectories);
  if (!options.html.empty()) {
    writeSolvePage(options.html, loaded.name, problem, report, solved_, viewer);
    written.push_back(options.html);
  }
  if (options.json) {
    out << report.dump(2) << '\n';
  } else {
    out << "problem " << loaded.name << " (" << loaded.file << ")\n";
    if (session.plannerSettings().validStateSampler() != ValidStateSampler::kUniform) {
      out << "valid state sampler: " << report["valid_state_sampler"].get<std::string>() << "\n";
    }
    for (const json& ignored : report["ignored_parameters"]) {
      out << "parameter \"" << ignored["name"].get<std::string>() << "\" = " << ignored["value"].get<std::string>()
          << " has no effect: " << ignored["reason"].get<std::string>() << "\n";
    }
    for (const json& query : report["queries"]) out << solveQueryText(query);
    std::string list;
    for (const std::string& file : written) list += (list.empty() ? "" : ", ") + file;
    if (!written.empty()) out << "wrote " << list << "\n";
  }
  if (!solved) throw TaskFailedError("solve: not every query was solved");
}

}  // namespace

void addSolveCommand(CLI::App& app, std::ostream& out) {
  auto options = std::make_shared<SolveOptions>();
  CLI::App* command = app.add_subcommand(
      "solve", "Solve a problem's motion queries with its planner (or --planner) and write the trajectories");
  command->add_option("PROBLEM", options->problem,
                      "Built-in problem name, Kautham problem .xml, or MoveIt scene .yaml (default: " +
                          defaultProblemName() + ")");
  command->add_option("--robot", options->robot, "Robot of a MoveIt scene: a built-in name or a .urdf/.xacro file (default: panda)");
  addSceneOptions(*command, options->scene);
  command->add_option("--planner", options->planner, "Planner name (OMPL or Kautham name)");
  command->add_option("--param", options->parameters, "Planner parameter NAME=VALUE (repeatable)");
  command->add_option("--time-limit", options->timeLimit, "Planning time limit per query, seconds")
      ->check(CLI::PositiveNumber);
  command->add_option("--query", options->query, "Solve only query N (1-based; default: all)");
  command->add_option("--seed", options->seed, "Random seed")->capture_default_str();
  command->add_option("--resolution", options->resolution,
                      "Largest joint step (rad or m) between collision checks of a motion while "
                      "planning; the result is re-verified at a finer resolution")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_flag("--json", options->json, "Print JSON");
  command->add_option("--html", options->html, "Also write FILE: the scene and the solved motions in one page that opens offline");
  command->add_flag("--record-tree", options->recordTree,
                    "Keep the planner's exploration graph (the --html page draws it green at the first robot's tool)");
  command->add_option("--out", options->out,
                      "Write the result as JSON to FILE and each trajectory as CSV beside it");
  command->callback([options, &out] { runSolve(*options, out); });
}

}  // namespace lang2manip
