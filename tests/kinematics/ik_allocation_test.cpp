// The IK inner loop does not allocate: one dls descent from a seed, after a warm-up, counted by
// replacing the global operator new of this test binary (its own executable for that reason),
// and by wrapping malloc/calloc/realloc at link time (-Wl,--wrap: Eigen allocates with malloc,
// not operator new; the static libraries linked here are wrapped too).

#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

#include "kinematics_test_robots.hpp"
#include "lang2manip/core/random.hpp"
#include "lang2manip/kinematics/dls_descent.hpp"

namespace {

std::atomic<long> allocationCount{0};

}  // namespace

extern "C" {
void* __real_malloc(std::size_t size);
void* __real_calloc(std::size_t count, std::size_t size);
void* __real_realloc(void* memory, std::size_t size);

void* __wrap_malloc(std::size_t size) {
  allocationCount.fetch_add(1, std::memory_order_relaxed);
  return __real_malloc(size);
}
void* __wrap_calloc(std::size_t count, std::size_t size) {
  allocationCount.fetch_add(1, std::memory_order_relaxed);
  return __real_calloc(count, size);
}
void* __wrap_realloc(void* memory, std::size_t size) {
  allocationCount.fetch_add(1, std::memory_order_relaxed);
  return __real_realloc(memory, size);
}
}

namespace {

void* countedAllocation(std::size_t size) {
  allocationCount.fetch_add(1, std::memory_order_relaxed);
  if (void* memory = __real_malloc(size == 0 ? 1 : size)) return memory;
  throw std::bad_alloc();
}

void* countedAlignedAllocation(std::size_t size, std::align_val_t alignment) {
  allocationCount.fetch_add(1, std::memory_order_relaxed);
  const auto align = static_cast<std::size_t>(alignment);
  const std::size_t rounded = (size + align - 1) / align * align;
  if (void* memory = std::aligned_alloc(align, rounded == 0 ? align : rounded)) return memory;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t size) { return countedAllocation(size); }
void* operator new[](std::size_t size) { return countedAllocation(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return countedAllocation(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept {
  return operator new(size, tag);
}
void* operator new(std::size_t size, std::align_val_t alignment) {
  return countedAlignedAllocation(size, alignment);
}
void* operator new[](std::size_t size, std::align_val_t alignment) {
  return countedAlignedAllocation(size, alignment);
}
void operator delete(void* memory) noexcept { std::free(memory); }
void operator delete[](void* memory) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t) noexcept { std::free(memory); }
void operator delete[](void* memory, std::size_t) noexcept { std::free(memory); }
void operator delete(void* memory, std::align_val_t) noexcept { std::free(memory); }
void operator delete[](void* memory, std::align_val_t) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t, std::align_val_t) noexcept { std::free(memory); }
void operator delete[](void* memory, std::size_t, std::align_val_t) noexcept { std::free(memory); }

namespace lang2manip::test {
namespace {

/// A solvable problem for robot `name`'s first manipulator: the pose of a random configuration,
/// from the mid-limit seed.
struct DescentSetup {
  explicit DescentSetup(const std::string& name)
      : model(kinematicsRobot(name)),
        chain(model, model.semantics().manipulators.front().baseLink,
              model.semantics().manipulators.front().toolFrame),
        seed(chain.dof()),
        lower(chain.dof()),
        upper(chain.dof()) {
    chain.gather(model.middleConfiguration(), seed);
    chain.gather(model.lowerLimits(), lower);
    chain.gather(model.upperLimits(), upper);
  }

  [[nodiscard]] IkProblem problem(const IkTarget& target) const {
    return IkProblem{model, chain, target, seed, lower, upper, StopCondition::afterSeconds(10.0),
                     1e-5, 1e-5, 1, 1, 0};
  }

  const RobotModel& model;
  KinematicChain chain;
  VectorX seed;
  VectorX lower;
  VectorX upper;
};

TEST(IkAllocation, TheCounterSeesOperatorNewAndEigenAllocations) {
  long before = allocationCount.load();
  auto* number = new double(1.0);
  delete number;
  EXPECT_EQ(allocationCount.load() - before, 1);
  before = allocationCount.load();
  const VectorX vector = VectorX::Zero(50);
  EXPECT_EQ(allocationCount.load() - before, 1);
  EXPECT_EQ(vector.size(), 50);
}

class DlsDescentAllocation : public ::testing::TestWithParam<std::string> {};

TEST_P(DlsDescentAllocation, NoAllocationAfterWarmUp) {
  const DescentSetup setup(GetParam());
  Random random(3);
  std::vector<IkTarget> targets;
  VectorX qc(setup.chain.dof());
  for (int i = 0; i < 50; ++i) {
    setup.chain.gather(random.uniformVector(setup.model.lowerLimits(), setup.model.upperLimits()), qc);
    targets.push_back(IkTarget::pose(setup.chain.pose(qc)));
  }
  targets.push_back(IkTarget::positionAndAxis(targets[0].position, Vector3(0.0, 0.0, -1.0)));
  std::vector<IkProblem> problems;
  for (const IkTarget& target : targets) problems.push_back(setup.problem(target));
  DlsWorkspace workspace(setup.chain.dof());
  {
    IkSearch warmUp(problems[0]);
    workspace.q = setup.seed;
    (void)dlsDescend(problems[0], workspace, warmUp);
  }
  int converged = 0;
  int iterations = 0;
  long allocations = 0;
  for (const IkProblem& problem : problems) {
    IkSearch search(problem);
    workspace.q = setup.seed;
    const long before = allocationCount.load();
    converged += dlsDescend(problem, workspace, search) ? 1 : 0;
    allocations += allocationCount.load() - before;
    iterations += search.result().iterations;
  }
  EXPECT_EQ(allocations, 0);
  // The descents did real work (from the mid-limit seed some fail: the UR5's is singular).
  EXPECT_GT(converged, 0);
  EXPECT_GT(iterations, static_cast<int>(problems.size()));
}

INSTANTIATE_TEST_SUITE_P(BuiltinRobots, DlsDescentAllocation,
                         ::testing::Values("panda", "iiwa14", "ur5", "tx90", "yumi"));

}  // namespace
}  // namespace lang2manip::test
