// The Kautham control map is affine before clamping (kautham-format.md):
// p_d = offset_d + sum_c eig_c * k_dc * (x_c - 0.5), value_d = low_d + clamp(p_d) * (high_d - low_d).
#include <algorithm>
#include <numbers>

#include "lang2manip/model/kautham_dof_target.hpp"
#include "lang2manip/planning/planning_space.hpp"

namespace lang2manip {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

struct DofRange {
  std::string name;
  double low = 0.0;
  double high = 1.0;
  double velocity = 1.0;
  double acceleration = 1.0;
};

DofRange jointRange(const RobotModel& model, int variable, const JointLimitDefaults& defaults) {
  const int joint = model.variableJoints()[static_cast<std::size_t>(variable)];
  const Joint& description = model.joints()[static_cast<std::size_t>(joint)];
  const bool continuous = description.type == JointType::kContinuous;
  DofRange range;
  range.name = description.name;
  range.low = continuous ? -kTwoPi : model.lowerLimits()[variable];
  range.high = continuous ? kTwoPi : model.upperLimits()[variable];
  range.velocity = defaults.velocityLimit(model, variable);
  range.acceleration = defaults.accelerationLimit(model, variable);
  return range;
}

DofRange baseRange(const KauthamEntity& entity, DofKind kind, const JointLimitDefaults& defaults) {
  static const char* const kNames[] = {"", "base_x", "base_y", "base_z", "base_x1", "base_x2", "base_x3"};
  DofRange range;
  range.name = kNames[static_cast<int>(kind)];
  range.velocity = defaults.baseVelocity;
  range.acceleration = defaults.baseAcceleration;
  const auto& limits = kind == DofKind::kX   ? entity.limits.x
                       : kind == DofKind::kY ? entity.limits.y
                                             : entity.limits.z;
  if (kind <= DofKind::kZ && limits) {
    range.low = limits->first;
    range.high = limits->second;
  }
  return range;
}

}  // namespace

KauthamControlSpace::KauthamControlSpace(std::shared_ptr<const CollisionChecker> checker,
                                         const KauthamProblem& problem,
                                         const JointLimitDefaults& defaults)
    : PlanningSpace(std::move(checker)), problem_(problem) {
  dofNames_ = problem.robotControls.controlNames();
  const auto n = static_cast<Eigen::Index>(dofNames_.size());
  if (n == 0) throw InputError(problem.file.string() + ": the problem has no robot controls to plan");
  lower_ = VectorX::Zero(n);
  upper_ = VectorX::Ones(n);
  buildTrajectoryMap(defaults);
}

void KauthamControlSpace::buildTrajectoryMap(const JointLimitDefaults& defaults) {
  const ControlSet& controls = problem_.robotControls;
  const std::vector<DofTarget> targets = resolveDofTargets(problem_, controls, true);
  const auto dofs = static_cast<Eigen::Index>(targets.size());
  jacobian_ = MatrixX::Zero(dofs, dimension());
  trajectoryOffset_ = VectorX::Zero(dofs);
  velocityLimits_ = VectorX::Zero(dofs);
  accelerationLimits_ = VectorX::Zero(dofs);
  jerkLimits_ = VectorX::Zero(dofs);
  trajectoryLow_ = VectorX::Zero(dofs);
  stepScale_ = VectorX::Ones(dofs);
  trajectoryHigh_ = VectorX::Zero(dofs);
  for (Eigen::Index d = 0; d < dofs; ++d) {
    const DofTarget& target = targets[static_cast<std::size_t>(d)];
    const auto entity = static_cast<std::size_t>(target.entity);
    const DofRange range =
        target.kind == DofKind::kJoint
            ? jointRange(*problem_.scene.robots()[entity].model, target.variable, defaults)
            : baseRange(problem_.robots[entity], target.kind, defaults);
    trajectoryJointNames_.push_back(problem_.robots[entity].name + "/" + range.name);
    velocityLimits_[d] = range.velocity;
    accelerationLimits_[d] = range.acceleration;
    if (target.kind == DofKind::kX || target.kind == DofKind::kY || target.kind == DofKind::kZ) {
      stepScale_[d] = std::max(1.0, (range.high - range.low) / 5.0);
      velocityLimits_[d] *= stepScale_[d];
      accelerationLimits_[d] *= stepScale_[d];
    }
    trajectoryLow_[d] = range.low;
    trajectoryHigh_[d] = range.high;
    const double span = range.high - range.low;
    double p0 = controls.dofs[static_cast<std::size_t>(d)].offset;
    for (Eigen::Index c = 0; c < dimension(); ++c) {
      const Control& control = controls.controls[static_cast<std::size_t>(c)];
      for (const auto& [dof, coefficient] : control.coefficients) {
        if (dof != d) continue;
        jacobian_(d, c) += span * control.eigValue * coefficient;
        p0 -= control.eigValue * coefficient * 0.5;
      }
    }
    trajectoryOffset_[d] = range.low + span * p0;
  }
}

VectorX KauthamControlSpace::trajectoryPositions(const VectorX& x) const {
  // Clamping p to [0,1] is clamping the value to the DOF's [low, high].
  return (trajectoryOffset_ + jacobian_ * x).cwiseMax(trajectoryLow_).cwiseMin(trajectoryHigh_);
}

WorldState KauthamControlSpace::worldState(const VectorX& x) const {
  const RobotStates states = robotStatesFromControls(
      problem_, std::vector<double>(x.data(), x.data() + x.size()), "planning state");
  WorldState world;
  world.configurations = states.configurations;
  world.basePoses = states.basePoses;
  return world;
}

bool KauthamControlSpace::isValidIn(const double* x, SpaceWorkspace& workspace) const {
  const RobotStates states = robotStatesFromControls(
      problem_, std::vector<double>(x, x + dimension()), "planning state");
  workspace.world.configurations = states.configurations;
  workspace.world.basePoses = states.basePoses;
  if (workspace.world.configurations.size() == 1 &&
      workspace.world.basePoses[0].isApprox(checker().scene().robots()[0].basePose, 1e-12)) {
    return checker().isStateValid(0, workspace.world.configurations[0], *workspace.collision);
  }
  return checker().checkWorld(workspace.world, CollisionRequest{}, *workspace.collision).valid;
}

}  // namespace lang2manip
