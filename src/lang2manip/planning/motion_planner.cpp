#include "lang2manip/planning/motion_planner.hpp"

#include <algorithm>
#include <cstdlib>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>

#include <ompl/base/PlannerData.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/base/goals/GoalStates.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/samplers/BridgeTestValidStateSampler.h>
#include <ompl/base/samplers/GaussianValidStateSampler.h>
#include <ompl/base/samplers/ObstacleBasedValidStateSampler.h>
#include <ompl/base/samplers/UniformValidStateSampler.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/util/Console.h>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/planning/ompl_bridge.hpp"
#include "lang2manip/planning/planner_registry.hpp"
#include "lang2manip/planning/segment_repair.hpp"

namespace lang2manip {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using Clock = std::chrono::steady_clock;


class LogOutputHandler final : public ompl::msg::OutputHandler {
 public:
  void log(const std::string& text, ompl::msg::LogLevel level, const char*, int) override {
    const LogLevel ours = level >= ompl::msg::LOG_ERROR  ? LogLevel::kError
                          : level >= ompl::msg::LOG_WARN ? LogLevel::kWarn
                          : level >= ompl::msg::LOG_INFO ? LogLevel::kInfo
                                                         : LogLevel::kDebug;
    logMessage(ours, "OMPL: " + text);
  }
};

ob::State* newState(const ob::SpaceInformationPtr& si, const VectorX& x) {
  ob::State* state = si->allocState();
  auto* values = state->as<ob::RealVectorStateSpace::StateType>()->values;
  for (Eigen::Index i = 0; i < x.size(); ++i) values[i] = x[i];
  return state;
}

long progressIterations(const ob::Planner& planner) {
  const auto& properties = planner.getPlannerProgressProperties();
  const auto found = properties.find("iterations INTEGER");
  if (found == properties.end()) return -1;
  try {
    return std::stol(found->second());
  } catch (const std::exception&) {
    return -1;
  }
}

bool plansUntilLimit(const PlannerSettings& settings) {
  const PlannerDescription& description = plannerDescription(settings.planner());
  return description.runsUntilTimeLimit || (settings.optimize() && description.optimizing);
}

/// When a planner's range exceeds the whole space, every extension must reach its sample in one
/// collision-free motion, which narrow passages never allow: the reason a path is not found.
std::string rangeHint(ob::Planner& planner) {
  if (!planner.params().hasParam("range")) return "";
  const double range = std::atof(planner.params()["range"].getValue().c_str());
  const double extent = planner.getSpaceInformation()->getMaximumExtent();
  if (!(range > extent)) return "";
  return " (its range " + numberText(range) + " exceeds the extent " + numberText(extent) +
         " of the planning space, so each extension must reach its sample in one collision-free motion; "
         "Kautham measures Range in its own state space, where the same number may mean a shorter step)";
}

/// The vertices of `data` as points of a space of `dimension` and at most `maxEdges` of its edges.
ExplorationTree explorationTree(const ob::PlannerData& data, int dimension, std::size_t maxEdges) {
  ExplorationTree tree;
  for (unsigned int v = 0; v < data.numVertices(); ++v) {
    const double* values = stateValues(data.getVertex(v).getState());
    tree.vertices.push_back(Eigen::Map<const VectorX>(values, dimension));
  }
  std::vector<unsigned int> targets;
  for (unsigned int v = 0; v < data.numVertices(); ++v) {
    data.getEdges(v, targets);
    for (const unsigned int target : targets) {
      if (tree.edges.size() < maxEdges) {
        tree.edges.emplace_back(static_cast<int>(v), static_cast<int>(target));
      } else {
        ++tree.omittedEdges;
      }
    }
  }
  return tree;
}

ob::ValidStateSamplerPtr allocValidStateSampler(ValidStateSampler sampler, const ob::SpaceInformation* si) {
  switch (sampler) {
    case ValidStateSampler::kGaussian: return std::make_shared<ob::GaussianValidStateSampler>(si);
    case ValidStateSampler::kObstacleBased: return std::make_shared<ob::ObstacleBasedValidStateSampler>(si);
    case ValidStateSampler::kBridgeTest: return std::make_shared<ob::BridgeTestValidStateSampler>(si);
    case ValidStateSampler::kUniform: break;
  }
  return std::make_shared<ob::UniformValidStateSampler>(si);
}

}  // namespace

void routeOmplMessagesToLog() {
  static std::once_flag once;
  std::call_once(once, [] {
    static LogOutputHandler handler;
    ompl::msg::useOutputHandler(&handler);
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  });
}

std::string motionPlanStatusName(MotionPlanStatus status) {
  switch (status) {
    case MotionPlanStatus::kSolved: return "solved";
    case MotionPlanStatus::kNoPath: return "no_path";
    case MotionPlanStatus::kStopped: return "stopped";
    case MotionPlanStatus::kVerificationFailed: return "verification_failed";
  }
  return "unknown";
}

