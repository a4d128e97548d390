#include <gtest/gtest.h>

#include <algorithm>

#include "lang2manip/core/error.hpp"
#include "model/model_test_support.hpp"
#include "lang2manip/planning/motion_planner.hpp"
#include "lang2manip/planning/planner_registry.hpp"
#include "planning_test_support.hpp"

namespace lang2manip::test {
namespace {

TEST(PlanarArmProblem, StraightLineCollidesSoPlannersMustGoAround) {
  const auto space = planarArmSpace();
  EXPECT_TRUE(space->isValid(planarStart().data()));
  EXPECT_TRUE(space->isValid(planarGoal().data()));
  EXPECT_FALSE(space->isMotionValid(planarStart().data(), planarGoal().data(), 0.01));
}

TEST(MotionPlanner, SolvesSimplifiesAndReturnsAVerifiedTrajectory) {
  MotionPlanner planner(planarArmSpace());
  PlannerSettings settings;
  settings.setParameter("_Max Planning Time", "5");
  const MotionPlan plan = planner.solve(planarStart(), {planarGoal()}, settings, StopCondition::never());
  ASSERT_TRUE(plan.solved()) << plan.message;
  EXPECT_TRUE(plan.path.front().isApprox(planarStart()));
  EXPECT_TRUE(plan.path.back().isApprox(planarGoal()));
  EXPECT_EQ(planner.verifyPath(plan.path), "");
  // Simplification only shortens; a segment planned again after failing the fine verification
  // (segment repair, rare) may make the final path longer than the planner's.
  if (plan.statistics.repairedSegments == 0) {
    EXPECT_LE(plan.statistics.lengthAfterSimplification, plan.statistics.lengthBeforeSimplification + 1e-9);
  }
  EXPECT_GT(plan.statistics.stateChecks + plan.statistics.motionChecks, 0);
  EXPECT_GT(plan.statistics.vertices, 1);
  ASSERT_FALSE(plan.trajectory.points.empty());
  EXPECT_EQ(checkTrajectoryLimits(planner.space(), plan.trajectory), "");
  EXPECT_TRUE(plan.trajectory.points.back().positions.isApprox(planarGoal()));
  EXPECT_TRUE(plan.trajectory.points.front().velocities.isZero());
  EXPECT_EQ(plan.trajectory.jointNames, (std::vector<std::string>{"planar/shoulder", "planar/elbow"}));
}

TEST(MotionPlanner, SegmentsThatFailTheFineCheckArePlannedAgainNotThePath) {
  // Checked in steps of 3 rad while planning, the straight motion through the post looks free:
  // verification at the fine resolution finds the collision and that segment is planned again.
  MotionPlanningOptions options;
  options.resolution = 3.0;
  MotionPlanner planner(planarArmSpace(), options);
  PlannerSettings settings;
  settings.setParameter("_Simplify Solution", "0");
  const MotionPlan plan = planner.solve(planarStart(), {planarGoal()}, settings, StopCondition::never());
  ASSERT_TRUE(plan.solved()) << plan.message;
  EXPECT_GE(plan.statistics.repairedSegments, 1);
  EXPECT_EQ(plan.statistics.rejectedPaths, 0);
  EXPECT_GT(plan.path.size(), 2u);
  EXPECT_EQ(planner.verifyPath(plan.path), "");
  EXPECT_TRUE(plan.path.front().isApprox(planarStart()));
  EXPECT_TRUE(plan.path.back().isApprox(planarGoal()));
  EXPECT_GT(plan.statistics.lengthAfterSimplification, plan.statistics.lengthBeforeSimplification);
}

TEST(MotionPlanner, EveryValidStateSamplerSolves) {
  for (const char* sampler : {"uniform", "gaussian", "obstacle_based", "bridge_test"}) {
    MotionPlanner planner(planarArmSpace());
    PlannerSettings settings;
    settings.setPlanner("PRM");
    settings.setParameter("_Max Planning Time", std::to_string(0.5 * kTimeLimitScale));
    settings.setParameter("_Valid State Sampler", sampler);
    const MotionPlan plan = planner.solve(planarStart(), {planarGoal()}, settings, StopCondition::never());
    EXPECT_TRUE(plan.solved()) << sampler << ": " << plan.message;
  }
}

TEST(MotionPlanner, RecordsTheExplorationTreeWhenAsked) {
  MotionPlanner plain(planarArmSpace());
  EXPECT_TRUE(plain.solve(planarStart(), {planarGoal()}, PlannerSettings{}, StopCondition::never()).tree.vertices.empty());
  MotionPlanningOptions options;
  options.recordTreeEdges = 5;
  MotionPlanner planner(planarArmSpace(), options);
  const MotionPlan plan = planner.solve(planarStart(), {planarGoal()}, PlannerSettings{}, StopCondition::never());
  ASSERT_TRUE(plan.solved()) << plan.message;
  EXPECT_EQ(static_cast<long>(plan.tree.vertices.size()), plan.statistics.vertices);
  EXPECT_EQ(plan.tree.edges.size() + plan.tree.omittedEdges, static_cast<std::size_t>(plan.statistics.edges));
  EXPECT_LE(plan.tree.edges.size(), 5U);
  for (const auto& [from, to] : plan.tree.edges) {
    EXPECT_LT(static_cast<std::size_t>(std::max(from, to)), plan.tree.vertices.size());
  }
  for (const VectorX& vertex : plan.tree.vertices) EXPECT_EQ(vertex.size(), 2);
}

TEST(MotionPlanner, AcceptsSeveralGoalsAndReachesOneOfThem) {
  MotionPlanner planner(planarArmSpace());
  VectorX other(2);
  other << -1.0, 0.5;
  const MotionPlan plan = planner.solve(planarStart(), {planarGoal(), other}, PlannerSettings{},
                                        StopCondition::never());
  ASSERT_TRUE(plan.solved()) << plan.message;
  EXPECT_TRUE(plan.path.back().isApprox(planarGoal()) || plan.path.back().isApprox(other));
}

TEST(MotionPlanner, UnreachableGoalIsANoPathResultNotAnError) {
  // Goal enclosed: the arm's tip inside a ring of posts is unreachable from outside.
  Scene scene = planarArmScene();
  SceneObject wall = scene.object("post");
  wall.name = "wall";
  wall.pose.translation() = Vector3(0.0, 0.0, 0.0);
  wall.collisions = {Shape{Box{Vector3(0.02, 0.02, 0.4)}, Pose::Identity(), std::nullopt, "w"}};
  // A thin pillar hugging the base blocks every rotation of the upper link past it.
  wall.pose.translation() = Vector3(0.3, -0.05, 0.0);
  scene.addObject(wall);
  auto checker = std::make_shared<FclCollisionChecker>(scene);
  auto space = std::make_shared<JointPlanningSpace>(checker, std::vector<std::string>{"planar"});
  VectorX start(2), goal(2);
  start << 0.5, 0.0;
  goal << -0.5, 0.0;
  ASSERT_TRUE(space->isValid(start.data()));
  ASSERT_TRUE(space->isValid(goal.data()));
  MotionPlanner planner(space);
  PlannerSettings settings;
  settings.setParameter("_Max Planning Time", "0.2");
  const MotionPlan plan = planner.solve(start, {goal}, settings, StopCondition::never());
  EXPECT_EQ(plan.status, MotionPlanStatus::kNoPath);
  EXPECT_NE(plan.message.find("no path found in 0.2 s by RRTConnect"), std::string::npos) << plan.message;
  EXPECT_TRUE(plan.trajectory.points.empty());
}

TEST(MotionPlanner, CancelledSolveStops) {
  MotionPlanner planner(planarArmSpace());
  auto flag = std::make_shared<std::atomic<bool>>(true);
  const MotionPlan plan = planner.solve(planarStart(), {planarGoal()}, PlannerSettings{},
                                        StopCondition::onCancel(flag));
  EXPECT_EQ(plan.status, MotionPlanStatus::kStopped);
}

TEST(MotionPlannerBadInput, EndpointsAreCheckedWithClearMessages) {
  MotionPlanner planner(planarArmSpace());
  const PlannerSettings settings;
  const auto stop = StopCondition::never();
  VectorX colliding(2);
  colliding << 0.0, 0.0;  // stretched through the post
  EXPECT_NE(test::errorMessage([&] { (void)planner.solve(colliding, {planarGoal()}, settings, stop); })
                .find("start is in collision: planar/fore touches post"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] { (void)planner.solve(planarStart(), {colliding}, settings, stop); })
                .find("goal is in collision"),
            std::string::npos);
  VectorX outside(2);
  outside << 3.5, 0.0;
  EXPECT_NE(test::errorMessage([&] { (void)planner.solve(outside, {planarGoal()}, settings, stop); })
                .find("start: planar/shoulder = 3.5"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] { (void)planner.solve(VectorX::Zero(3), {planarGoal()}, settings, stop); })
                .find("start has 3 values; the planning space has 2 (planar/shoulder, planar/elbow)"),
            std::string::npos);
  VectorX nan(2);
  nan << std::nan(""), 0.0;
  EXPECT_NE(test::errorMessage([&] { (void)planner.solve(planarStart(), {nan}, settings, stop); })
                .find("not a finite number"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] { (void)planner.solve(planarStart(), {}, settings, stop); }).find("no goal"),
            std::string::npos);
}

}  // namespace
}  // namespace lang2manip::test

