#pragma once
/// @file Solving a motion query with an OMPL planner chosen by name: plan under a stop
/// condition, simplify, time-parameterize, and re-verify the result with the exact checker at
/// a fine resolution, planning again only the segments that fail it. A trajectory that fails
/// verification is never returned as solved.

#include <memory>
#include <string>
#include <vector>

#include <ompl/base/PlannerStatus.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/geometric/PathGeometric.h>

#include "lang2manip/core/stop_condition.hpp"
#include "lang2manip/planning/planner_settings.hpp"
#include "lang2manip/planning/planning_space.hpp"
#include "lang2manip/planning/trajectory.hpp"

namespace lang2manip {

struct MotionPlanningOptions {
  /// Largest joint step (rad or m) between checked states of a motion while planning (about
  /// what MoveIt uses for a 7-DOF arm); paths are re-verified at verificationResolution.
  double resolution = 0.05;
  /// Largest joint step when the final path is re-verified.
  double verificationResolution = 0.002;
  TimeParameterizationOptions timing;
  /// How far intermediate states keep from the joints' position limits (see PositionMargin);
  /// PositionMargin{0, 0} plans up to the limits.
  PositionMargin positionMargin;
  /// Keep the planner's exploration graph (OMPL's PlannerData) in MotionPlan::tree, at most this
  /// many edges (0: not kept).
  std::size_t recordTreeEdges = 0;
};

/// A planner's exploration graph: vertices in the planning space and edges between them.
struct ExplorationTree {
  std::vector<VectorX> vertices;
  std::vector<std::pair<int, int>> edges;
  /// Edges left out beyond MotionPlanningOptions::recordTreeEdges.
  std::size_t omittedEdges = 0;
};

enum class MotionPlanStatus {
  kSolved,
  /// No exact solution within the time limit (an approximate one is not accepted).
  kNoPath,
  /// The stop condition fired (cancelled, or the caller's deadline) before a solution.
  kStopped,
  /// Solutions were found but each failed re-verification (collision or limits) and no other
  /// was found in the time left; none is returned.
  kVerificationFailed,
};

/// "solved", "no_path", "stopped", "verification_failed".
std::string motionPlanStatusName(MotionPlanStatus status);

struct MotionPlanStatistics {
  double planningSeconds = 0.0;
  double simplifySeconds = 0.0;
  double parameterizationSeconds = 0.0;
  double verificationSeconds = 0.0;
  /// -1 when the planner does not report iterations.
  long iterations = -1;
  long vertices = 0;
  long edges = 0;
  long stateChecks = 0;
  long motionChecks = 0;
  /// Path length in planning-space units before and after simplification (after: of the path
  /// returned, repaired segments included, which may make it longer than before).
  double lengthBeforeSimplification = 0.0;
  double lengthAfterSimplification = 0.0;
  /// Solutions rejected by verification (each followed by planning again in the time left).
  int rejectedPaths = 0;
  /// Segments that collided at the verification resolution and were planned again at it.
  int repairedSegments = 0;
  double repairSeconds = 0.0;
};

struct MotionPlan {
  MotionPlanStatus status = MotionPlanStatus::kNoPath;
  /// Why it is not solved, in words ("no path found in 10 s by RRTConnect").
  std::string message;
  /// The planner's path and the simplified path (planning-space points).
  std::vector<VectorX> rawPath;
  std::vector<VectorX> path;
  JointTrajectory trajectory;
  MotionPlanStatistics statistics;
  /// The exploration graph of the last attempt, when recorded (MotionPlanningOptions).
  ExplorationTree tree;

  [[nodiscard]] bool solved() const noexcept { return status == MotionPlanStatus::kSolved; }
};

/// Plans in one space. Not thread-safe (one solve at a time); planners may use threads inside.
class MotionPlanner {
 public:
  explicit MotionPlanner(std::shared_ptr<const PlanningSpace> space,
                         const MotionPlanningOptions& options = {});
  ~MotionPlanner();
  MotionPlanner(const MotionPlanner&) = delete;
  MotionPlanner& operator=(const MotionPlanner&) = delete;

  [[nodiscard]] const PlanningSpace& space() const noexcept { return *space_; }

  /// Plans from `start` to any of `goals` with `settings`, stopping at its time limit or when
  /// `stop` fires. Throws InputError when there is no goal, a point has the wrong size, is outside
  /// the limits, or is in collision (naming the colliding pair). No path is a result, not an error.
  /// A planner that accepts a single goal state only (pSBL) plans to the first of `goals`.
  MotionPlan solve(const VectorX& start, const std::vector<VectorX>& goals,
                   const PlannerSettings& settings, const StopCondition& stop);

  /// Empty when `path` is collision-free at the verification resolution; otherwise names the
  /// segment and the colliding pair.
  [[nodiscard]] std::string verifyPath(const std::vector<VectorX>& path) const;

 private:
  struct Ompl;
  void checkEndpoint(const VectorX& x, const std::string& what) const;
  [[nodiscard]] ompl::base::ProblemDefinitionPtr makeProblem(const VectorX& start,
                                                             const std::vector<VectorX>& goals,
                                                             const PlannerSettings& settings) const;
  void preparePlanner(const PlannerSettings& settings);
  ompl::base::PlannerStatus runPlanner(const ompl::base::ProblemDefinitionPtr& problem,
                                       const PlannerSettings& settings, const StopCondition& limit,
                                       MotionPlan& plan);
  void appendExactGoal(ompl::geometric::PathGeometric& path, const std::vector<VectorX>& goals) const;
  [[nodiscard]] bool mendPath(const StopCondition& stop, MotionPlan& plan) const;
  [[nodiscard]] std::string finishPath(ompl::geometric::PathGeometric path, const VectorX& start,
                                       const std::vector<VectorX>& goals, const PlannerSettings& settings, const StopCondition& stop,
                                       MotionPlan& plan) const;

  std::shared_ptr<const PlanningSpace> space_;
  MotionPlanningOptions options_;
  /// The box of the current query (PlanningSpace::plannedBounds).
  StateBounds bounds_;
  std::unique_ptr<Ompl> ompl_;
};

/// Routes OMPL's console messages to the lang2manip log sink (done once per process; the planning
/// module calls it itself, so library users need not).
void routeOmplMessagesToLog();

}  // namespace lang2manip