struct MotionPlanner::Ompl {
  // Planners free their graphs in clear(); LazyPRM leaks its states when destroyed without it.
  ~Ompl() {
    if (planner) planner->clear();
  }
  std::shared_ptr<CheckCounters> counters = std::make_shared<CheckCounters>();
  ob::SpaceInformationPtr si;
  ob::PlannerPtr planner;
  std::string plannerKey;
};

MotionPlanner::MotionPlanner(std::shared_ptr<const PlanningSpace> space,
                             const MotionPlanningOptions& options)
    : space_(std::move(space)), options_(options), ompl_(std::make_unique<Ompl>()) {
  if (!space_) throw InputError("motion planner: no planning space given");
  for (const double resolution : {options_.resolution, options_.verificationResolution}) {
    if (!(resolution > 0.0 && std::isfinite(resolution))) {
      throw InputError("motion planner: resolutions must be positive and finite");
    }
  }
  routeOmplMessagesToLog();
  ompl_->si = makeSpaceInformation(*space_, options_.resolution, ompl_->counters);
  bounds_ = {space_->lower(), space_->upper()};
}

MotionPlanner::~MotionPlanner() = default;

void MotionPlanner::checkEndpoint(const VectorX& x, const std::string& what) const {
  space_->checkPoint(x, what);
  if (space_->isValid(x.data())) return;
  const CollisionReport report = space_->report(x);
  std::string pairs;
  for (const CollisionContact& contact : report.contacts) {
    pairs += (pairs.empty() ? "" : ", ") + contact.first + " touches " + contact.second;
  }
  throw InputError(what + " is in collision: " + (pairs.empty() ? "(no pair reported)" : pairs));
}

std::string MotionPlanner::verifyPath(const std::vector<VectorX>& path) const {
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (!space_->isValid(path[i].data())) return "path point " + std::to_string(i) + " is in collision";
    if (i > 0 && !space_->isMotionValid(path[i - 1].data(), path[i].data(),
                                        options_.verificationResolution)) {
      std::string pairs;
      if (const auto state = space_->firstInvalidState(path[i - 1], path[i], options_.verificationResolution)) {
        for (const CollisionContact& contact : space_->report(*state).contacts) {
          pairs += (pairs.empty() ? ": " : ", ") + contact.first + " touches " + contact.second;
        }
      }
      return "path segment " + std::to_string(i - 1) + " -> " + std::to_string(i) +
             " collides at resolution " + numberText(options_.verificationResolution) + pairs;
    }
  }
  return {};
}

ompl::base::ProblemDefinitionPtr MotionPlanner::makeProblem(const VectorX& start,
                                                            const std::vector<VectorX>& goals,
                                                            const PlannerSettings& settings) const {
  const ob::SpaceInformationPtr& si = ompl_->si;
  auto problem = std::make_shared<ob::ProblemDefinition>(si);
  ob::State* startState = newState(si, start);
  problem->addStartState(startState);
  si->freeState(startState);
  // Within the planning resolution of a goal counts as reached (planners that steer by random
  // propagation, such as SST, never land on it exactly); finishPath() appends the exact goal.
  if (goals.size() == 1 || plannerDescription(settings.planner()).singleGoalState) {
    auto goal = std::make_shared<ob::GoalState>(si);
    ob::State* state = newState(si, goals.front());
    goal->setState(state);
    si->freeState(state);
    goal->setThreshold(options_.resolution);
    problem->setGoal(goal);
  } else {
    auto goalStates = std::make_shared<ob::GoalStates>(si);
    for (const VectorX& goal : goals) {
      ob::State* state = newState(si, goal);
      goalStates->addState(state);
      si->freeState(state);
    }
    goalStates->setThreshold(options_.resolution);
    problem->setGoal(goalStates);
  }
  auto objective = std::make_shared<ob::PathLengthOptimizationObjective>(si);
  if (!settings.optimize()) objective->setCostThreshold(ob::Cost(std::numeric_limits<double>::infinity()));
  problem->setOptimizationObjective(objective);
  return problem;
}

