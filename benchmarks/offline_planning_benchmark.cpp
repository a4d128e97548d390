// Milliseconds for the offline planner to answer an instruction on the Panda's desk, over a set
// of instructions of every kind it understands (steps, several objects, references by quantity,
// property and place). Variants:
//   FirstRound   one plan per instruction (the baseline, registered first);
//   WithRepair   the plan, then the answer to a structured grounding failure of its first pick
//                (the repair loop's second round: another grasp direction);
//   Tabletop10   the benchmarks' families (regions, ordinals, assignments, stacks, lines) on a
//                generated tabletop of 10 objects (6 blocks, 3 bowls, a cylinder) on the Panda's desk.
// Counters: median_ms and p95_ms over all instructions and iterations, and
// median_over_first_round = a variant's median over the baseline's (same process).
//
//   build/benchmarks/offline_planning_benchmark

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "lang2manip/cli/tabletop_scenes.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"

namespace lang2manip {
namespace {

const char* const kInstructions[] = {
    "put the marker and eraser in the holder",
    "put the eraser and the marker into the holder",
    "pick up the marker and put it in the holder",
    "grab the eraser, then drop it into the holder",
    "put both objects in the holder",
    "put all the movable objects in the holder",
    "put the largest object in the holder",
    "put the object closest to the holder in the holder",
    "put the thing on the right into the holder",
    "put the object to the left of the holder in the holder",
    "place the eraser next to the holder",
    "move the marker 5 cm to the left",
    "push the eraser 3 cm forward",
    "put the marker in the holder, then go home",
    "swap the marker and the eraser",
    "put the marker where the eraser is",
    "rotate the eraser by 90 degrees",
    "point the marker at the holder",
    "put everything except the eraser in the holder",
    "hand me the marker",
};

enum class Variant { kFirstRound, kWithRepair, kTabletop };

/// The generated 10-object tabletop (seed 11) and instructions naming its objects.
const Scene& tabletopScene() {
  static const Scene scene = [] {
    Random random(11);
    TabletopRequest request;
    request.blocks = 6;
    request.bowls = 3;
    request.cylinders = 1;
    return *generateTabletop(readKauthamProblem(resolveProblem("panda_desk")).scene, request, random);
  }();
  return scene;
}

std::vector<std::string> tabletopInstructions() {
  const auto words = [](std::string name) {
    std::replace(name.begin(), name.end(), '_', ' ');
    return name;
  };
  const std::vector<std::string> blocks = objectsOfKind(tabletopScene(), "block");
  const std::vector<std::string> bowls = objectsOfKind(tabletopScene(), "bowl");
  return {"put the " + words(blocks[0]) + " in the " + words(bowls[0]),
          "stack all the blocks",
          "put the blocks in the bowls with mismatched colors",
          "pick up the second block from the left and place it on the top right corner",
          "put all the blocks in a horizontal line",
          "put the " + words(blocks[1]) + " in the corner closest to the " + words(bowls[1]),
          "place the " + words(blocks[2]) + " a little to the left of the " + words(bowls[0]),
          "pick up the block closest to the " + words(bowls[2]) + " and place it on the bottom side",
          "put the " + words(blocks[3]) + " on the " + words(blocks[4]),
          "move the " + words(blocks[5]) + " to the middle of the table"};
}

/// A failed round of `plan`: its first pick could not be grasped.
PlanAttempt graspFailureOf(const Plan& plan) {
  PlanAttempt attempt;
  attempt.plan = plan;
  for (std::size_t i = 0; i < plan.actions.size(); ++i) {
    if (plan.actions[i].type != ActionType::kPick) continue;
    attempt.grounding = GroundingFailure{i, "grasp", plan.actions[i].object, "no grasp is reachable", {}};
    break;
  }
  attempt.failure = "no grasp is reachable";
  return attempt;
}

void planTheInstructions(benchmark::State& state, Variant variant) {
  static double firstRoundMedian = 0.0;
  static const Scene desk = readKauthamProblem(resolveProblem("panda_desk")).scene;
  const bool tabletop = variant == Variant::kTabletop;
  const Scene& scene = tabletop ? tabletopScene() : desk;
  const std::vector<std::string> instructions = tabletop ? tabletopInstructions() : std::vector<std::string>(std::begin(kInstructions), std::end(kInstructions));
  OfflineTaskPlanner planner;
  std::vector<double> times;
  int refused = 0;
  for (auto _ : state) {
    for (const std::string& instruction : instructions) {
      PlanningRequest request;
      request.task = instruction;
      request.scene = &scene;
      PlanningStatistics statistics;
      const auto start = std::chrono::steady_clock::now();
      Plan plan;
      try {
        plan = planner.plan(request, StopCondition::never(), statistics);
      } catch (const PlanningError&) {  // a refusal is an answer too, and is timed
        ++refused;
      }
      if (variant == Variant::kWithRepair && graspFailureOf(plan).grounding) {
        request.earlierAttempts.push_back(graspFailureOf(plan));
        plan = planner.plan(request, StopCondition::never(), statistics);
      }
      times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
      benchmark::DoNotOptimize(plan);
    }
  }
  std::sort(times.begin(), times.end());
  const double median = times[times.size() / 2];
  state.counters["median_ms"] = median;
  state.counters["p95_ms"] = times[times.size() * 95 / 100];
  state.counters["refused_per_pass"] = static_cast<double>(refused) / static_cast<double>(state.iterations());
  if (variant == Variant::kFirstRound) firstRoundMedian = median;
  if (variant != Variant::kFirstRound && firstRoundMedian > 0.0) state.counters["median_over_first_round"] = median / firstRoundMedian;
}

}  // namespace
}  // namespace lang2manip

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  using lang2manip::Variant;
  for (const auto& [name, variant] : {std::pair{"OfflinePlanning/FirstRound", Variant::kFirstRound},
                                      std::pair{"OfflinePlanning/WithRepair", Variant::kWithRepair},
                                      std::pair{"OfflinePlanning/Tabletop10", Variant::kTabletop}}) {
    const Variant chosen = variant;
    benchmark::RegisterBenchmark(name, [chosen](benchmark::State& state) { lang2manip::planTheInstructions(state, chosen); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(20);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
