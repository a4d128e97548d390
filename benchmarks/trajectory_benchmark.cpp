// Milliseconds to time the paper task's motions on the Panda ("put the marker and eraser in the
// holder", planned offline and grounded once, deterministic): the segments of its four actions
// (transits, Cartesian approach/lift/lower/retreat chains, gripper motions) timed as the executor
// does (timeActionMotions), per iteration all four actions. Variants:
//   RestToRest     a trapezoid per waypoint pair, rest at every waypoint (the baseline,
//                  registered first);
//   TimeOptimal    what the executor does: runs joined and blended (every arc re-checked with the
//                  exact checker and, on Cartesian moves, for straightness), Kunz & Stilman
//                  time-optimal parameterization, limits checked on the samples;
//   TimeOptimal/without_jerk_limits  the same with ExecutionSettings::limitJerk off;
//   TimeOptimal/parameterization_only  the parameterization alone: the same runs with the
//                  blends the executor chose, BlendedPath + timeOptimalParameterize;
//   TimeOptimal/jerk_limited_parameterization  the same sampled every millisecond and
//                  jerk-limited (limitJerk), as the executor does for the Panda;
// both at the Panda's limits (scaling 1). Counters: median_ms and p95_ms per call, duration_s of
// the whole trajectory, points output, stops_inside_runs, and median_over_rest_to_rest = a
// variant's median over the baseline's (run first, same process).
//
//   build/benchmarks/trajectory_benchmark [--benchmark_filter=TimeOptimal]

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <ompl/util/RandomNumbers.h>

#include "lang2manip/execution/motion_timing.hpp"
#include "lang2manip/planning/blended_path.hpp"
#include "lang2manip/planning/jerk_limiting.hpp"
#include "lang2manip/planning/time_optimal_trajectory.hpp"
#include "lang2manip/execution/task_executor.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/symbolic/repair_loop.hpp"

