#include "lang2manip/cli/solve_scene.hpp"

#include <algorithm>
#include <cstdio>

#include "lang2manip/cli/run_scene.hpp"
#include "lang2manip/model/gltf_writer.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

void setRobotStates(const RobotStates& states, Scene& scene) {
  for (std::size_t r = 0; r < scene.robots().size(); ++r) {
    scene.robot(scene.robots()[r].name).basePose = states.basePoses[r];
    scene.setConfiguration(scene.robots()[r].name, states.configurations[r]);
  }
}

/// The scene with the robots where the planning state `controls` (a tree vertex) puts them.
void moveRobotsToControls(const KauthamProblem& problem, const VectorX& controls, Scene& scene) {
  std::vector<double> values(controls.data(), controls.data() + controls.size());
  for (double& value : values) value = std::clamp(value, 0.0, 1.0);
  setRobotStates(robotStatesFromControls(problem, values, "exploration tree"), scene);
}

/// The scene with the robots at a trajectory point's positions (joint values, base axes).
void moveRobotsToPositions(const KauthamProblem& problem, const VectorX& positions, Scene& scene) {
  setRobotStates(robotStatesFromDofPositions(problem, std::vector<double>(positions.data(), positions.data() + positions.size()),
                                             "trajectory"),
                 scene);
}

/// The first robot's tool frame (its first manipulator's) or last link: where paths are drawn.
Vector3 tipPosition(const Scene& scene) {
  const SceneRobot& robot = scene.robots().front();
  const std::vector<Manipulator>& manipulators = robot.model->semantics().manipulators;
  const int link = manipulators.empty() || manipulators.front().toolFrame.empty()
                       ? static_cast<int>(robot.model->links().size()) - 1
                       : robot.model->linkIndex(manipulators.front().toolFrame);
  return (robot.basePose * robot.model->linkPoses(robot.configuration)[static_cast<std::size_t>(link)]).translation();
}

std::vector<Pose> bodyPoses(const Scene& scene) {
  std::vector<Pose> poses;
  for (const SceneRobot& robot : scene.robots()) {
    for (const Pose& X_BL : robot.model->linkPoses(robot.configuration)) poses.push_back(robot.basePose * X_BL);
  }
  for (const SceneObject& object : scene.objects()) poses.push_back(scene.objectWorldPose(object.name));
  return poses;
}

void addTree(const KauthamProblem& problem, const SolvedQuery& query, GlbBuilder& builder) {
  if (query.tree.edges.empty()) return;
  Scene scene = problem.scene;
  std::vector<Vector3> points;
  for (const VectorX& vertex : query.tree.vertices) {
    moveRobotsToControls(problem, vertex, scene);
    points.push_back(tipPosition(scene));
  }
  addExplorationGraph(builder, "exploration_tree/" + std::to_string(query.index), points, query.tree.edges);
}

}  // namespace

std::string solveSceneGlb(const KauthamProblem& problem, const std::vector<SolvedQuery>& queries) {
  GlbBuilder builder(GltfGeometry::kBoth, 24);
  const std::vector<int> nodes = addSceneBodies(problem.scene, builder);
  Scene scene = problem.scene;
  std::vector<double> times;
  std::vector<std::vector<Pose>> frames;
  double start = 0.0;
  for (const SolvedQuery& query : queries) {
    std::vector<Vector3> path;
    for (const TrajectoryPoint& point : query.trajectory.points) {
      moveRobotsToPositions(problem, point.positions, scene);
      path.push_back(tipPosition(scene));
      const double time = start + point.time;
      if (!times.empty() && time <= times.back()) continue;
      times.push_back(time);
      frames.push_back(bodyPoses(scene));
    }
    builder.addPolyline("tool_paths", "tool_path/" + std::to_string(query.index), path, Vector4(0.9, 0.1, 0.1, 1.0));
    addTree(problem, query, builder);
    start += query.trajectory.duration();
  }
  if (times.size() >= 2) {
    std::vector<std::pair<int, std::vector<Pose>>> tracks;
    for (std::size_t b = 0; b < nodes.size(); ++b) {
      std::vector<Pose> poses;
      for (const std::vector<Pose>& frame : frames) poses.push_back(frame[b]);
      tracks.emplace_back(nodes[b], std::move(poses));
    }
    builder.addAnimation("trajectory", times, tracks);
  }
  return builder.finish();
}

json solveViewerDocument(const std::string& problem, const json& report, const std::vector<SolvedQuery>& queries) {
  json actions = json::array();
  json moments = json::array({{{"time", 0.0}, {"label", "start"}}});
  double time = 0.0;
  for (const SolvedQuery& query : queries) {
    const double end = time + query.trajectory.duration();
    const std::string text = "query " + std::to_string(query.index + 1);
    actions.push_back({{"index", query.index}, {"kind", "query"}, {"object", ""}, {"status", query.status}, {"start_time", time},
                       {"end_time", end}, {"text", text}});
    if (end > time) moments.push_back({{"time", end}, {"label", text + " reached"}});
    time = end;
  }
  return {{"format_version", 1}, {"task", "solve " + problem}, {"success", report.value("solved", false)}, {"duration", time},
          {"actions", actions}, {"moments", moments}, {"report", report}};
}

std::string solveQueryText(const nlohmann::json& query) {
  if (query["status"] == "invalid_query") {
    return "query " + std::to_string(query["query"].get<int>()) + ": not planned: " +
           query["message"].get<std::string>() + "\n";
  }
  const nlohmann::json& statistics = query["statistics"];
  char line[512];
  std::snprintf(line, sizeof line,
                "query %d: %s by %s in %.1f ms (%ld vertices, %ld edges, %ld state and %ld motion "
                "checks)\n",
                query["query"].get<int>(), query["status"].get<std::string>().c_str(),
                query["planner"].get<std::string>().c_str(), statistics["planning_seconds"].get<double>() * 1e3,
                statistics["vertices"].get<long>(), statistics["edges"].get<long>(),
                statistics["state_checks"].get<long>(), statistics["motion_checks"].get<long>());
  std::string text = line;
  if (query["status"] != "solved") return text + "  " + query["message"].get<std::string>() + "\n";
  const double before = statistics["length_before_simplification"].get<double>();
  const double after = statistics["length_after_simplification"].get<double>();
  const int repaired = statistics.value("repaired_segments", 0);
  // Simplification never lengthens a path; only segments planned again around an obstacle that
  // the planner's coarser checks missed do, and that is said.
  const std::string why = after > before + 1e-9 && repaired > 0
                              ? ", longer: " + std::to_string(repaired) + " segment(s) that touched an obstacle at the verification "
                                                                          "resolution planned again around it"
                              : "";
  std::snprintf(line, sizeof line,
                "  path: %zu points, length %.3f -> %.3f after simplification (%.1f ms%s); trajectory "
                "%.2f s, %zu points, verified\n",
                query["path"].size(), before, after, statistics["simplify_seconds"].get<double>() * 1e3, why.c_str(),
                query["duration"].get<double>(), query["trajectory"]["points"].size());
  return text + line;
}

}  // namespace lang2manip
