// Kautham's control -> configuration formula (kautham-format.md):
// p_d = clamp(sum_j eig_j * k_dj * (c_j - 0.5) + offset_d), q = lower + p * (upper - lower).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "lang2manip/core/rotation.hpp"
#include "lang2manip/model/kautham_dof_target.hpp"

namespace lang2manip {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

DofKind baseDofKind(const std::string& name) {
  if (name == "X") return DofKind::kX;
  if (name == "Y") return DofKind::kY;
  if (name == "Z") return DofKind::kZ;
  if (name == "X1") return DofKind::kX1;
  if (name == "X2") return DofKind::kX2;
  if (name == "X3") return DofKind::kX3;
  return DofKind::kJoint;
}

const std::optional<std::pair<double, double>>& axisLimits(const BaseLimits& limits, DofKind kind) {
  if (kind == DofKind::kX) return limits.x;
  if (kind == DofKind::kY) return limits.y;
  return limits.z;
}

std::string validDofNames(const RobotModel* model) {
  std::string names = "X, Y, Z, X1, X2, X3";
  if (model == nullptr) return names;
  for (const int joint : model->variableJoints()) {
    names += ", " + model->joints()[static_cast<std::size_t>(joint)].childLink;
  }
  return names;
}

int jointVariableForChildLink(const RobotModel& model, const std::string& link) {
  for (const int joint : model.variableJoints()) {
    if (model.joints()[static_cast<std::size_t>(joint)].childLink == link) {
      return model.variableOfJoint(joint);
    }
  }
  return -1;
}

// Translation of a base from its X/Y/Z DOF values (nullopt where uncontrolled).
struct BaseDofs {
  std::array<std::optional<double>, 6> values;  // X Y Z X1 X2 X3
};

double axisValue(const BaseLimits& limits, DofKind kind, const std::optional<double>& p) {
  const auto& range = axisLimits(limits, kind);
  if (!range) return 0.0;
  return range->first + p.value_or(0.5) * (range->second - range->first);
}

// X_WB = Home * T(x, y, z) * R(X1, X2, X3). Like Kautham (whose base is only "SE3-enabled"
// when its control file names one of its X..X3 DOFs), an entity none of whose base DOFs the
// control set names stays at Home, whatever its <Limits>.
Pose basePose(const Pose& home, const BaseLimits& limits, const BaseDofs& dofs) {
  const bool controlled = std::any_of(dofs.values.begin(), dofs.values.end(),
                                      [](const auto& value) { return value.has_value(); });
  if (!controlled) return home;
  const Vector3 translation(axisValue(limits, DofKind::kX, dofs.values[0]),
                            axisValue(limits, DofKind::kY, dofs.values[1]),
                            axisValue(limits, DofKind::kZ, dofs.values[2]));
  // Unnamed rotation DOFs keep Kautham's default offset 0.5 (a half turn about (0,-1,1)/sqrt(2)),
  // which is why Kautham's files give X1..X3 offsets explicitly.
  const Quaternion rotation = quaternionFromKauthamUnitCube(
      dofs.values[3].value_or(0.5), dofs.values[4].value_or(0.5), dofs.values[5].value_or(0.5));
  return home * makePose(translation, rotation);
}

std::size_t baseSlot(DofKind kind) { return static_cast<std::size_t>(kind) - 1; }

}  // namespace

std::pair<double, double> kauthamJointRange(const RobotModel& model, int variable) {
  const int joint = model.variableJoints()[static_cast<std::size_t>(variable)];
  if (model.joints()[static_cast<std::size_t>(joint)].type == JointType::kContinuous) {
    return {-kTwoPi, kTwoPi};
  }
  return {model.lowerLimits()[variable], model.upperLimits()[variable]};
}

std::vector<DofTarget> resolveDofTargets(const KauthamProblem& problem, const ControlSet& controls,
                                         bool robots) {
  std::vector<DofTarget> targets;
  const auto& entities = robots ? problem.robots : problem.obstacles;
  for (const ControlledDof& dof : controls.dofs) {
    const SourceLocation where{controls.source, dof.line};
    int entity = -1;
    for (std::size_t i = 0; i < entities.size(); ++i) {
      if (entities[i].name == dof.entity) entity = static_cast<int>(i);
    }
    if (entity < 0) {
      std::string names;
      for (const KauthamEntity& e : entities) names += (names.empty() ? "" : ", ") + e.name;
      throw InputError(where, "DOF \"" + dof.fullName() + "\": the problem has no " +
                                  (robots ? "robot" : "obstacle") + " named \"" + dof.entity +
                                  "\" (" + (robots ? "robots" : "obstacles") + ": " +
                                  (names.empty() ? "none" : names) + ")");
    }
    DofTarget target{entity, baseDofKind(dof.dof), -1};
    const RobotModel* model =
        robots ? problem.scene.robots()[static_cast<std::size_t>(entity)].model.get() : nullptr;
    const KauthamEntity& owner = entities[static_cast<std::size_t>(entity)];
    if (target.kind == DofKind::kJoint) {
      target.variable = model ? jointVariableForChildLink(*model, dof.dof) : -1;
      if (target.variable < 0) {
        throw InputError(where, "unknown DOF \"" + dof.fullName() + "\"; valid DOFs of \"" +
                                    dof.entity + "\": " + validDofNames(model) +
                                    " (a joint DOF is named after the joint's child link)");
      }
    } else if (target.kind <= DofKind::kZ && !axisLimits(owner.limits, target.kind)) {
      throw InputError(where, "DOF \"" + dof.fullName() + "\" moves the base along " + dof.dof +
                                  ", but \"" + dof.entity + "\" has no <Limits name=\"" + dof.dof +
                                  "\">");
    }
    targets.push_back(target);
  }
  return targets;
}

