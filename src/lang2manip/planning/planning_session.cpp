#include "lang2manip/planning/planning_session.hpp"

#include <cmath>

#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/rotation.hpp"
#include "lang2manip/model/object_model.hpp"
#include "lang2manip/model/urdf_reader.hpp"

namespace lang2manip {

PlanningSession::PlanningSession(const MotionPlanningOptions& options,
                                 const FclCheckerSettings& checkerSettings)
    : options_(options), checkerSettings_(checkerSettings) {}
PlanningSession::~PlanningSession() = default;

void PlanningSession::openProblem(const std::filesystem::path& file) {
  openProblem(readKauthamProblem(file));
}

void PlanningSession::openProblem(KauthamProblem problem) {
  PlannerSettings settings;
  if (!problem.planner.name.empty()) {
    settings.setPlanner(problem.planner.name);
    for (const auto& [name, value] : problem.planner.parameters) {
      try {
        settings.setParameter(name, value);
      } catch (const InputError& error) {
        throw InputError(problem.file.string() + ": <Planner>: " + error.what());
      }
    }
  }
  auto opened = std::make_unique<KauthamProblem>(std::move(problem));
  closeProblem();
  problem_ = std::move(opened);
  settings_ = settings;
  if (!problem_->queries.empty()) {
    init_ = Eigen::Map<const VectorX>(problem_->queries[0].init.data(),
                                      static_cast<Eigen::Index>(problem_->queries[0].init.size()));
    goal_ = Eigen::Map<const VectorX>(problem_->queries[0].goal.data(),
                                      static_cast<Eigen::Index>(problem_->queries[0].goal.size()));
  }
}

void PlanningSession::closeProblem() {
  planner_.reset();
  space_.reset();
  checker_.reset();
  problem_.reset();
  init_.reset();
  goal_.reset();
  lastPlan_.reset();
  lastSolveFailure_.clear();
}

KauthamProblem& PlanningSession::openedProblem() const {
  if (!problem_) throw InputError("no problem is open: call openProblem first");
  return *problem_;
}

const KauthamProblem& PlanningSession::problem() const { return openedProblem(); }

void PlanningSession::setPlanner(const std::string& name) {
  settings_.setPlanner(name);
  lastPlan_.reset();
}

void PlanningSession::setPlannerParameter(const std::string& name, const std::string& value) {
  settings_.setParameter(name, value);
}

void PlanningSession::worldChanged() {
  std::vector<std::shared_ptr<const AllowedCollisionMatrix>> matrices;
  if (const auto* fcl = dynamic_cast<const FclCollisionChecker*>(checker_.get())) {
    for (std::size_t r = 0; r < openedProblem().scene.robots().size(); ++r) {
      matrices.push_back(fcl->sharedAllowedCollisions(static_cast<int>(r)));
    }
  }
  planner_.reset();
  space_.reset();
  checker_.reset();
  lastPlan_.reset();
  if (!matrices.empty()) {
    FclCheckerSettings settings = checkerSettings_;
    settings.precomputedMatrices = matrices;
    checker_ = std::make_shared<FclCollisionChecker>(openedProblem().scene, settings);
  }
}

std::shared_ptr<const PlanningSpace> PlanningSession::planningSpace() {
  if (!space_) {
    if (!checker_) checker_ = std::make_shared<FclCollisionChecker>(openedProblem().scene, checkerSettings_);
    space_ = std::make_shared<KauthamControlSpace>(checker_, openedProblem());
  }
  return space_;
}

VectorX PlanningSession::checkedPoint(const std::vector<double>& controls, const std::string& what) {
  const VectorX x = Eigen::Map<const VectorX>(controls.data(), static_cast<Eigen::Index>(controls.size()));
  const auto space = planningSpace();
  space->checkPoint(x, what);
  if (!space->isValid(x.data())) {
    const CollisionReport report = space->report(x);
    std::string pairs;
    for (const CollisionContact& contact : report.contacts) {
      pairs += (pairs.empty() ? "" : ", ") + contact.first + " touches " + contact.second;
    }
    throw InputError(what + " is in collision: " + pairs);
  }
  return x;
}

void PlanningSession::setQuery(const std::vector<double>& init, const std::vector<double>& goal) {
  const VectorX start = checkedPoint(init, "init");
  const VectorX end = checkedPoint(goal, "goal");
  init_ = start;
  goal_ = end;
}

void PlanningSession::setInit(const std::vector<double>& init) { init_ = checkedPoint(init, "init"); }
void PlanningSession::setGoal(const std::vector<double>& goal) { goal_ = checkedPoint(goal, "goal"); }

std::vector<std::string> PlanningSession::pathDofNames() const {
  return openedProblem().robotControls.controlNames();
}

const MotionPlan& PlanningSession::solve(const StopCondition& stop) {
  openedProblem();
  if (!init_ || !goal_) throw InputError("no query to solve: call setQuery (or setInit and setGoal) first");
  const auto space = planningSpace();
  if (!planner_) planner_ = std::make_unique<MotionPlanner>(space, options_);
  lastPlan_ = planner_->solve(*init_, {*goal_}, settings_, stop);
  return *lastPlan_;
}

const MotionPlan& PlanningSession::solveWithin(double maxPlanningSeconds, const StopCondition& stop) {
  const PlannerSettings kept = settings_;
  settings_.setParameter("_Max Planning Time", std::to_string(maxPlanningSeconds));
  try {
    solve(stop);
  } catch (...) {
    settings_ = kept;
    throw;
  }
  settings_ = kept;
  return *lastPlan_;
}

const MotionPlan& PlanningSession::getPath() const {
  if (!lastPlan_) throw InputError("no path: call solve first (the world or planner changed since)");
  if (!lastPlan_->solved()) throw InputError("no path: the last solve failed: " + lastPlan_->message);
  return *lastPlan_;
}

double PlanningSession::getLastPlanComputationTime() const {
  if (!lastPlan_) throw InputError("no plan computed yet: call solve first");
  return lastPlan_->statistics.planningSeconds;
}

long PlanningSession::getNumVertices() const {
  if (!lastPlan_) throw InputError("no plan computed yet: call solve first");
  return lastPlan_->statistics.vertices;
}

long PlanningSession::getNumEdges() const {
  if (!lastPlan_) throw InputError("no plan computed yet: call solve first");
  return lastPlan_->statistics.edges;
}

CollisionReport PlanningSession::checkCollision(const std::vector<double>& controls) {
  const VectorX x = Eigen::Map<const VectorX>(controls.data(), static_cast<Eigen::Index>(controls.size()));
  const auto space = planningSpace();
  space->checkPoint(x, "configuration");
  return space->report(x);
}

void PlanningSession::setRobotsConfig(const std::vector<double>& controls) {
  KauthamProblem& opened = openedProblem();
  const RobotStates states = robotStatesFromControls(opened, controls, "robot configuration");
  for (std::size_t r = 0; r < states.configurations.size(); ++r) {
    SceneRobot& robot = opened.scene.robot(opened.scene.robots()[r].name);
    robot.configuration = states.configurations[r];
    robot.basePose = states.basePoses[r];
  }
  worldChanged();
}

void PlanningSession::setObstaclesConfig(const std::vector<double>& controls) {
  KauthamProblem& opened = openedProblem();
  const std::vector<Pose> poses = obstaclePosesFromControls(opened, controls, "obstacle configuration");
  for (std::size_t o = 0; o < poses.size(); ++o) opened.scene.object(opened.obstacles[o].name).pose = poses[o];
  worldChanged();
}

void PlanningSession::setObstaclePos(const std::string& obstacle, const Pose& pose) {
  if (!pose.matrix().allFinite()) throw InputError("obstacle pose of \"" + obstacle + "\" is not finite");
  requirePositionInRange(pose.translation(), "obstacle position of \"" + obstacle + "\"", SourceLocation{});
  openedProblem().scene.object(obstacle).pose = pose;
  worldChanged();
}

Pose PlanningSession::getObstaclePos(const std::string& obstacle) const {
  return openedProblem().scene.object(obstacle).pose;
}

void PlanningSession::setRobotPos(const std::string& robot, const Pose& pose) {
  if (!pose.matrix().allFinite()) throw InputError("base pose of \"" + robot + "\" is not finite");
  requirePositionInRange(pose.translation(), "base position of \"" + robot + "\"", SourceLocation{});
  KauthamProblem& opened = openedProblem();
  opened.scene.robot(robot).basePose = pose;
  for (KauthamEntity& entity : opened.robots) {
    if (entity.name == robot) entity.home = pose;
  }
  worldChanged();
}

Pose PlanningSession::getRobotPos(const std::string& robot) const {
  return openedProblem().scene.robot(robot).basePose;
}

void PlanningSession::addObstacle(const std::filesystem::path& urdf, const std::string& name,
                                  const Pose& pose, double scale) {
  KauthamProblem& opened = openedProblem();
  if (opened.scene.findObject(name) != nullptr) throw InputError("an obstacle named \"" + name + "\" exists");
  if (!(scale > 0.0 && std::isfinite(scale))) throw InputError("obstacle scale must be positive");
  SceneObject object = objectFromModel(*readUrdfFile(urdf), name, urdf, scale);
  object.pose = pose;
  opened.scene.addObject(object);
  KauthamEntity entity;
  entity.name = name;
  entity.reference = urdf.string();
  entity.resolvedPath = urdf;
  entity.scale = scale;
  entity.home = pose;
  opened.obstacles.push_back(entity);
  worldChanged();
}

void PlanningSession::removeObstacle(const std::string& name) {
  KauthamProblem& opened = openedProblem();
  opened.scene.removeObject(name);
  std::erase_if(opened.obstacles, [&name](const KauthamEntity& entity) { return entity.name == name; });
  worldChanged();
}

Pose PlanningSession::currentLinkPose(const std::string& robot, const std::string& link) const {
  const SceneRobot& sceneRobot = openedProblem().scene.robot(robot);
  const int index = sceneRobot.model->linkIndex(link);
  return sceneRobot.basePose *
         sceneRobot.model->linkPoses(sceneRobot.configuration)[static_cast<std::size_t>(index)];
}

void PlanningSession::attachObstacle2RobotLink(const std::string& robot, const std::string& link,
                                               const std::string& obstacle) {
  KauthamProblem& opened = openedProblem();
  const Pose linkPose = currentLinkPose(robot, link);
  opened.scene.attach(Attachment{obstacle, robot, link,
                                 linkPose.inverse() * opened.scene.object(obstacle).pose});
  worldChanged();
}

void PlanningSession::detachObstacle(const std::string& obstacle) {
  KauthamProblem& opened = openedProblem();
  const Attachment* attachment = opened.scene.findAttachment(obstacle);
  if (attachment == nullptr) throw InputError("obstacle \"" + obstacle + "\" is not attached");
  const Pose world = currentLinkPose(attachment->robot, attachment->link) * attachment->linkToObject;
  opened.scene.detach(obstacle, world);
  worldChanged();
}

}  // namespace lang2manip