namespace lang2manip::test {
namespace {

TEST(MultiRobotPlanning, TwoArmsPlannedTogetherAvoidEachOther) {
  Scene scene = planarArmScene();
  SceneRobot second = scene.robot("planar");
  second.name = "planar2";
  second.basePose.translation() = Vector3(1.4, 0.0, 0.0);
  second.configuration << 2.0, 0.0;
  scene.addRobot(second);
  scene.removeObject("post");
  auto checker = std::make_shared<FclCollisionChecker>(scene);
  auto space = std::make_shared<JointPlanningSpace>(checker, std::vector<std::string>{"planar", "planar2"});
  ASSERT_EQ(space->dimension(), 4);
  // Both arms swing from pointing up to pointing at each other's base and back again: moved
  // together in a straight line, their forearms would cross.
  const VectorX start = (VectorX(4) << 0.0, 0.0, 3.0, 0.0).finished();
  const VectorX goal = (VectorX(4) << 1.4, 0.0, 1.7, 0.0).finished();
  ASSERT_TRUE(space->isValid(start.data()));
  ASSERT_TRUE(space->isValid(goal.data()));
  MotionPlanner planner(space);
  const MotionPlan plan = planner.solve(start, {goal}, PlannerSettings{}, StopCondition::never());
  ASSERT_TRUE(plan.solved()) << plan.message;
  EXPECT_EQ(planner.verifyPath(plan.path), "");
  EXPECT_EQ(plan.trajectory.jointNames,
            (std::vector<std::string>{"planar/shoulder", "planar/elbow", "planar2/shoulder", "planar2/elbow"}));
  const WorldState world = space->worldState(goal);
  EXPECT_DOUBLE_EQ(world.configurations[1][0], 1.7);
}

}  // namespace
}  // namespace lang2manip::test

