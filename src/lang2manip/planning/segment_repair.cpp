#include "lang2manip/planning/segment_repair.hpp"

#include <algorithm>

#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

namespace lang2manip {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

// A segment not mended within half a second is usually one no detour nearby mends (an end touching
// an obstacle): the time is better spent planning the query again.
constexpr double kMinSegmentSeconds = 0.05;
constexpr double kMaxSegmentSeconds = 0.5;

ob::ScopedState<> scopedState(const ob::SpaceInformationPtr& si, const VectorX& x) {
  ob::ScopedState<> state(si);
  for (Eigen::Index i = 0; i < x.size(); ++i) state[static_cast<unsigned int>(i)] = x[i];
  return state;
}

/// A path from `from` to `to` whose motions are valid in `si`, or nullopt by `stop`.
std::optional<std::vector<VectorX>> planSegment(const ob::SpaceInformationPtr& si, const PlanningSpace& space,
                                                const VectorX& from, const VectorX& to, const StopCondition& stop) {
  auto problem = std::make_shared<ob::ProblemDefinition>(si);
  problem->setStartAndGoalStates(scopedState(si, from), scopedState(si, to), 0.0);
  og::RRTConnect planner(si);
  if (const auto range = space.defaultRange()) planner.setRange(*range);
  planner.setProblemDefinition(problem);
  planner.setup();
  const StopCondition limit =
      stop.orElse(StopCondition::afterSeconds(std::clamp(0.5 * stop.secondsLeft(), kMinSegmentSeconds, kMaxSegmentSeconds)));
  const ob::PlannerStatus status = planner.solve(ob::PlannerTerminationCondition([&limit] { return limit.shouldStop(); }));
  std::optional<std::vector<VectorX>> points;
  if (status == ob::PlannerStatus::EXACT_SOLUTION && problem->hasExactSolution()) {
    points = pathPoints(*problem->getSolutionPath()->as<og::PathGeometric>(), space.dimension());
    points->back() = to;  // exact goal: the segment ends where the path goes on
  }
  planner.clear();
  return points;
}

}  // namespace

std::optional<RepairedPath> repairCollidingSegments(const PlanningSpace& space, const std::vector<VectorX>& path,
                                                    const StateBounds& bounds, double resolution,
                                                    const StopCondition& stop,
                                                    const std::shared_ptr<CheckCounters>& counters) {
  if (path.empty()) return RepairedPath{};
  for (const VectorX& point : path) {
    if (!space.isValid(point.data())) return std::nullopt;
  }
  ob::SpaceInformationPtr si;
  RepairedPath repaired{{path.front()}, 0};
  for (std::size_t i = 1; i < path.size(); ++i) {
    if (space.isMotionValid(path[i - 1].data(), path[i].data(), resolution)) {
      repaired.points.push_back(path[i]);
      continue;
    }
    if (stop.shouldStop()) return std::nullopt;
    if (!si) {
      si = makeSpaceInformation(space, resolution, counters);
      setStateBounds(*si, bounds);
    }
    const auto detour = planSegment(si, space, path[i - 1], path[i], stop);
    if (!detour) return std::nullopt;
    repaired.points.insert(repaired.points.end(), detour->begin() + 1, detour->end());
    ++repaired.repairedSegments;
  }
  return repaired;
}

}  // namespace lang2manip
