// IK micro-benchmarks under the TRAC-IK protocol (docs/benchmarks.md): random configurations
// within the limits -> FK -> target, solved from the mid-limit seed with a 5 ms budget. For the
// Panda, the iiwa and the UR5: the default solver (dls) and the KDL NR_JL baseline with restarts
// (kdl_restarts) in the same run, plus the allocation-free inner loop (one dls descent from the
// seed) and the chain's pose + Jacobian.
// Counters: median_us and p95_us per call (each call timed alone), success = fraction of calls
// that met the protocol (solvers) or converged (descent).
//
//   build/benchmarks/ik_benchmark [--benchmark_filter=Solve/panda]

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "lang2manip/core/random.hpp"
#include "lang2manip/kinematics/dls_descent.hpp"
#include "lang2manip/kinematics/ik_solver.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/urdf_reader.hpp"

namespace lang2manip {
namespace {

constexpr int kTargets = 2000;
constexpr std::uint64_t kSeed = 7;
constexpr double kBudgetSeconds = 0.005;

/// A robot's first manipulator chain and seeded reachable targets, built once.
struct IkFixture {
  RobotModelPtr model;
  std::unique_ptr<KinematicChain> chain;
  std::vector<IkTarget> targets;
};

IkFixture& fixture(const std::string& robot) {
  static std::map<std::string, IkFixture> fixtures;
  IkFixture& entry = fixtures[robot];
  if (entry.model) return entry;
  UrdfReadOptions read;
  read.loadMeshes = false;
  entry.model = readUrdfFile(builtinRobotUrdf(robot), read);
  const Manipulator& arm = entry.model->semantics().manipulators.front();
  entry.chain = std::make_unique<KinematicChain>(*entry.model, arm.baseLink, arm.toolFrame);
  Random random(kSeed);
  VectorX qc(entry.chain->dof());
  for (int i = 0; i < kTargets; ++i) {
    entry.chain->gather(random.uniformVector(entry.model->lowerLimits(), entry.model->upperLimits()), qc);
    entry.targets.push_back(IkTarget::pose(entry.chain->pose(qc)));
  }
  return entry;
}

/// Records one timed call; returns its time in microseconds.
class Timings {
 public:
  Timings() { times_.reserve(1 << 20); }
  void add(std::chrono::steady_clock::time_point start, bool success) {
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
    if (times_.size() < times_.capacity()) times_.push_back(us);
    successes_ += success ? 1 : 0;
  }
  void report(benchmark::State& state) {
    std::sort(times_.begin(), times_.end());
    if (!times_.empty()) {
      state.counters["median_us"] = times_[times_.size() / 2];
      state.counters["p95_us"] = times_[times_.size() * 95 / 100];
    }
    state.counters["success"] =
        static_cast<double>(successes_) / static_cast<double>(std::max<std::int64_t>(state.iterations(), 1));
  }

 private:
  std::vector<double> times_;
  std::int64_t successes_ = 0;
};

void solve(benchmark::State& state, const std::string& robot, const std::string& solverName) {
  IkFixture& f = fixture(robot);
  const std::unique_ptr<IkSolver> solver = makeIkSolver(solverName);
  IkRequest request;
  request.model = f.model.get();
  request.seed = f.model->middleConfiguration();
  request.timeoutSeconds = kBudgetSeconds;
  Timings timings;
  std::size_t i = 0;
  for (auto _ : state) {
    request.target = f.targets[i];
    request.randomSeed = kSeed + i;
    const auto start = std::chrono::steady_clock::now();
    const IkResult result = solver->solve(request);
    timings.add(start, result.status == IkStatus::kSuccess);
    benchmark::DoNotOptimize(result);
    i = (i + 1) % f.targets.size();
  }
  timings.report(state);
}

/// One dls descent from the mid-limit seed: the allocation-free inner loop alone.
void descent(benchmark::State& state, const std::string& robot) {
  IkFixture& f = fixture(robot);
  const KinematicChain& chain = *f.chain;
  VectorX seed(chain.dof());
  VectorX lower(chain.dof());
  VectorX upper(chain.dof());
  chain.gather(f.model->middleConfiguration(), seed);
  chain.gather(f.model->lowerLimits(), lower);
  chain.gather(f.model->upperLimits(), upper);
  IkProblem problem{*f.model, chain, f.targets[0], seed, lower, upper, StopCondition::never(),
                    1e-5, 1e-5, 1, kSeed};
  DlsWorkspace workspace(chain.dof());
  Timings timings;
  std::size_t i = 0;
  for (auto _ : state) {
    problem.target = f.targets[i];
    IkSearch search(problem);
    workspace.q = seed;
    const auto start = std::chrono::steady_clock::now();
    const bool converged = dlsDescend(problem, workspace, search);
    timings.add(start, converged);
    i = (i + 1) % f.targets.size();
  }
  timings.report(state);
}

void poseAndJacobian(benchmark::State& state, const std::string& robot) {
  IkFixture& f = fixture(robot);
  const KinematicChain& chain = *f.chain;
  VectorX qc(chain.dof());
  chain.gather(f.model->middleConfiguration(), qc);
  Pose pose = Pose::Identity();
  Jacobian6 jacobian(6, chain.dof());
  for (auto _ : state) {
    chain.poseAndJacobian(qc, pose, jacobian);
    benchmark::DoNotOptimize(jacobian.data());
    qc[0] += 1e-9;
  }
}

void registerAll() {
  for (const std::string robot : {"panda", "iiwa14", "ur5"}) {
    for (const std::string solver : {"dls", "kdl_restarts"}) {
      benchmark::RegisterBenchmark(("Solve/" + robot + "/" + solver).c_str(),
                                   [=](benchmark::State& state) { solve(state, robot, solver); })
          ->Unit(benchmark::kMicrosecond);
    }
    benchmark::RegisterBenchmark(("DlsDescentFromSeed/" + robot).c_str(),
                                 [=](benchmark::State& state) { descent(state, robot); })
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("PoseAndJacobian/" + robot).c_str(),
                                 [=](benchmark::State& state) { poseAndJacobian(state, robot); })
        ->Unit(benchmark::kNanosecond);
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
