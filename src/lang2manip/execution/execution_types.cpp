#include "lang2manip/execution/execution_types.hpp"

#include <cmath>

#include "lang2manip/core/error.hpp"

namespace lang2manip {
namespace {

void checkPositive(double value, const char* field) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw InputError(std::string("execution settings: ") + field + " must be a positive number (got " + std::to_string(value) + ")");
  }
}

void checkLength(double value, const char* field) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    throw InputError(std::string("execution settings: ") + field + " must be a finite length >= 0 (got " + std::to_string(value) + ")");
  }
}

}  // namespace

std::string actionStatusName(ActionStatus status) {
  switch (status) {
    case ActionStatus::kSucceeded: return "succeeded";
    case ActionStatus::kFailed: return "failed";
    case ActionStatus::kNotRun: return "not run";
  }
  return "unknown";
}

StageTimes& StageTimes::operator+=(const StageTimes& other) {
  grasp += other.grasp;
  placement += other.placement;
  ik += other.ik;
  motion += other.motion;
  return *this;
}

ExecutionCounters& ExecutionCounters::operator+=(const ExecutionCounters& other) {
  plannerCalls += other.plannerCalls;
  plannerSolved += other.plannerSolved;
  ikCalls += other.ikCalls;
  collisionChecks += other.collisionChecks;
  graspPlans += other.graspPlans;
  placementPlans += other.placementPlans;
  return *this;
}

void checkExecutionSettings(const ExecutionSettings& s) {
  checkPositive(s.planningTimeSeconds, "planningTimeSeconds");
  checkPositive(s.cartesianStep, "cartesianStep");
  checkPositive(s.cartesianAngleStep, "cartesianAngleStep");
  checkPositive(s.maxJointStep, "maxJointStep");
  checkPositive(s.verificationResolution, "verificationResolution");
  checkLength(s.pushApproachHeight, "pushApproachHeight");
  checkLength(s.pushStandoff, "pushStandoff");
  checkLength(s.pushRetreat, "pushRetreat");
  checkPositive(s.reach.ikTimeoutSeconds, "reach.ikTimeoutSeconds");
  if (s.maxGraspAttempts < 1) throw InputError("execution settings: maxGraspAttempts must be >= 1");
  if (s.maxPlacementAttempts < 1) throw InputError("execution settings: maxPlacementAttempts must be >= 1");
  if (s.reach.ikSolutions < 1) throw InputError("execution settings: reach.ikSolutions must be >= 1");
  for (const auto& [value, name] : {std::pair{s.velocityScaling, "velocityScaling"}, std::pair{s.accelerationScaling, "accelerationScaling"}}) {
    if (const std::string problem = scalingProblem(value); !problem.empty()) {
      throw InputError(std::string("execution settings: ") + name + " " + problem);
    }
  }
  checkLength(s.blendDeviation, "blendDeviation");
  checkPositive(s.cartesianDeviation, "cartesianDeviation");
  checkGraspSettings(s.grasp);
  checkPlacementSettings(s.placement);
}

TrajectoryQuality& TrajectoryQuality::operator+=(const TrajectoryQuality& other) {
  stopsInsideRuns += other.stopsInsideRuns;
  blendedCorners += other.blendedCorners;
  reducedBlends += other.reducedBlends;
  restToRestFallbacks += other.restToRestFallbacks;
  jerkLimitedRuns += other.jerkLimitedRuns;
  jerkReducedRuns += other.jerkReducedRuns;
  pathLength += other.pathLength;
  seconds += other.seconds;
  return *this;
}

std::string trajectoryTimingName(TrajectoryTiming timing) {
  return timing == TrajectoryTiming::kTimeOptimal ? "time-optimal" : "rest-to-rest";
}

TrajectoryTiming trajectoryTimingNamed(const std::string& name) {
  for (const TrajectoryTiming timing : {TrajectoryTiming::kTimeOptimal, TrajectoryTiming::kRestToRest}) {
    if (trajectoryTimingName(timing) == name) return timing;
  }
  throw InputError("unknown trajectory timing \"" + name + "\" (known: time-optimal, rest-to-rest)");
}

}  // namespace lang2manip