namespace lang2manip::test {
namespace {

TEST(PositionMargin, PlannedBoxIsTheLimitsMovedInwardAndWidenedToTheRestingPoints) {
  const auto space = planarArmSpace();  // shoulder in [-3, 3], elbow in [-2.5, 2.5]
  const StateBounds limits = space->plannedBounds(PositionMargin{0.0, 0.0}, {});
  EXPECT_TRUE(limits.lower.isApprox(space->lower()));
  EXPECT_TRUE(limits.upper.isApprox(space->upper()));
  const StateBounds margin = space->plannedBounds(PositionMargin{0.2, 0.01}, {});
  EXPECT_TRUE(margin.lower.isApprox((VectorX(2) << -2.8, -2.3).finished()));
  EXPECT_TRUE(margin.upper.isApprox((VectorX(2) << 2.8, 2.3).finished()));
  // A margin is at most a tenth of the joint's range (6 and 5 rad here).
  const StateBounds capped = space->plannedBounds(PositionMargin{2.0, 0.01}, {});
  EXPECT_TRUE(capped.lower.isApprox((VectorX(2) << -2.4, -2.0).finished()));
  // A start at a limit widens the box of that joint to it, and of no other.
  const VectorX start = (VectorX(2) << 3.0, 0.0).finished();
  const StateBounds widened = space->plannedBounds(PositionMargin{0.2, 0.01}, {start});
  EXPECT_DOUBLE_EQ(widened.upper[0], 3.0);
  EXPECT_DOUBLE_EQ(widened.upper[1], 2.3);
  EXPECT_DOUBLE_EQ(widened.lower[0], -2.8);
}

bool insideBox(const VectorX& x, const StateBounds& box) {
  return (x.array() >= box.lower.array() - 1e-9).all() && (x.array() <= box.upper.array() + 1e-9).all();
}

TEST(PositionMargin, EveryPlannedStateAndTrajectorySampleKeepsTheMargin) {
  MotionPlanningOptions options;
  options.positionMargin = PositionMargin{0.5, 0.01};
  const auto space = planarArmSpace();
  const StateBounds box = space->plannedBounds(options.positionMargin, {});
  for (const std::string planner : {"RRTConnect", "PRM", "KPIECE1"}) {
    SCOPED_TRACE(planner);
    MotionPlanner motion(space, options);
    PlannerSettings settings;
    settings.setPlanner(planner);
    settings.setParameter("_Max Planning Time", "5");
    const MotionPlan plan = motion.solve(planarStart(), {planarGoal()}, settings, StopCondition::never());
    ASSERT_TRUE(plan.solved()) << plan.message;
    for (const VectorX& point : plan.rawPath) EXPECT_TRUE(insideBox(point, box)) << point.transpose();
    for (const VectorX& point : plan.path) EXPECT_TRUE(insideBox(point, box)) << point.transpose();
    for (const TrajectoryPoint& sample : plan.trajectory.points) {
      EXPECT_TRUE(insideBox(sample.positions, box)) << sample.positions.transpose();
    }
  }
}

/// The planar arm with a pillar by its base that no rotation of the upper link passes: from
/// shoulder 0.5 to -0.5 there is no path, so a planner explores its whole region until its limit.
std::shared_ptr<const PlanningSpace> pillarSpace() {
  Scene scene = planarArmScene();
  SceneObject pillar = scene.object("post");
  pillar.name = "pillar";
  pillar.pose.translation() = Vector3(0.3, -0.05, 0.0);
  pillar.collisions = {Shape{Box{Vector3(0.02, 0.02, 0.4)}, Pose::Identity(), std::nullopt, "pillar"}};
  scene.addObject(pillar);
  return std::make_shared<JointPlanningSpace>(std::make_shared<FclCollisionChecker>(scene),
                                              std::vector<std::string>{"planar"});
}

TEST(PositionMargin, ExplorationStaysOutOfTheMarginAndGoesThereWithout) {
  const VectorX start = (VectorX(2) << 0.5, 0.0).finished();
  const VectorX goal = (VectorX(2) << -0.5, 0.0).finished();
  PlannerSettings settings;
  settings.setParameter("_Max Planning Time", "0.2");
  const auto exploredOutside = [&](const PositionMargin& margin) {
    MotionPlanningOptions options;
    options.positionMargin = margin;
    options.recordTreeEdges = 1;
    MotionPlanner motion(pillarSpace(), options);
    const MotionPlan plan = motion.solve(start, {goal}, settings, StopCondition::never());
    EXPECT_EQ(plan.status, MotionPlanStatus::kNoPath);
    EXPECT_GT(plan.tree.vertices.size(), 100U);
    const StateBounds box = motion.space().plannedBounds(PositionMargin{0.5, 0.01}, {start, goal});
    return std::count_if(plan.tree.vertices.begin(), plan.tree.vertices.end(),
                         [&](const VectorX& vertex) { return !insideBox(vertex, box); });
  };
  EXPECT_EQ(exploredOutside(PositionMargin{0.5, 0.01}), 0);
  EXPECT_GT(exploredOutside(PositionMargin{0.0, 0.0}), 0);
}

TEST(PositionMargin, AStartInsideTheMarginIsPlannedFrom) {
  MotionPlanningOptions options;
  options.positionMargin = PositionMargin{0.5, 0.01};
  MotionPlanner motion(planarArmSpace(), options);
  const VectorX start = (VectorX(2) << 2.9, 2.4).finished();  // both joints inside the margin
  ASSERT_TRUE(motion.space().isValid(start.data()));
  const MotionPlan plan = motion.solve(start, {planarGoal()}, PlannerSettings{}, StopCondition::never());
  ASSERT_TRUE(plan.solved()) << plan.message;
  EXPECT_TRUE(plan.path.front().isApprox(start));
  EXPECT_EQ(checkTrajectoryLimits(motion.space(), plan.trajectory), "");
}

}  // namespace
}  // namespace lang2manip::test
