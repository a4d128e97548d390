#pragma once
/// @file `solve --html`: a Kautham problem's solved queries as the viewer shows them (the
/// scene with every query's trajectory animated one after another, the path of the first robot's
/// tool or last link in red, the exploration graphs in green when recorded).

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/planning/motion_planner.hpp"

namespace lang2manip {

/// One query of a solve: its trajectory (joint values and base axes, as the planning space's
/// trajectories hold them) and its exploration graph (vertices in the problem's robot controls).
struct SolvedQuery {
  std::size_t index = 0;
  /// "solved", "no_path", "invalid_query", ...
  std::string status;
  JointTrajectory trajectory;
  ExplorationTree tree;
};

/// The GLB: `problem`'s scene with both geometries and the queries' motion.
std::string solveSceneGlb(const KauthamProblem& problem, const std::vector<SolvedQuery>& queries);

/// What `solve` prints for one query of its report: how it was solved (planner, time, tree, checks)
/// and its path and trajectory, saying why a path got longer when segments were planned again; or
/// why it was not planned.
std::string solveQueryText(const nlohmann::json& query);

/// The viewer document: one "action" per query (start and end time, status), moments at the
/// start and after each query.
nlohmann::json solveViewerDocument(const std::string& problem, const nlohmann::json& report, const std::vector<SolvedQuery>& queries);

}  // namespace lang2manip
