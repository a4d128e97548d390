#pragma once
/// @file A planning session with Kautham's service verbs (kautham-format.md): open a problem,
/// choose a planner and its parameters, set queries in the problem's controls, solve, read the
/// path, and edit the world (obstacles, robot bases, attachments) between queries. Poses in this
/// API are quaternion poses; kauthamPose() converts Kautham's axis-angle form.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lang2manip/collision/collision_checker.hpp"
#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/core/rotation.hpp"
#include "lang2manip/core/stop_condition.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/planning/motion_planner.hpp"

namespace lang2manip {


class PlanningSession {
 public:
  /// `checkerSettings` configure the FCL checkers built for the problem's worlds.
  explicit PlanningSession(const MotionPlanningOptions& options = {},
                           const FclCheckerSettings& checkerSettings = {});
  ~PlanningSession();
  PlanningSession(const PlanningSession&) = delete;
  PlanningSession& operator=(const PlanningSession&) = delete;

  /// Opens a Kautham problem; its planner, parameters and first query become current.
  /// Throws InputError for a bad file (the previous problem stays open).
  void openProblem(const std::filesystem::path& file);
  /// Opens a problem already loaded (e.g. built from a MoveIt scene).
  void openProblem(KauthamProblem problem);
  void closeProblem();
  [[nodiscard]] bool isOpen() const noexcept { return problem_ != nullptr; }
  /// The open problem (the scene reflects every edit). Throws InputError when none is open.
  [[nodiscard]] const KauthamProblem& problem() const;

  /// Kautham's setPlanner / setPlannerByName (the same here: any registered name or alias).
  void setPlanner(const std::string& name);
  void setPlannerByName(const std::string& name) { setPlanner(name); }
  void setPlannerParameter(const std::string& name, const std::string& value);
  [[nodiscard]] const PlannerSettings& plannerSettings() const noexcept { return settings_; }

  /// Start and goal in the problem's robot controls. A point of the wrong size, outside [0,1] or
  /// in collision (the colliding pair is named) is rejected with InputError; the session then
  /// keeps its previous query.
  void setQuery(const std::vector<double>& init, const std::vector<double>& goal);
  void setInit(const std::vector<double>& init);
  void setGoal(const std::vector<double>& goal);
  /// The current start and goal (absent until set).
  [[nodiscard]] const std::optional<VectorX>& init() const noexcept { return init_; }
  [[nodiscard]] const std::optional<VectorX>& goal() const noexcept { return goal_; }
  /// Whether solve() stored a result that getPath() returns.
  [[nodiscard]] bool hasPath() const noexcept { return lastPlan_ && lastPlan_->solved(); }
  /// Names of the coordinates of queries and paths (the control names).
  [[nodiscard]] std::vector<std::string> pathDofNames() const;

  /// Solves the current query; the result is kept for getPath() and the statistics. No path is a
  /// result (solved() false, with the reason), not an error. Throws InputError without a query.
  const MotionPlan& solve(const StopCondition& stop = StopCondition::never());
  /// solve() with `maxPlanningSeconds` (> 0) for this call only, instead of the planner's
  /// "_Max Planning Time", which stays as it was (not a Kautham verb: a solve with a time limit).
  const MotionPlan& solveWithin(double maxPlanningSeconds, const StopCondition& stop = StopCondition::never());
  /// The stored solution of the last solve() (never re-solves). Throws InputError when there is
  /// none, saying why.
  [[nodiscard]] const MotionPlan& getPath() const;
  [[nodiscard]] double getLastPlanComputationTime() const;
  [[nodiscard]] long getNumVertices() const;
  [[nodiscard]] long getNumEdges() const;

  /// The space queries are planned in (the problem's controls), built on the current world.
  std::shared_ptr<const PlanningSpace> planningSpace();

  /// The collision report at robot control values `controls`.
  [[nodiscard]] CollisionReport checkCollision(const std::vector<double>& controls);
  /// Moves the robots to control values `controls` (the scene's configurations).
  void setRobotsConfig(const std::vector<double>& controls);
  /// Moves the obstacles to obstacle control values.
  void setObstaclesConfig(const std::vector<double>& controls);

  void setObstaclePos(const std::string& obstacle, const Pose& pose);
  [[nodiscard]] Pose getObstaclePos(const std::string& obstacle) const;
  void setRobotPos(const std::string& robot, const Pose& pose);
  [[nodiscard]] Pose getRobotPos(const std::string& robot) const;
  /// Adds obstacle `name` read from a URDF at `pose`; throws InputError for a bad file or a
  /// name in use.
  void addObstacle(const std::filesystem::path& urdf, const std::string& name, const Pose& pose,
                   double scale = 1.0);
  void removeObstacle(const std::string& name);
  /// Attaches `obstacle` to `link` of `robot` where it is now.
  void attachObstacle2RobotLink(const std::string& robot, const std::string& link,
                                const std::string& obstacle);
  void detachObstacle(const std::string& obstacle);

 private:
  KauthamProblem& openedProblem() const;
  void worldChanged();
  [[nodiscard]] VectorX checkedPoint(const std::vector<double>& controls, const std::string& what);
  [[nodiscard]] Pose currentLinkPose(const std::string& robot, const std::string& link) const;

  MotionPlanningOptions options_;
  FclCheckerSettings checkerSettings_;
  std::unique_ptr<KauthamProblem> problem_;
  PlannerSettings settings_;
  std::shared_ptr<const CollisionChecker> checker_;
  std::shared_ptr<const PlanningSpace> space_;
  std::unique_ptr<MotionPlanner> planner_;
  std::optional<VectorX> init_;
  std::optional<VectorX> goal_;
  std::optional<MotionPlan> lastPlan_;
  std::string lastSolveFailure_;
};

}  // namespace lang2manip