void MotionPlanner::preparePlanner(const PlannerSettings& settings) {
  std::string key = settings.planner() + ";" + validStateSamplerName(settings.validStateSampler());
  for (const auto& [name, value] : settings.omplParameters()) key += ";" + name + "=" + value;
  // A roadmap kept between queries holds states of its box only.
  for (Eigen::Index i = 0; i < bounds_.lower.size(); ++i) {
    key += ";" + std::to_string(bounds_.lower[i]) + ":" + std::to_string(bounds_.upper[i]);
  }
  if (settings.incremental() && ompl_->planner && key == ompl_->plannerKey) {
    ompl_->planner->clearQuery();
    return;
  }
  if (ompl_->planner) ompl_->planner->clear();
  ompl_->si->setValidStateSamplerAllocator([sampler = settings.validStateSampler()](const ob::SpaceInformation* si) {
    return allocValidStateSampler(sampler, si);
  });
  ompl_->planner = createOmplPlanner(settings.planner(), ompl_->si);
  const bool rangeGiven = std::any_of(settings.omplParameters().begin(), settings.omplParameters().end(),
                                      [](const auto& parameter) { return parameter.first == "range"; });
  if (!rangeGiven && space_->defaultRange() && plannerDescription(settings.planner()).takesSpaceRange &&
      ompl_->planner->params().hasParam("range")) {
    ompl_->planner->params().setParam("range", std::to_string(*space_->defaultRange()));
  }
  for (const auto& [name, value] : settings.omplParameters()) {
    if (!ompl_->planner->params().setParam(name, value)) {
      throw InputError("planner " + settings.planner() + " rejected parameter " + name + " = " + value);
    }
  }
  ompl_->plannerKey = key;
}

// Simplifies, verifies and time-parameterizes an exact solution; returns why it failed, if it did.
void MotionPlanner::appendExactGoal(og::PathGeometric& path, const std::vector<VectorX>& goals) const {
  const Eigen::Map<const VectorX> last(stateValues(path.getState(static_cast<unsigned int>(path.getStateCount() - 1))),
                                       space_->dimension());
  const VectorX* nearest = &goals.front();
  for (const VectorX& goal : goals) {
    if ((goal - last).norm() < (*nearest - last).norm()) nearest = &goal;
  }
  if ((*nearest - last).norm() == 0.0) return;
  ob::State* state = newState(ompl_->si, *nearest);
  path.append(state);
  ompl_->si->freeState(state);
}

// A path that grazes an obstacle between the planner's coarser checks: its colliding segments
// are planned again at the verification resolution, in the simplified path, else in the
// planner's own path.
bool MotionPlanner::mendPath(const StopCondition& stop, MotionPlan& plan) const {
  const auto repairStart = Clock::now();
  std::vector<std::vector<VectorX>> candidates = {plan.path};
  if (plan.rawPath != plan.path) candidates.push_back(plan.rawPath);
  std::optional<RepairedPath> repaired;
  for (std::size_t c = 0; c < candidates.size() && !repaired && !stop.shouldStop(); ++c) {
    repaired = repairCollidingSegments(*space_, candidates[c], bounds_, options_.verificationResolution, stop,
                                       ompl_->counters);
  }
  plan.statistics.repairSeconds += secondsSince(repairStart);
  if (!repaired) return false;
  const auto verificationStart = Clock::now();
  const bool verified = verifyPath(repaired->points).empty();
  plan.statistics.verificationSeconds += secondsSince(verificationStart);
  if (!verified) return false;
  plan.path = std::move(repaired->points);
  plan.statistics.repairedSegments += repaired->repairedSegments;
  double length = 0.0;
  for (std::size_t i = 1; i < plan.path.size(); ++i) length += (plan.path[i] - plan.path[i - 1]).norm();  // OMPL's RealVector metric
  plan.statistics.lengthAfterSimplification = length;
  return true;
}

std::string MotionPlanner::finishPath(og::PathGeometric path, const VectorX& start,
                                      const std::vector<VectorX>& goals, const PlannerSettings& settings, const StopCondition& stop,
                                      MotionPlan& plan) const {
  appendExactGoal(path, goals);
  plan.rawPath = pathPoints(path, space_->dimension());
  plan.statistics.lengthBeforeSimplification = path.length();
  const auto simplifyStart = Clock::now();
  const og::PathGeometric unsimplified = path;
  og::PathSimplifier simplifier(ompl_->si);
  if (settings.simplifyLevel() == SimplifyLevel::kSmooth) {
    simplifier.smoothBSpline(path);
  } else if (settings.simplifyLevel() == SimplifyLevel::kShortcutAndSmooth) {
    const double budget = std::max(0.05, std::min(1.0, stop.secondsLeft()));
    simplifier.simplify(path, ob::plannerOrTerminationCondition(
                                  ob::timedPlannerTerminationCondition(budget),
                                  ob::PlannerTerminationCondition([&stop] { return stop.shouldStop(); })));
  }
  // Smoothing may lengthen a path it was asked to shorten: the planner's path is kept then.
  if (path.length() > unsimplified.length()) path = unsimplified;
  plan.statistics.simplifySeconds += secondsSince(simplifyStart);
  plan.statistics.lengthAfterSimplification = path.length();
  plan.path = pathPoints(path, space_->dimension());
  plan.path.front() = start;
  const auto verificationStart = Clock::now();
  const std::string failure = verifyPath(plan.path);
  plan.statistics.verificationSeconds += secondsSince(verificationStart);
  if (!failure.empty() && !mendPath(stop, plan)) return failure;
  const auto timingStart = Clock::now();
  plan.trajectory = timeParameterize(*space_, plan.path, options_.timing);
  plan.statistics.parameterizationSeconds += secondsSince(timingStart);
  return checkTrajectoryLimits(*space_, plan.trajectory);
}

