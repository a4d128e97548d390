#include <gtest/gtest.h>

#include "lang2manip/core/error.hpp"
#include "model/model_test_support.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/planning/planning_session.hpp"

namespace lang2manip {
namespace {


class PandaDeskSession : public ::testing::Test {
 protected:
  void SetUp() override { session.openProblem(resolveProblem("panda_desk")); }
  PlanningSession session;
};

TEST_F(PandaDeskSession, OpensWithTheFilesPlannerAndQuery) {
  EXPECT_EQ(session.plannerSettings().planner(), "RRTConnect");
  EXPECT_DOUBLE_EQ(session.plannerSettings().maxPlanningTime(), 10.0);
  ASSERT_EQ(session.plannerSettings().omplParameters().size(), 1u);
  EXPECT_EQ(session.pathDofNames().size(), 8u);
}

TEST_F(PandaDeskSession, SolveThenGetPathReturnsTheStoredSolution) {
  EXPECT_NE(test::errorMessage([&] { (void)session.getPath(); }).find("call solve first"), std::string::npos);
  const MotionPlan& plan = session.solve();
  ASSERT_TRUE(plan.solved()) << plan.message;
  const MotionPlan& stored = session.getPath();
  EXPECT_EQ(&stored, &session.getPath());
  EXPECT_EQ(stored.path.size(), plan.path.size());
  EXPECT_GT(session.getNumVertices(), 1);
  EXPECT_GE(session.getNumEdges(), 1);
  EXPECT_GT(session.getLastPlanComputationTime(), 0.0);
  EXPECT_EQ(stored.trajectory.jointNames.front(), "panda/panda_joint1");
}

TEST_F(PandaDeskSession, SolveWithinATimeLimitLeavesThePlannersOwnLimit) {
  const MotionPlan& plan = session.solveWithin(5.0);
  ASSERT_TRUE(plan.solved()) << plan.message;
  EXPECT_DOUBLE_EQ(session.plannerSettings().maxPlanningTime(), 10.0);
  EXPECT_TRUE(session.hasPath());
  session.closeProblem();
  EXPECT_THROW((void)session.solveWithin(5.0), InputError);
}

TEST_F(PandaDeskSession, CollidingQueryIsRejectedAndThePreviousOneKept) {
  const auto& query = session.problem().queries.front();
  std::vector<double> colliding = query.init;
  colliding[1] = 1.0;  // shoulder fully forward: the arm goes through the desk
  colliding[3] = 1.0;
  const std::string message = test::errorMessage([&] { session.setGoal(colliding); });
  EXPECT_NE(message.find("goal is in collision: panda/"), std::string::npos) << message;
  EXPECT_NE(message.find("desk"), std::string::npos) << message;
  const MotionPlan& plan = session.solve();
  ASSERT_TRUE(plan.solved());
  EXPECT_NEAR(plan.path.back()[1], query.goal[1], 1e-9);
}

TEST_F(PandaDeskSession, BadQueriesAndVerbsInTheWrongOrder) {
  EXPECT_NE(test::errorMessage([&] { session.setInit({0.5, 0.5}); }).find("init has 2 values; the planning space has 8"),
            std::string::npos);
  std::vector<double> outside = session.problem().queries.front().init;
  outside[0] = 1.5;
  EXPECT_NE(test::errorMessage([&] { session.setInit(outside); }).find("outside its limits [0, 1]"), std::string::npos);
  EXPECT_NE(test::errorMessage([&] { session.setPlanner("omplFoo"); }).find("valid planners"), std::string::npos);
  EXPECT_NE(test::errorMessage([&] { session.setPlannerParameter("Nope", "1"); }).find("valid parameters"),
            std::string::npos);
  PlanningSession empty;
  EXPECT_NE(test::errorMessage([&] { (void)empty.solve(); }).find("no problem is open"), std::string::npos);
  EXPECT_NE(test::errorMessage([&] { (void)empty.getPath(); }).find("call solve first"), std::string::npos);
  EXPECT_NE(test::errorMessage([&] { empty.openProblem(std::filesystem::path("/nonexistent/problem.xml")); })
                .find("/nonexistent/problem.xml"),
            std::string::npos);
}

TEST_F(PandaDeskSession, ObstacleVerbsEditTheWorld) {
  const Pose original = session.getObstaclePos("eraser");
  Pose moved = original;
  moved.translation().z() += 0.1;
  session.setObstaclePos("eraser", moved);
  EXPECT_TRUE(session.getObstaclePos("eraser").isApprox(moved));
  session.removeObstacle("eraser");
  EXPECT_THROW((void)session.getObstaclePos("eraser"), InputError);
  session.addObstacle(builtinDataDirectory() / "models/obstacles/desk/eraser.urdf", "eraser2", original);
  EXPECT_TRUE(session.getObstaclePos("eraser2").isApprox(original));
  EXPECT_THROW(session.addObstacle(builtinDataDirectory() / "models/obstacles/desk/eraser.urdf", "eraser2",
                                   original),
               InputError);
  const Pose base = session.getRobotPos("panda");
  session.setRobotPos("panda", base);
  EXPECT_TRUE(session.getRobotPos("panda").isApprox(base));
  EXPECT_TRUE(session.solve().solved());
}

TEST_F(PandaDeskSession, AttachedObstacleMovesWithTheHandAndDetaches) {
  session.attachObstacle2RobotLink("panda", "panda_hand", "marker");
  EXPECT_THROW(session.attachObstacle2RobotLink("panda", "panda_hand", "marker"), InputError);
  session.detachObstacle("marker");
  EXPECT_NE(test::errorMessage([&] { session.detachObstacle("marker"); }).find("not attached"), std::string::npos);
}

TEST_F(PandaDeskSession, CheckCollisionAndSetRobotsConfig) {
  const auto& query = session.problem().queries.front();
  EXPECT_TRUE(session.checkCollision(query.init).valid);
  std::vector<double> colliding = query.init;
  colliding[1] = 1.0;
  colliding[3] = 1.0;
  const CollisionReport report = session.checkCollision(colliding);
  EXPECT_FALSE(report.valid);
  EXPECT_FALSE(report.contacts.empty());
  session.setRobotsConfig(query.goal);
  EXPECT_TRUE(session.checkCollision(query.goal).valid);
}

TEST(PlanningSessionBadInput, SolveWithoutAQuery) {
  KauthamProblem problem = readKauthamProblem(resolveProblem("panda_desk"));
  problem.queries.clear();
  PlanningSession session;
  session.openProblem(std::move(problem));
  EXPECT_NE(test::errorMessage([&] { (void)session.solve(); }).find("no query to solve"), std::string::npos);
  EXPECT_NE(test::errorMessage([&] { (void)session.getNumVertices(); }).find("call solve first"), std::string::npos);
}

TEST(KauthamPose, AxisAngleAsKauthamWritesIt) {
  const Pose pose = kauthamPose({1, 2, 3, 0, 0, 1, 1.5707963267948966});
  EXPECT_TRUE(pose.translation().isApprox(Vector3(1, 2, 3)));
  EXPECT_TRUE((pose.linear() * Vector3::UnitX()).isApprox(Vector3::UnitY()));
  EXPECT_THROW((void)kauthamPose({1, 2, 3}), InputError);
  EXPECT_TRUE(kauthamPose({0, 0, 0, 0, 0, 0, 0}).linear().isIdentity(0.0));
  EXPECT_NE(test::errorMessage([] { (void)kauthamPose({0, 0, 0, 0, 0, 0, 1.0}); }).find("zero rotation axis"),
            std::string::npos);
}

TEST_F(PandaDeskSession, PosesFarOutsideTheModelRangeAreRefused) {
  Pose far = session.getObstaclePos("eraser");
  far.translation().x() = 1e300;
  EXPECT_NE(test::errorMessage([&] { session.setObstaclePos("eraser", far); }).find("more than 10000 m"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] { session.setRobotPos("panda", far); }).find("base position of \"panda\""),
            std::string::npos);
  EXPECT_TRUE(session.solve().solved());
}

}  // namespace
}  // namespace lang2manip
