// Milliseconds to time-parameterize a paper-task-like Panda path of 98 joint-space waypoints
// (four transit paths of 8-10 waypoints, with three pick-and-place Cartesian-like chains of 11
// waypoints 1.2 cm apart in between, each approached and retraced: reversals), deterministic
// (seeded). Variants, each timed alone per iteration:
//   RestToRest            timeParameterize(): a trapezoid per segment, rest at every waypoint
//                         (the baseline, registered first);
//   TimeOptimal/space     timeOptimalParameterize() with the same limits (the Panda space's:
//                         URDF velocity limits, the datasheet accelerations {15, 7.5, 10, 12.5,
//                         15, 20, 20} rad/s^2 of panda.joint_limits.yaml);
//   TimeOptimal/default_accelerations  the same with planning's default accelerations for a
//                         robot without a joint limits file (2 x velocity).
// Counters: median_ms and p95_ms per call, duration_s of the trajectory, points output, and
// median_over_rest_to_rest = a variant's median over the baseline's (run first, same process).
//
//   build/benchmarks/trajectory_benchmark [--benchmark_filter=TimeOptimal]

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/core/random.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/scene.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "lang2manip/planning/planning_space.hpp"
#include "lang2manip/planning/time_optimal_trajectory.hpp"
#include "lang2manip/planning/trajectory.hpp"

namespace lang2manip {
namespace {

constexpr std::uint64_t kSeed = 7;

std::shared_ptr<const PlanningSpace> pandaArmSpace() {
  static const std::shared_ptr<const PlanningSpace> space = [] {
    Scene scene;
    SceneRobot robot;
    robot.name = "panda";
    robot.model = readUrdfFile(builtinRobotUrdf("panda"));
    robot.configuration = robot.model->namedConfiguration("home");
    scene.addRobot(robot);
    std::vector<std::string> joints;
    for (int i = 1; i <= 7; ++i) joints.push_back("panda_joint" + std::to_string(i));
    return std::make_shared<const JointPlanningSpace>(std::make_shared<FclCollisionChecker>(scene),
                                                      std::vector<std::string>{"panda"},
                                                      std::vector<std::vector<std::string>>{joints});
  }();
  return space;
}

/// Transit paths between random configurations (a straight line with every waypoint but the
/// last moved by up to 0.25 rad per joint, as a shortcut planner leaves them), and at three of
/// them a chain of 11 waypoints 1.2 cm apart along a slowly bending direction (a Cartesian
/// approach), then the same chain back (the retreat).
std::vector<VectorX> taskPath(const PlanningSpace& space) {
  Random random(kSeed);
  const VectorX margin = VectorX::Constant(7, 0.3);
  const VectorX lower = space.lower() + margin;
  const VectorX upper = space.upper() - margin;
  const VectorX home = (VectorX(7) << 0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785).finished();
  std::vector<VectorX> path{home};
  const auto transit = [&](int waypoints) {
    const VectorX start = path.back();
    const VectorX goal = random.uniformVector(lower, upper);
    for (int i = 1; i <= waypoints; ++i) {
      VectorX q = start + (goal - start) * (static_cast<double>(i) / waypoints);
      if (i < waypoints) q += random.uniformVector(VectorX::Constant(7, -0.25), VectorX::Constant(7, 0.25));
      path.push_back(q.cwiseMax(lower).cwiseMin(upper));
    }
  };
  const auto chainAndBack = [&] {
    VectorX direction = random.uniformVector(VectorX::Constant(7, -1.0), VectorX::Constant(7, 1.0)).normalized();
    const VectorX bend = random.uniformVector(VectorX::Constant(7, -0.02), VectorX::Constant(7, 0.02));
    const std::size_t first = path.size() - 1;
    for (int i = 1; i < 11; ++i) {
      direction = (direction + bend).normalized();
      path.push_back(path.back() + 0.012 * direction);
    }
    for (std::size_t i = path.size() - 1; i-- > first;) {
      const VectorX back = path[i];
      path.push_back(back);
    }
  };
  const int transits[] = {9, 10, 8, 10};
  for (int i = 0; i < 4; ++i) {
    transit(transits[i]);
    if (i < 3) chainAndBack();
  }
  return path;
}

enum class Variant { kRestToRest, kTimeOptimalSpace, kTimeOptimalDefaultAccelerations };

void parameterize(benchmark::State& state, Variant variant) {
  static double restToRestMedian = 0.0;
  const auto space = pandaArmSpace();
  const std::vector<VectorX> path = taskPath(*space);
  const VectorX pandaVelocity = space->jointVelocityLimits();
  const VectorX defaultAcceleration = JointLimitDefaults{}.accelerationPerVelocity * pandaVelocity;
  std::vector<double> times;
  JointTrajectory trajectory;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    switch (variant) {
      case Variant::kRestToRest: trajectory = timeParameterize(*space, path); break;
      case Variant::kTimeOptimalSpace: trajectory = timeOptimalParameterize(*space, path); break;
      case Variant::kTimeOptimalDefaultAccelerations:
        trajectory = timeOptimalParameterize(path, pandaVelocity, defaultAcceleration);
        break;
    }
    times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    benchmark::DoNotOptimize(trajectory);
  }
  std::sort(times.begin(), times.end());
  const double median = times[times.size() / 2];
  state.counters["median_ms"] = median;
  state.counters["p95_ms"] = times[times.size() * 95 / 100];
  state.counters["duration_s"] = trajectory.duration();
  state.counters["points"] = static_cast<double>(trajectory.points.size());
  state.counters["waypoints"] = static_cast<double>(path.size());
  if (variant == Variant::kRestToRest) restToRestMedian = median;
  if (variant != Variant::kRestToRest && restToRestMedian > 0.0) {
    state.counters["median_over_rest_to_rest"] = median / restToRestMedian;
  }
}

void registerAll() {
  for (const auto& [name, variant] : {std::pair{"TrajectoryPanda98/RestToRest", Variant::kRestToRest},
                                      std::pair{"TrajectoryPanda98/TimeOptimal/space", Variant::kTimeOptimalSpace},
                                      std::pair{"TrajectoryPanda98/TimeOptimal/default_accelerations",
                                                Variant::kTimeOptimalDefaultAccelerations}}) {
    const Variant chosen = variant;
    benchmark::RegisterBenchmark(name, [chosen](benchmark::State& state) { parameterize(state, chosen); })
        ->Unit(benchmark::kMillisecond)
        ->MinTime(2.0);
  }
}

}  // namespace
}  // namespace lang2manip

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  lang2manip::registerAll();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
