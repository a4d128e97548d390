#include "lang2manip/planning/planning_space.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {

double JointLimitDefaults::velocityLimit(const RobotModel& model, int variable) const {
  const double limit = model.velocityLimits()[variable];
  return limit > 0.0 ? limit : kDefaultJointVelocityLimit;
}

double JointLimitDefaults::accelerationLimit(const RobotModel& model, int variable) const {
  return model.accelerationLimit(variable).value_or(accelerationPerVelocity * velocityLimit(model, variable));
}

PlanningSpace::PlanningSpace(std::shared_ptr<const CollisionChecker> checker)
    : checker_(std::move(checker)) {
  if (!checker_) throw InputError("planning space: no collision checker given");
}

StateBounds PlanningSpace::plannedBounds(const PositionMargin& margin,
                                        const std::vector<VectorX>& restingPoints) const {
  StateBounds bounds{lower_, upper_};
  for (std::size_t i = 0; i < marginKinds_.size(); ++i) {
    const auto c = static_cast<Eigen::Index>(i);
    const double wanted = marginKinds_[i] == MarginKind::kAngular  ? margin.angular
                          : marginKinds_[i] == MarginKind::kLinear ? margin.linear
                                                                   : 0.0;
    const double inward =
        std::clamp(wanted, 0.0, PositionMargin::kMaxRangeFraction * (upper_[c] - lower_[c]));
    bounds.lower[c] += inward;
    bounds.upper[c] -= inward;
  }
  for (const VectorX& point : restingPoints) {
    if (point.size() != lower_.size()) continue;
    bounds.lower = bounds.lower.cwiseMin(point);
    bounds.upper = bounds.upper.cwiseMax(point);
  }
  return bounds;
}

void PlanningSpace::checkPoint(const VectorX& x, const std::string& what) const {
  if (x.size() != dimension()) {
    throw InputError(what + " has " + std::to_string(x.size()) + " values; the planning space has " +
                     std::to_string(dimension()) + " (" + [this] {
                       std::string names;
                       for (const auto& name : dofNames_) names += (names.empty() ? "" : ", ") + name;
                       return names;
                     }() + ")");
  }
  for (int i = 0; i < x.size(); ++i) {
    const std::string name = dofNames_[static_cast<std::size_t>(i)];
    if (!std::isfinite(x[i])) throw InputError(what + ": " + name + " is not a finite number");
    if (x[i] < lower_[i] - 1e-9 || x[i] > upper_[i] + 1e-9) {
      throw InputError(what + ": " + name + " = " + numberText(x[i]) + " is outside its limits [" +
                       numberText(lower_[i]) + ", " + numberText(upper_[i]) + "]");
    }
  }
}

SpaceWorkspace& PlanningSpace::workspace() const {
  const std::lock_guard lock(workspacesMutex_);
  auto& slot = workspaces_[std::this_thread::get_id()];
  if (!slot) {
    slot = std::make_unique<SpaceWorkspace>();
    slot->collision = checker_->makeContext();
    slot->world = checker_->sceneState();
  }
  return *slot;
}

bool PlanningSpace::isValid(const double* x) const { return isValidIn(x, workspace()); }

std::optional<bool> PlanningSpace::fastMotionCheck(const double*, const double*, double,
                                                   SpaceWorkspace&) const {
  return std::nullopt;
}

bool PlanningSpace::isMotionValid(const double* x0, const double* x1, double resolution) const {
  SpaceWorkspace& scratch = workspace();
  if (auto fast = fastMotionCheck(x0, x1, resolution, scratch)) return *fast;
  const int n = dimension();
  const Eigen::Map<const VectorX> from(x0, n);
  const Eigen::Map<const VectorX> to(x1, n);
  const int steps = motionSteps(x0, x1, resolution);
  VectorX point(n);
  for (int step = 0; step <= steps; ++step) {
    point = from + (to - from) * (static_cast<double>(step) / steps);
    if (!isValidIn(point.data(), scratch)) return false;
  }
  return true;
}

int PlanningSpace::motionSteps(const double* x0, const double* x1, double resolution) const {
  const int n = dimension();
  const Eigen::Map<const VectorX> from(x0, n);
  const Eigen::Map<const VectorX> to(x1, n);
  const VectorX jointSteps = (jacobian_ * (to - from)).cwiseAbs();
  double largest = 0.0;
  for (Eigen::Index j = 0; j < jointSteps.size(); ++j) {
    const double scale = stepScale_.size() == jointSteps.size() ? stepScale_[j] : 1.0;
    largest = std::max(largest, jointSteps[j] / scale);
  }
  return std::max(1, static_cast<int>(std::ceil(largest / resolution)));
}

std::optional<VectorX> PlanningSpace::firstInvalidState(const VectorX& x0, const VectorX& x1,
                                                        double resolution) const {
  const int steps = motionSteps(x0.data(), x1.data(), resolution);
  for (int step = 0; step <= steps; ++step) {
    VectorX point = x0 + (x1 - x0) * (static_cast<double>(step) / steps);
    if (!isValid(point.data())) return point;
  }
  return std::nullopt;
}

CollisionReport PlanningSpace::report(const VectorX& x) const {
  auto context = checker_->makeContext();
  return checker_->checkWorld(worldState(x), CollisionRequest{}, *context);
}

}  // namespace lang2manip
