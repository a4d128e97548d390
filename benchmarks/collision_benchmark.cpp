// Microseconds per state check of the exact (FCL) checker: self-collision only, the paper's desk
// scene (panda_desk) and a mesh scene from ../shared/data/kautham (TX90 + gripper, TwoCan), each
// with and without the bounding-box pre-check (the in-process baseline), over seeded random
// configurations and over valid ones only (every pair reaches the end of the list). Random
// states also with a strict contact tolerance of 0 (the baseline of the resting-contact probes,
// which only run on overlapping pairs).
// Per edge: isMotionValid() at a fixed resolution (kEdgeResolution rad per sample) on short
// edges from a valid state to a random neighbour (each joint moved up to kEdgeReach rad), like a
// planner's edges, for the same scenes and the same two variants.
// MeshTrees: milliseconds to get the FCL trees of the TX90 + gripper's meshes, rebuilt (the
// baseline: what each checker did before the process-wide cache), rebuilt on every core, cached.
// Counters: median_us and p95_us per check or edge (each timed alone), valid = fraction valid,
// states_per_edge = states an edge holds at the resolution, median_over_default = a variant's
// median state check over the default checker's.
//
//   build/benchmarks/collision_benchmark [--benchmark_filter=Desk]

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <variant>

#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/collision/fcl_mesh_cache.hpp"
#include "lang2manip/core/random.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/model/urdf_reader.hpp"