ControlSet defaultRobotControls(const KauthamProblem& problem) {
  ControlSet set;
  auto add = [&set](const std::string& entity, const std::string& dof) {
    set.dofs.push_back(ControlledDof{entity, dof, 0.5, 0});
    set.controls.push_back(Control{entity + "/" + dof, 1.0,
                                   {{static_cast<int>(set.dofs.size()) - 1, 1.0}}, 0});
  };
  for (std::size_t r = 0; r < problem.robots.size(); ++r) {
    const KauthamEntity& robot = problem.robots[r];
    bool movesBase = false;
    for (const auto& [name, range] : {std::pair{"X", robot.limits.x}, std::pair{"Y", robot.limits.y},
                                      std::pair{"Z", robot.limits.z}}) {
      if (range && range->first != range->second) {
        add(robot.name, name);
        movesBase = true;
      }
    }
    // A moving base keeps its Home orientation (offsets 0 instead of Kautham's 0.5 half turn).
    for (const char* rotation : {"X1", "X2", "X3"}) {
      if (movesBase) set.dofs.push_back(ControlledDof{robot.name, rotation, 0.0, 0});
    }
    const RobotModel& model = *problem.scene.robots()[r].model;
    for (const int joint : model.variableJoints()) {
      const Joint& description = model.joints()[static_cast<std::size_t>(joint)];
      if (description.limits.lower < description.limits.upper) add(robot.name, description.childLink);
    }
  }
  return set;
}

namespace {

/// Robot states from one value per DOF of the robot controls: `jointValue(d, target)` for a
/// joint, `baseFraction(d)` (the DOF's [0, 1] value) for a base axis.
template <typename JointValue, typename BaseFraction>
RobotStates robotStatesFromDofs(const KauthamProblem& problem, JointValue jointValue, BaseFraction baseFraction) {
  const std::vector<DofTarget> targets = resolveDofTargets(problem, problem.robotControls, true);
  RobotStates states;
  std::vector<BaseDofs> bases(problem.robots.size());
  for (const SceneRobot& robot : problem.scene.robots()) {
    states.configurations.push_back(robot.model->middleConfiguration());
  }
  for (std::size_t d = 0; d < targets.size(); ++d) {
    const DofTarget& target = targets[d];
    const auto entity = static_cast<std::size_t>(target.entity);
    if (target.kind == DofKind::kJoint) {
      states.configurations[entity][target.variable] = jointValue(d, target);
    } else {
      bases[entity].values[baseSlot(target.kind)] = baseFraction(d, target);
    }
  }
  for (std::size_t r = 0; r < problem.robots.size(); ++r) {
    states.basePoses.push_back(basePose(problem.robots[r].home, problem.robots[r].limits, bases[r]));
  }
  return states;
}

}  // namespace

RobotStates robotStatesFromControls(const KauthamProblem& problem,
                                    const std::vector<double>& controls, const std::string& what) {
  const std::vector<double> p = problem.robotControls.dofValues(controls, what);
  return robotStatesFromDofs(
      problem,
      [&](std::size_t d, const DofTarget& target) {
        const auto [lower, upper] = kauthamJointRange(*problem.scene.robots()[static_cast<std::size_t>(target.entity)].model, target.variable);
        return lower + p[d] * (upper - lower);
      },
      [&](std::size_t d, const DofTarget&) { return p[d]; });
}

RobotStates robotStatesFromDofPositions(const KauthamProblem& problem, const std::vector<double>& positions,
                                        const std::string& what) {
  if (positions.size() != problem.robotControls.dofs.size()) {
    throw InputError(what + ": " + std::to_string(positions.size()) + " values for the " +
                     std::to_string(problem.robotControls.dofs.size()) + " DOFs of the robot controls");
  }
  for (std::size_t d = 0; d < positions.size(); ++d) {
    if (!std::isfinite(positions[d])) throw InputError(what + ": value " + std::to_string(d + 1) + " is not a finite number");
  }
  return robotStatesFromDofs(
      problem, [&](std::size_t d, const DofTarget&) { return positions[d]; },
      [&](std::size_t d, const DofTarget& target) {
        if (target.kind > DofKind::kZ) return positions[d];
        const auto& range = axisLimits(problem.robots[static_cast<std::size_t>(target.entity)].limits, target.kind);
        if (!range || range->second <= range->first) return positions[d];
        return (positions[d] - range->first) / (range->second - range->first);
      });
}

std::vector<Pose> obstaclePosesFromControls(const KauthamProblem& problem,
                                            const std::vector<double>& controls,
                                            const std::string& what) {
  std::vector<BaseDofs> bases(problem.obstacles.size());
  if (!problem.obstacleControls.dofs.empty() || !controls.empty()) {
    const std::vector<double> p = problem.obstacleControls.dofValues(controls, what);
    const std::vector<DofTarget> targets = resolveDofTargets(problem, problem.obstacleControls, false);
    for (std::size_t d = 0; d < targets.size(); ++d) {
      bases[static_cast<std::size_t>(targets[d].entity)].values[baseSlot(targets[d].kind)] = p[d];
    }
  }
  std::vector<Pose> poses;
  for (std::size_t o = 0; o < problem.obstacles.size(); ++o) {
    poses.push_back(basePose(problem.obstacles[o].home, problem.obstacles[o].limits, bases[o]));
  }
  return poses;
}

}  // namespace lang2manip
