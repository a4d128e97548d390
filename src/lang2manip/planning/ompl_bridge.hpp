#pragma once
/// @file Internal: an OMPL SpaceInformation over a PlanningSpace, with validity and motion
/// checks that count how often they run.

#include <atomic>
#include <memory>
#include <vector>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/geometric/PathGeometric.h>

#include "lang2manip/planning/planning_space.hpp"

namespace lang2manip {

struct CheckCounters {
  std::atomic<long> states{0};
  std::atomic<long> motions{0};
};

/// A SpaceInformation for `space` (RealVectorStateSpace with its bounds), motions checked at
/// `resolution`; the counters are incremented by every check.
ompl::base::SpaceInformationPtr makeSpaceInformation(const PlanningSpace& space, double resolution,
                                                     const std::shared_ptr<CheckCounters>& counters);

/// Makes `bounds` the box of `si`'s RealVectorStateSpace (sampling and satisfiesBounds()).
void setStateBounds(const ompl::base::SpaceInformation& si, const StateBounds& bounds);

/// The values of an OMPL state of a RealVectorStateSpace.
const double* stateValues(const ompl::base::State* state);

/// Converts between OMPL paths and vectors of points.
std::vector<VectorX> pathPoints(const ompl::geometric::PathGeometric& path, int dimension);

}  // namespace lang2manip
