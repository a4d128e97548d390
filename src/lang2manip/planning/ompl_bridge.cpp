#include "lang2manip/planning/ompl_bridge.hpp"

#include <algorithm>
#include <cmath>

#include <ompl/base/spaces/RealVectorStateSpace.h>

namespace lang2manip {
namespace {

namespace ob = ompl::base;

class SpaceValidityChecker final : public ob::StateValidityChecker {
 public:
  SpaceValidityChecker(const ob::SpaceInformationPtr& si, const PlanningSpace& space,
                       std::shared_ptr<CheckCounters> counters)
      : ob::StateValidityChecker(si), space_(space), counters_(std::move(counters)) {}

  bool isValid(const ob::State* state) const override {
    counters_->states.fetch_add(1, std::memory_order_relaxed);
    return space_.isValid(stateValues(state));
  }

 private:
  const PlanningSpace& space_;
  std::shared_ptr<CheckCounters> counters_;
};

class SpaceMotionValidator final : public ob::MotionValidator {
 public:
  SpaceMotionValidator(const ob::SpaceInformationPtr& si, const PlanningSpace& space,
                       double resolution, std::shared_ptr<CheckCounters> counters)
      : ob::MotionValidator(si), space_(space), resolution_(resolution),
        counters_(std::move(counters)) {}

  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    counters_->motions.fetch_add(1, std::memory_order_relaxed);
    const bool valid = space_.isMotionValid(stateValues(s1), stateValues(s2), resolution_);
    (valid ? valid_ : invalid_)++;
    return valid;
  }

  // The first invalid state's predecessor is reported as the last valid one.
  bool checkMotion(const ob::State* s1, const ob::State* s2,
                   std::pair<ob::State*, double>& lastValid) const override {
    counters_->motions.fetch_add(1, std::memory_order_relaxed);
    const int n = space_.dimension();
    const Eigen::Map<const VectorX> from(stateValues(s1), n);
    const Eigen::Map<const VectorX> to(stateValues(s2), n);
    const int steps = space_.motionSteps(stateValues(s1), stateValues(s2), resolution_);
    VectorX point(n);
    for (int step = 1; step <= steps; ++step) {
      point = from + (to - from) * (static_cast<double>(step) / steps);
      if (space_.isValid(point.data())) continue;
      lastValid.second = static_cast<double>(step - 1) / steps;
      if (lastValid.first != nullptr) si_->getStateSpace()->interpolate(s1, s2, lastValid.second, lastValid.first);
      invalid_++;
      return false;
    }
    valid_++;
    return true;
  }

 private:
  const PlanningSpace& space_;
  double resolution_;
  std::shared_ptr<CheckCounters> counters_;
};

// Projection onto the first (at most two) coordinates, as MoveIt projects arms onto their first
// joints; cells are a twentieth of each range. Replaces OMPL's identity projection, which aborts
// in Debian's OMPL 1.5.2 for spaces of two or fewer dimensions.
class LeadingCoordinatesProjection final : public ob::ProjectionEvaluator {
 public:
  LeadingCoordinatesProjection(const ob::StateSpacePtr& space, const PlanningSpace& planningSpace)
      : ob::ProjectionEvaluator(space),
        dimensions_(static_cast<unsigned int>(std::min(2, planningSpace.dimension()))) {
    std::vector<double> cells;
    for (unsigned int i = 0; i < dimensions_; ++i) {
      cells.push_back((planningSpace.upper()[i] - planningSpace.lower()[i]) / 20.0);
    }
    setCellSizes(cells);
  }

  unsigned int getDimension() const override { return dimensions_; }

  void project(const ob::State* state, Eigen::Ref<Eigen::VectorXd> projection) const override {
    const double* values = stateValues(state);
    for (unsigned int i = 0; i < dimensions_; ++i) projection[i] = values[i];
  }

 private:
  unsigned int dimensions_;
};

}  // namespace

const double* stateValues(const ob::State* state) {
  return state->as<ob::RealVectorStateSpace::StateType>()->values;
}

ob::SpaceInformationPtr makeSpaceInformation(const PlanningSpace& space, double resolution,
                                             const std::shared_ptr<CheckCounters>& counters) {
  const auto n = static_cast<unsigned int>(space.dimension());
  auto stateSpace = std::make_shared<ob::RealVectorStateSpace>(n);
  ob::RealVectorBounds bounds(n);
  for (unsigned int i = 0; i < n; ++i) {
    bounds.setLow(i, space.lower()[i]);
    bounds.setHigh(i, space.upper()[i]);
  }
  stateSpace->setBounds(bounds);
  stateSpace->registerDefaultProjection(std::make_shared<LeadingCoordinatesProjection>(stateSpace, space));
  auto si = std::make_shared<ob::SpaceInformation>(stateSpace);
  si->setStateValidityChecker(std::make_shared<SpaceValidityChecker>(si, space, counters));
  si->setMotionValidator(std::make_shared<SpaceMotionValidator>(si, space, resolution, counters));
  si->setup();
  return si;
}

void setStateBounds(const ob::SpaceInformation& si, const StateBounds& bounds) {
  const auto n = static_cast<unsigned int>(bounds.lower.size());
  ob::RealVectorBounds box(n);
  for (unsigned int i = 0; i < n; ++i) {
    box.setLow(i, bounds.lower[i]);
    box.setHigh(i, bounds.upper[i]);
  }
  si.getStateSpace()->as<ob::RealVectorStateSpace>()->setBounds(box);
}

std::vector<VectorX> pathPoints(const ompl::geometric::PathGeometric& path, int dimension) {
  std::vector<VectorX> points;
  for (std::size_t i = 0; i < path.getStateCount(); ++i) {
    points.push_back(Eigen::Map<const VectorX>(stateValues(path.getState(static_cast<unsigned int>(i))), dimension));
  }
  return points;
}

}  // namespace lang2manip
