#include "lang2manip/core/error.hpp"
#include "lang2manip/planning/planning_space.hpp"

namespace lang2manip {
namespace {

MarginKind marginKindOf(JointType type) {
  switch (type) {
    case JointType::kRevolute:
      return MarginKind::kAngular;
    case JointType::kPrismatic:
      return MarginKind::kLinear;
    default:
      return MarginKind::kNone;
  }
}

}  // namespace

JointPlanningSpace::JointPlanningSpace(std::shared_ptr<const CollisionChecker> checker,
                                       const std::vector<std::string>& robots,
                                       const std::vector<std::vector<std::string>>& variables,
                                       const JointLimitDefaults& defaults)
    : PlanningSpace(std::move(checker)) {
  if (robots.empty()) throw InputError("joint planning space: no robot given");
  if (!variables.empty() && variables.size() != robots.size()) {
    throw InputError("joint planning space: " + std::to_string(variables.size()) +
                     " joint lists for " + std::to_string(robots.size()) + " robots");
  }
  sceneWorld_ = this->checker().sceneState();
  std::vector<double> lower;
  std::vector<double> upper;
  std::vector<double> velocity;
  std::vector<double> acceleration;
  std::vector<double> jerk;
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const int robot = this->checker().robotIndex(robots[r]);
    robots_.push_back(robot);
    const SceneRobot& sceneRobot = this->checker().scene().robots()[static_cast<std::size_t>(robot)];
    const RobotModel& model = *sceneRobot.model;
    std::vector<std::string> names =
        variables.empty() || variables[r].empty() ? model.variableNames() : variables[r];
    for (const std::string& name : names) {
      const int variable = model.variableIndex(name);
      if (!(model.lowerLimits()[variable] < model.upperLimits()[variable])) {
        throw InputError("joint planning space: joint \"" + name + "\" of robot \"" + robots[r] +
                         "\" has an empty range; it cannot be planned");
      }
      planned_.push_back({robot, variable});
      marginKinds_.push_back(marginKindOf(model.joints()[static_cast<std::size_t>(model.variableJoints()[variable])].type));
      dofNames_.push_back(robots[r] + "/" + name);
      lower.push_back(model.lowerLimits()[variable]);
      upper.push_back(model.upperLimits()[variable]);
      velocity.push_back(defaults.velocityLimit(model, variable));
      acceleration.push_back(defaults.accelerationLimit(model, variable));
      jerk.push_back(model.jerkLimit(variable).value_or(0.0));
    }
  }
  const auto n = static_cast<Eigen::Index>(planned_.size());
  lower_ = Eigen::Map<VectorX>(lower.data(), n);
  upper_ = Eigen::Map<VectorX>(upper.data(), n);
  trajectoryJointNames_ = dofNames_;
  jacobian_ = MatrixX::Identity(n, n);
  velocityLimits_ = Eigen::Map<VectorX>(velocity.data(), n);
  accelerationLimits_ = Eigen::Map<VectorX>(acceleration.data(), n);
  jerkLimits_ = Eigen::Map<VectorX>(jerk.data(), n);
}

VectorX JointPlanningSpace::trajectoryPositions(const VectorX& x) const { return x; }

void JointPlanningSpace::fillWorld(const double* x, WorldState& world) const {
  for (std::size_t i = 0; i < planned_.size(); ++i) {
    world.configurations[static_cast<std::size_t>(planned_[i].robot)][planned_[i].variable] = x[i];
  }
}

WorldState JointPlanningSpace::worldState(const VectorX& x) const {
  WorldState world = sceneWorld_;
  fillWorld(x.data(), world);
  return world;
}

VectorX JointPlanningSpace::pointFromConfigurations(const std::vector<VectorX>& configurations) const {
  if (configurations.size() != robots_.size()) {
    throw InputError("expected " + std::to_string(robots_.size()) + " configurations, got " +
                     std::to_string(configurations.size()));
  }
  VectorX x(dimension());
  for (std::size_t i = 0; i < planned_.size(); ++i) {
    std::size_t slot = 0;
    while (robots_[slot] != planned_[i].robot) ++slot;
    const VectorX& q = configurations[slot];
    const auto& robot = checker().scene().robots()[static_cast<std::size_t>(planned_[i].robot)];
    robot.model->checkConfiguration(q, "configuration of robot \"" + robot.name + "\"");
    x[static_cast<Eigen::Index>(i)] = q[planned_[i].variable];
  }
  return x;
}

bool JointPlanningSpace::isValidIn(const double* x, SpaceWorkspace& workspace) const {
  fillWorld(x, workspace.world);
  if (robots_.size() == 1) {
    return checker().isStateValid(robots_[0],
                                  workspace.world.configurations[static_cast<std::size_t>(robots_[0])],
                                  *workspace.collision);
  }
  return checker().checkWorld(workspace.world, CollisionRequest{}, *workspace.collision).valid;
}

std::optional<bool> JointPlanningSpace::fastMotionCheck(const double* x0, const double* x1,
                                                        double resolution,
                                                        SpaceWorkspace& workspace) const {
  if (robots_.size() != 1) return std::nullopt;
  const auto robot = static_cast<std::size_t>(robots_[0]);
  fillWorld(x0, workspace.world);
  workspace.configuration = workspace.world.configurations[robot];
  fillWorld(x1, workspace.world);
  return checker().isMotionValid(robots_[0], workspace.configuration,
                                 workspace.world.configurations[robot], resolution,
                                 *workspace.collision);
}

}  // namespace lang2manip