namespace lang2manip {
namespace {

/// The paper task executed once on the Panda's desk: its actions' motion segments.
struct PaperTaskMotions {
  Scene scene;
  std::vector<std::vector<MotionSegment>> actions;
};

const PaperTaskMotions& paperTaskMotions() {
  static const PaperTaskMotions motions = [] {
    PaperTaskMotions result;
    result.scene = readKauthamProblem(resolveProblem("panda_desk")).scene;
    TaskExecutor executor(result.scene, ExecutionSettings{});
    OfflineTaskPlanner planner;
    PlanningRequest request;
    request.task = "put the marker and eraser in the holder";
    request.scene = &result.scene;
    request.robot = executor.arm().robotName();
    const RepairResult repair = planWithRepair(planner, request, &executor, RepairOptions{}, StopCondition::never());
    if (!repair.succeeded()) throw InputError("trajectory benchmark: the paper task failed: " + repair.failure);
    for (const ActionExecution& action : executor.lastExecution().actions) result.actions.push_back(action.segments);
    return result;
  }();
  return motions;
}

enum class Variant { kRestToRest, kTimeOptimal, kWithoutJerkLimits, kParameterizationOnly, kJerkLimitedParameterization };

/// Every run of the task with the blends the executor chose.
std::vector<std::pair<std::vector<VectorX>, std::vector<double>>> chosenRuns(const ArmContext& arm,
                                                                             const PaperTaskMotions& motions) {
  std::vector<std::pair<std::vector<VectorX>, std::vector<double>>> runs;
  for (const std::vector<MotionSegment>& segments : motions.actions) {
    for (const TimedRun& run : timeActionMotions(arm, segments).runs) {
      const RunPath path = runPath(segments, run);
      if (!path.waypoints.empty()) runs.emplace_back(path.waypoints, run.cornerDeviations);
    }
  }
  return runs;
}

/// The time-optimal trajectory along `path`; jerk-limited: sampled every millisecond and averaged
/// as the executor does (planning/jerk_limiting.hpp).
JointTrajectory parameterized(const PlanningSpace& space, const BlendedPath& path, bool jerkLimited) {
  if (!jerkLimited) return timeOptimalParameterize(space, path);
  TimeOptimalOptions fine;
  fine.sampleInterval = 1e-3;
  const JointTrajectory timed = timeOptimalParameterize(space, path, fine);
  if (timed.points.size() < 2) return timed;
  return limitJerk(timed, space.jointAccelerationLimits(), space.jointJerkLimits(), 0.02).trajectory;
}

void timeTheTask(benchmark::State& state, Variant variant) {
  static double restToRestMedian = 0.0;
  const PaperTaskMotions& motions = paperTaskMotions();
  ExecutionSettings settings;
  settings.timing = variant == Variant::kRestToRest ? TrajectoryTiming::kRestToRest : TrajectoryTiming::kTimeOptimal;
  settings.limitJerk = variant != Variant::kWithoutJerkLimits;
  const ArmContext arm(motions.scene, settings);
  const auto runs = chosenRuns(arm, motions);
  std::vector<double> times;
  double duration = 0.0;
  double points = 0.0;
  double stops = 0.0;
  double checks = 0.0;
  for (auto _ : state) {
    duration = points = stops = checks = 0.0;
    const auto start = std::chrono::steady_clock::now();
    if (variant == Variant::kParameterizationOnly || variant == Variant::kJerkLimitedParameterization) {
      for (const auto& [waypoints, deviations] : runs) {
        const JointTrajectory trajectory = parameterized(arm.robotSpace(), BlendedPath(waypoints, deviations),
                                                         variant == Variant::kJerkLimitedParameterization);
        duration += trajectory.duration();
        points += static_cast<double>(trajectory.points.size());
        benchmark::DoNotOptimize(trajectory);
      }
    } else {
      for (const std::vector<MotionSegment>& segments : motions.actions) {
        const ActionTiming timed = timeActionMotions(arm, segments);
        duration += timed.trajectory.duration();
        points += static_cast<double>(timed.trajectory.points.size());
        stops += timed.quality.stopsInsideRuns;
        checks += static_cast<double>(timed.collisionChecks);
        benchmark::DoNotOptimize(timed);
      }
    }
    times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(times.begin(), times.end());
  const double median = times[times.size() / 2];
  state.counters["median_ms"] = median;
  state.counters["p95_ms"] = times[times.size() * 95 / 100];
  state.counters["duration_s"] = duration;
  state.counters["points"] = points;
  state.counters["stops_inside_runs"] = stops;
  state.counters["blend_states_checked"] = checks;
  if (variant == Variant::kRestToRest) restToRestMedian = median;
  if (variant != Variant::kRestToRest && restToRestMedian > 0.0) {
    state.counters["median_over_rest_to_rest"] = median / restToRestMedian;
  }
}

void registerAll() {
  for (const auto& [name, variant] : {std::pair{"PaperTaskPanda/RestToRest", Variant::kRestToRest},
                                      std::pair{"PaperTaskPanda/TimeOptimal", Variant::kTimeOptimal},
                                      std::pair{"PaperTaskPanda/TimeOptimal/without_jerk_limits", Variant::kWithoutJerkLimits},
                                      std::pair{"PaperTaskPanda/TimeOptimal/parameterization_only", Variant::kParameterizationOnly},
                                      std::pair{"PaperTaskPanda/TimeOptimal/jerk_limited_parameterization", Variant::kJerkLimitedParameterization}}) {
    const Variant chosen = variant;
    benchmark::RegisterBenchmark(name, [chosen](benchmark::State& state) { timeTheTask(state, chosen); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(100);
  }
}

}  // namespace
}  // namespace lang2manip

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  ompl::RNG::setSeed(1);  // the transit planners' paths, as `lang2manip run --seed 1`
  lang2manip::registerAll();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
