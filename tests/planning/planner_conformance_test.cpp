// Every registered planner on the planar-arm problem: statistically, at least 9 of 10 runs solve
// it, and every returned trajectory is verified and within limits.
#include <gtest/gtest.h>

#include "lang2manip/planning/motion_planner.hpp"
#include "lang2manip/planning/planner_registry.hpp"
#include "planning_test_support.hpp"

namespace lang2manip::test {
namespace {

class PlannerConformance : public ::testing::TestWithParam<std::string> {};

// The statistics are measured in the optimized build. The sanitized Debug build (where checks
// run several hundred times slower) runs each planner once with a long limit, to put every
// planner's code path under AddressSanitizer, and checks whatever it returns.
TEST_P(PlannerConformance, SolvesNineOfTenRunsWithVerifiedTrajectories) {
  const auto space = planarArmSpace();
  // The post is thin next to the arm's reach: plan at a fine step so that few paths graze it
  // (LBTRRT always uses its whole time, leaving none to plan again after a rejected path).
  MotionPlanningOptions options;
  options.resolution = 0.01;
  MotionPlanner planner(space, options);
  PlannerSettings settings;
  settings.setPlanner(GetParam());
  settings.setParameter("_Max Planning Time", kSanitizedBuild ? "30" : "1");
  const int runs = kSanitizedBuild ? 1 : 10;
  int solved = 0;
  std::string failures;
  for (int run = 0; run < runs; ++run) {
    const MotionPlan plan = planner.solve(planarStart(), {planarGoal()}, settings, StopCondition::never());
    if (!plan.solved()) {
      failures += "\n  run " + std::to_string(run + 1) + ": " + plan.message;
      continue;
    }
    ++solved;
    EXPECT_EQ(planner.verifyPath(plan.path), "");
    EXPECT_EQ(checkTrajectoryLimits(*space, plan.trajectory), "");
    EXPECT_TRUE(plan.trajectory.points.back().positions.isApprox(planarGoal(), 1e-9));
  }
  if (!kSanitizedBuild) {
    EXPECT_GE(solved, 9) << GetParam() << " failed:" << failures;
  }
}

INSTANTIATE_TEST_SUITE_P(EveryPlanner, PlannerConformance, ::testing::ValuesIn(plannerNames()),
                         [](const auto& param) { return param.param; });

}  // namespace
}  // namespace lang2manip::test
