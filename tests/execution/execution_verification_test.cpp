// The verification before success is reported: a motion that enters an obstacle, an object that
// moved without being acted on, and a goal that does not hold each make the run fail.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "execution_test_support.hpp"
#include "lang2manip/execution/execution_verification.hpp"
#include "lang2manip/execution/motion_timing.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;

Goal markerInHolder() {
  Goal goal;
  goal.object = "marker";
  goal.relation = SpatialRelation::kIn;
  goal.target = "holder";
  return goal;
}

class Verification : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto failure = executor_.execute(planOf({pickAction("marker"), placeAction("marker", SpatialRelation::kIn, "holder")}),
                                           StopCondition::never());
    ASSERT_FALSE(failure.has_value()) << failure->reason;
    record_ = executor_.lastExecution();
  }
  TaskExecutor executor_{deskScene("panda"), testSettings()};
  ExecutionRecord record_;
};

TEST_F(Verification, AnExecutedPlanIsVerified) {
  const ExecutionVerification v = verifyExecution(executor_.arm(), executor_.initialScene(), record_, {markerInHolder()});
  EXPECT_TRUE(v.success) << v.collision;
  EXPECT_TRUE(v.goals.front().holds);
}

/// True when every contact of the arm at `q` is with the desk (none when `mustTouch` is false).
bool touchesOnlyTheDesk(const CollisionChecker& checker, CollisionContext& context, int robot, const VectorX& q,
                        bool mustTouch) {
  const auto contacts = checker.checkState(robot, q, {}, context).contacts;
  for (const CollisionContact& c : contacts) {
    if (c.second != "desk" && c.first != "desk") return false;
  }
  return !mustTouch || !contacts.empty();
}

/// A configuration touching the desk and nothing else, reached from `before` and left toward
/// `after` along straight joint-space lines that touch nothing but the desk, so that the first
/// collision on the modified motion is the desk whatever path the planner found (seeded search).
VectorX configurationInTheDesk(const ArmContext& arm, const Scene& world, const VectorX& before, const VectorX& after) {
  const auto checker = arm.checkerFor(world);
  const auto context = checker->makeContext();
  const int robot = checker->robotIndex(arm.robotName());
  const auto legTouchesOnlyTheDesk = [&](const VectorX& from, const VectorX& to) {
    for (int i = 0; i <= 200; ++i) {
      const double t = i / 200.0;
      if (!touchesOnlyTheDesk(*checker, *context, robot, (1.0 - t) * from + t * to, false)) return false;
    }
    return true;
  };
  std::uint64_t state = 12345;
  VectorX q = after;
  for (int attempt = 0; attempt < 20000; ++attempt) {
    for (int v : arm.armVariables()) {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      const double u = static_cast<double>(state >> 11) / 9007199254740992.0;
      q[v] = arm.model().lowerLimits()[v] + u * (arm.model().upperLimits()[v] - arm.model().lowerLimits()[v]);
    }
    if (touchesOnlyTheDesk(*checker, *context, robot, q, true) && legTouchesOnlyTheDesk(before, q) &&
        legTouchesOnlyTheDesk(q, after)) {
      return q;
    }
  }
  ADD_FAILURE() << "no configuration touching only the desk found";
  return q;
}

TEST_F(Verification, AMotionThroughTheDeskIsFound) {
  MotionSegment& transit = record_.actions[1].segments.front();
  ASSERT_GE(transit.waypoints.size(), 2u);
  const VectorX inTheDesk = configurationInTheDesk(executor_.arm(), transit.world, *(transit.waypoints.end() - 2), transit.waypoints.back());
  transit.waypoints.insert(transit.waypoints.end() - 1, inTheDesk);
  const ExecutionVerification changed = verifyExecution(executor_.arm(), executor_.initialScene(), record_, {markerInHolder()});
  EXPECT_FALSE(changed.success);
  EXPECT_THAT(changed.collision, HasSubstr("the motion was changed after it was timed"));
  record_.actions[1].runs = timeActionMotions(executor_.arm(), record_.actions[1].segments).runs;
  const ExecutionVerification v = verifyExecution(executor_.arm(), executor_.initialScene(), record_, {markerInHolder()});
  EXPECT_FALSE(v.success);
  EXPECT_THAT(v.collision, HasSubstr("step 2 (place marker in holder)"));
  EXPECT_THAT(v.collision, HasSubstr("transit holding marker"));
  EXPECT_THAT(v.collision, HasSubstr("desk"));
}

TEST_F(Verification, AnObjectMovedByNoActionIsReported) {
  record_.finalScene.object("eraser").pose.translation().x() += 0.01;
  const ExecutionVerification v = verifyExecution(executor_.arm(), executor_.initialScene(), record_, {markerInHolder()});
  EXPECT_FALSE(v.success);
  ASSERT_EQ(v.disturbedObjects.size(), 1u);
  EXPECT_THAT(v.disturbedObjects.front(), HasSubstr("eraser moved by 0.0100 m"));
}

TEST_F(Verification, AGoalThatDoesNotHoldFailsTheRun) {
  Goal eraser = markerInHolder();
  eraser.object = "eraser";
  const ExecutionVerification v = verifyExecution(executor_.arm(), executor_.initialScene(), record_, {markerInHolder(), eraser});
  EXPECT_FALSE(v.success);
  EXPECT_FALSE(v.goals[1].holds);
  EXPECT_THAT(v.goals[1].explanation, HasSubstr("eraser"));
  EXPECT_FALSE(verifyExecution(executor_.arm(), executor_.initialScene(), record_, {}).success) << "no goal, no success";
}

TEST(GoalsImpliedByPlan, LastPlacementPushesHoldingConfigurationAndPositions) {
  SymbolicAction placeAtPose;
  placeAtPose.type = ActionType::kPlace;
  placeAtPose.object = "eraser";
  placeAtPose.params.position = Vector3(0.3, 0.0, 0.0);
  const Plan plan = planOf({pickAction("marker"), placeAction("marker", SpatialRelation::kOn, "desk"), pickAction("marker"),
                            placeAction("marker", SpatialRelation::kIn, "holder"), pushAction("eraser", Vector3(0, 2, 0), 0.05),
                            pickAction("eraser"), moveHomeAction()});
  const std::vector<Goal> goals = goalsImpliedByPlan(plan);
  ASSERT_EQ(goals.size(), 4u);
  EXPECT_EQ(describeGoal(goals[0]), "marker in holder");
  EXPECT_EQ(goals[1].kind, GoalKind::kDisplaced);
  EXPECT_NEAR(goals[1].displacement.y(), 0.05, 1e-12);
  EXPECT_EQ(goals[2].kind, GoalKind::kHolding);
  EXPECT_EQ(goals[3].kind, GoalKind::kAtConfiguration);
  // A place at a position: the object stands there at the end.
  const std::vector<Goal> atPose = goalsImpliedByPlan(planOf({pickAction("eraser"), placeAtPose}));
  ASSERT_EQ(atPose.size(), 1u);
  EXPECT_EQ(atPose[0].kind, GoalKind::kAtPosition);
  EXPECT_TRUE(atPose[0].position->isApprox(Vector3(0.3, 0.0, 0.0)));
}

}  // namespace
}  // namespace lang2manip::test