// One planner run on `problem`, adding its time, iterations and graph size to `statistics`.
ompl::base::PlannerStatus MotionPlanner::runPlanner(const ob::ProblemDefinitionPtr& problem,
                                                   const PlannerSettings& settings,
                                                   const StopCondition& limit,
                                                   MotionPlan& plan) {
  MotionPlanStatistics& statistics = plan.statistics;
  ob::Planner& planner = *ompl_->planner;
  planner.setProblemDefinition(problem);
  planner.setup();
  // A planner that always plans until its limit is given 80% of the time left, keeping the
  // rest to plan again if its path fails verification.
  const StopCondition attemptLimit =
      plansUntilLimit(settings)
          ? limit.orElse(StopCondition::afterSeconds(std::max(1e-3, 0.8 * limit.secondsLeft())))
          : limit;
  const auto planningStart = Clock::now();
  const ob::PlannerStatus status = planner.solve(
      ob::PlannerTerminationCondition([&attemptLimit] { return attemptLimit.shouldStop(); }));
  statistics.planningSeconds += secondsSince(planningStart);
  statistics.iterations = progressIterations(planner);
  ob::PlannerData data(ompl_->si);
  planner.getPlannerData(data);
  statistics.vertices = static_cast<long>(data.numVertices());
  statistics.edges = static_cast<long>(data.numEdges());
  if (options_.recordTreeEdges > 0) plan.tree = explorationTree(data, space_->dimension(), options_.recordTreeEdges);
  return status;
}

MotionPlan MotionPlanner::solve(const VectorX& start, const std::vector<VectorX>& goals,
                                const PlannerSettings& settings, const StopCondition& stop) {
  if (goals.empty()) throw InputError("motion query: no goal given");
  checkEndpoint(start, "start");
  for (std::size_t g = 0; g < goals.size(); ++g) {
    checkEndpoint(goals[g], goals.size() == 1 ? "goal" : "goal " + std::to_string(g));
  }
  std::vector<VectorX> restingPoints = goals;
  restingPoints.push_back(start);
  bounds_ = space_->plannedBounds(options_.positionMargin, restingPoints);
  setStateBounds(*ompl_->si, bounds_);
  preparePlanner(settings);
  MotionPlan plan;
  ompl_->counters->states = 0;
  ompl_->counters->motions = 0;
  const StopCondition limit = stop.orElse(StopCondition::afterSeconds(settings.maxPlanningTime()));
  std::string rejected;
  for (int attempt = 1;; ++attempt) {
    const auto problem = makeProblem(start, goals, settings);
    if (attempt > 1) {  // a fresh planner: OMPL planners warn when set up twice
      ompl_->planner->clear();
      ompl_->planner.reset();
      preparePlanner(settings);
    }
    const ob::PlannerStatus status = runPlanner(problem, settings, limit, plan);
    const bool exact = status == ob::PlannerStatus::EXACT_SOLUTION && problem->hasExactSolution();
    if (!exact) {
      plan.status = !rejected.empty() ? MotionPlanStatus::kVerificationFailed
                    : stop.shouldStop() ? MotionPlanStatus::kStopped
                                        : MotionPlanStatus::kNoPath;
      plan.message = !rejected.empty() ? rejected
                     : plan.status == MotionPlanStatus::kStopped
                         ? "stopped before a path was found by " + settings.planner()
                         : "no path found in " + numberText(settings.maxPlanningTime()) + " s by " +
                               settings.planner() + rangeHint(*ompl_->planner);
      break;
    }
    const std::string failure =
        finishPath(*problem->getSolutionPath()->as<og::PathGeometric>(), start, goals, settings, limit, plan);
    if (failure.empty()) {
      plan.status = MotionPlanStatus::kSolved;
      plan.message.clear();
      break;
    }
    // A path that grazes an obstacle between the planner's checks is rejected; plan again with
    // the time left.
    rejected = "the paths found by " + settings.planner() + " failed verification (last: " + failure + ")";
    plan.trajectory = {};
    ++plan.statistics.rejectedPaths;
  }
  if (!plan.solved()) {
    plan.path.clear();
    plan.trajectory = {};
  }
  plan.statistics.stateChecks = ompl_->counters->states;
  plan.statistics.motionChecks = ompl_->counters->motions;
  return plan;
}

}  // namespace lang2manip