namespace lang2manip {
namespace {

constexpr int kConfigurations = 2000;
constexpr std::uint64_t kSeed = 42;
constexpr double kEdgeResolution = 0.01;
constexpr double kEdgeReach = 0.3;

std::filesystem::path tx90Problem() {
  return std::filesystem::path(LANG2MANIP_SHARED_DIR) /
         "data/kautham/OMPL_geo_demos/TX90_IOC/OMPL_RRTConnect_TX90_gripper_TwoCan.xml";
}

Scene sceneNamed(const std::string& name) {
  if (name == "self") {
    Scene scene;
    SceneRobot robot;
    robot.name = "panda";
    robot.model = readUrdfFile(builtinRobotUrdf("panda"));
    robot.configuration = robot.model->namedConfiguration("home");
    scene.addRobot(robot);
    return scene;
  }
  if (name == "desk") return readKauthamProblem(resolveProblem("panda_desk")).scene;
  return readKauthamProblem(tx90Problem()).scene;
}

/// One checker per (scene, pre-check), built once; the ACM is shared between the two variants.
struct Fixture {
  std::unique_ptr<FclCollisionChecker> checker;
  std::vector<VectorX> random;
  std::vector<VectorX> valid;
  /// Edge i runs from valid[i] to edgeEnds[i].
  std::vector<VectorX> edgeEnds;
};

void addEdges(const RobotModel& model, Random& random, Fixture& entry) {
  const VectorX reach = VectorX::Constant(model.variableCount(), kEdgeReach);
  for (const VectorX& start : entry.valid) {
    const VectorX end = (start + random.uniformVector(-reach, reach))
                            .cwiseMax(model.lowerLimits())
                            .cwiseMin(model.upperLimits());
    entry.edgeEnds.push_back(end);
  }
}

/// What a fixture's checker does differently from the default one.
enum class Variant { kDefault, kNoPrecheck, kStrictContacts };

std::string variantName(Variant variant) {
  switch (variant) {
    case Variant::kDefault: return "/aabb_precheck";
    case Variant::kNoPrecheck: return "/no_precheck";
    case Variant::kStrictContacts: return "/aabb_precheck/strict_contacts";
  }
  return "";
}

Fixture& fixture(const std::string& scene, Variant variant) {
  static std::map<std::pair<std::string, Variant>, Fixture> fixtures;
  Fixture& entry = fixtures[{scene, variant}];
  if (entry.checker) return entry;
  FclCheckerSettings settings;
  settings.boundingBoxPrecheck = variant != Variant::kNoPrecheck;
  if (variant != Variant::kDefault) {
    settings.precomputedMatrices = {fixture(scene, Variant::kDefault).checker->sharedAllowedCollisions(0)};
  }
  Scene world = sceneNamed(scene);
  if (variant == Variant::kStrictContacts) world.setContactTolerance(0.0);
  entry.checker = std::make_unique<FclCollisionChecker>(std::move(world), settings);
  const RobotModel& model = *entry.checker->scene().robots()[0].model;
  Random random(kSeed);
  const auto context = entry.checker->makeContext();
  while (entry.random.size() < kConfigurations || entry.valid.size() < kConfigurations) {
    const VectorX q = random.uniformVector(model.lowerLimits(), model.upperLimits());
    const bool valid = entry.checker->isStateValid(0, q, *context);
    if (entry.random.size() < kConfigurations) entry.random.push_back(q);
    if (valid && entry.valid.size() < kConfigurations) entry.valid.push_back(q);
  }
  addEdges(model, random, entry);
  return entry;
}

/// Stores the median of the default variant of `key`; for another variant, prints its median
/// over the default's as "median_over_default" (the default runs first, in the same process).
void reportRatioToDefault(benchmark::State& state, const std::string& key, Variant variant) {
  static std::map<std::string, double> defaultMedians;
  if (state.counters.count("median_us") == 0) return;
  const double median = state.counters["median_us"];
  if (variant == Variant::kDefault) {
    defaultMedians[key] = median;
  } else if (const auto found = defaultMedians.find(key); found != defaultMedians.end() && found->second > 0.0) {
    state.counters["median_over_default"] = median / found->second;
  }
}

void checkStates(benchmark::State& state, const std::string& scene, Variant variant, bool validOnly) {
  if (scene == "tx90" && !std::filesystem::exists(tx90Problem())) {
    state.SkipWithError(("../shared is absent: " + tx90Problem().string() + " not found").c_str());
    return;
  }
  Fixture& f = fixture(scene, variant);
  const std::vector<VectorX>& configurations = validOnly ? f.valid : f.random;
  const auto context = f.checker->makeContext();
  std::vector<double> times;
  times.reserve(1 << 20);
  std::size_t i = 0;
  int valid = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const bool ok = f.checker->isStateValid(0, configurations[i], *context);
    const auto end = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(ok);
    valid += ok ? 1 : 0;
    if (times.size() < times.capacity()) times.push_back(std::chrono::duration<double, std::micro>(end - start).count());
    i = (i + 1) % configurations.size();
  }
  std::sort(times.begin(), times.end());
  if (!times.empty()) {
    state.counters["median_us"] = times[times.size() / 2];
    state.counters["p95_us"] = times[times.size() * 95 / 100];
  }
  state.counters["valid"] = static_cast<double>(valid) / static_cast<double>(std::max<std::int64_t>(state.iterations(), 1));
  state.counters["pairs"] = static_cast<double>(f.checker->pairCount(0));
  reportRatioToDefault(state, scene + (validOnly ? "/valid" : "/random"), variant);
}

void checkEdges(benchmark::State& state, const std::string& scene, Variant variant) {
  if (scene == "tx90" && !std::filesystem::exists(tx90Problem())) {
    state.SkipWithError(("../shared is absent: " + tx90Problem().string() + " not found").c_str());
    return;
  }
  Fixture& f = fixture(scene, variant);
  const auto context = f.checker->makeContext();
  std::vector<double> times;
  times.reserve(1 << 20);
  std::size_t i = 0;
  int valid = 0;
  double states = 0.0;
  for (auto _ : state) {
    const VectorX& q0 = f.valid[i];
    const VectorX& q1 = f.edgeEnds[i];
    const auto start = std::chrono::steady_clock::now();
    const bool ok = f.checker->isMotionValid(0, q0, q1, kEdgeResolution, *context);
    const auto end = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(ok);
    valid += ok ? 1 : 0;
    states += std::ceil((q1 - q0).cwiseAbs().maxCoeff() / kEdgeResolution) + 1.0;
    if (times.size() < times.capacity()) times.push_back(std::chrono::duration<double, std::micro>(end - start).count());
    i = (i + 1) % f.valid.size();
  }
  std::sort(times.begin(), times.end());
  if (!times.empty()) {
    state.counters["median_us"] = times[times.size() / 2];
    state.counters["p95_us"] = times[times.size() * 95 / 100];
  }
  const double edges = static_cast<double>(std::max<std::int64_t>(state.iterations(), 1));
  state.counters["valid"] = static_cast<double>(valid) / edges;
  state.counters["states_per_edge"] = states / edges;
}

/// How a checker gets the FCL trees of a robot's meshes.
enum class TreeSource { kBuiltPerChecker, kBuiltPerCheckerOnAllCores, kSharedCache };

/// Milliseconds to get the trees of every collision mesh of the TX90 + gripper scene: built
/// anew on one thread (what every checker did before the process-wide cache, the baseline run
/// first), built anew on every core, or found in the cache. Counter median_over_rebuilt.
void meshTrees(benchmark::State& state, TreeSource source) {
  if (!std::filesystem::exists(tx90Problem())) {
    state.SkipWithError(("../shared is absent: " + tx90Problem().string() + " not found").c_str());
    return;
  }
  static double rebuiltMedian = 0.0;
  const Scene scene = sceneNamed("tx90");
  std::vector<MeshGeometry> meshes;
  for (const Link& link : scene.robots().front().model->links()) {
    for (const Shape& shape : link.collisions) {
      if (const auto* mesh = std::get_if<MeshGeometry>(&shape.geometry)) meshes.push_back(*mesh);
    }
  }
  if (source == TreeSource::kSharedCache) {
    for (const MeshGeometry& mesh : meshes) (void)sharedMeshBvh(mesh);  // in the cache before timing
  }
  std::vector<double> times;
  for (auto _ : state) {
    std::vector<MeshGeometry> fresh = meshes;
    if (source != TreeSource::kSharedCache) {
      for (MeshGeometry& mesh : fresh) mesh.mesh = std::make_shared<const TriangleMesh>(*mesh.mesh);
    }
    std::vector<const MeshGeometry*> pointers;
    for (const MeshGeometry& mesh : fresh) pointers.push_back(&mesh);
    const auto start = std::chrono::steady_clock::now();
    prebuildMeshBvhs(pointers, source == TreeSource::kBuiltPerChecker ? 1U : std::thread::hardware_concurrency());
    for (const MeshGeometry& mesh : fresh) benchmark::DoNotOptimize(sharedMeshBvh(mesh));
    times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(times.begin(), times.end());
  const double median = times[times.size() / 2];
  state.counters["median_ms"] = median;
  state.counters["p95_ms"] = times[times.size() * 95 / 100];
  if (source == TreeSource::kBuiltPerChecker) rebuiltMedian = median;
  if (source != TreeSource::kBuiltPerChecker && rebuiltMedian > 0.0) state.counters["median_over_rebuilt"] = median / rebuiltMedian;
}

void registerAll() {
  for (const auto& [name, source] : {std::pair{"MeshTrees/tx90/built_per_checker", TreeSource::kBuiltPerChecker},
                                     std::pair{"MeshTrees/tx90/built_per_checker_on_all_cores", TreeSource::kBuiltPerCheckerOnAllCores},
                                     std::pair{"MeshTrees/tx90/shared_cache", TreeSource::kSharedCache}}) {
    const TreeSource chosen = source;
    benchmark::RegisterBenchmark(name, [chosen](benchmark::State& state) { meshTrees(state, chosen); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(20);
  }
  for (const std::string scene : {"self", "desk", "tx90"}) {
    for (const bool validOnly : {false, true}) {
      for (const Variant variant : {Variant::kDefault, Variant::kNoPrecheck, Variant::kStrictContacts}) {
        if (validOnly && variant == Variant::kStrictContacts) continue;
        const std::string name = "StateCheck/" + scene + (validOnly ? "/valid_states" : "/random_states") +
                                 variantName(variant);
        benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& state) {
          checkStates(state, scene, variant, validOnly);
        })->Unit(benchmark::kMicrosecond);
      }
    }
    for (const Variant variant : {Variant::kDefault, Variant::kNoPrecheck}) {
      const std::string name = "EdgeCheck/" + scene + "/resolution_0.01" + variantName(variant);
      benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& state) {
        checkEdges(state, scene, variant);
      })->Unit(benchmark::kMicrosecond);
    }
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
