#include <gtest/gtest.h>

#include <atomic>
#include <memory>

#include "lang2manip/language/offline_task_planner.hpp"
#include "language/language_test_scenes.hpp"

namespace lang2manip {
namespace {

PlanningRequest requestFor(const Scene& scene, const std::string& task) {
  PlanningRequest request;
  request.task = task;
  request.scene = &scene;
  return request;
}

std::string planningErrorOf(OfflineTaskPlanner& planner, const PlanningRequest& request,
                            const StopCondition& stop = StopCondition::never()) {
  PlanningStatistics statistics;
  try {
    (void)planner.plan(request, stop, statistics);
  } catch (const PlanningError& error) {
    return error.what();
  }
  return "no error";
}

PlanAttempt graspFailure(const std::string& object) {
  return {"{\"actions\":[]}", "action 2 (pick " + object + "): no collision-free grasp of " +
                                  object + " found"};
}

TEST(OfflineTaskPlannerTest, PlansThePaperTaskOnEveryBuiltInDesk) {
  OfflineTaskPlanner planner;
  EXPECT_EQ(planner.name(), "offline");
  const Scene scene = test::deskScene();
  PlanningStatistics statistics;
  const Plan plan = planner.plan(requestFor(scene, "put the marker and eraser in the holder"),
                                 StopCondition::never(), statistics);
  ASSERT_EQ(plan.actions.size(), 4u);
  EXPECT_EQ(plan.actions[0].type, ActionType::kPick);
  EXPECT_EQ(plan.actions[0].object, "marker");
  EXPECT_EQ(plan.actions[1].type, ActionType::kPlace);
  EXPECT_EQ(plan.actions[1].params.target, "holder");
  EXPECT_EQ(plan.actions[2].object, "eraser");
  EXPECT_EQ(plan.actions[3].params.relation, SpatialRelation::kIn);
  EXPECT_EQ(statistics.llmCalls, 0);
  EXPECT_GE(statistics.planningSeconds, 0.0);
}

TEST(OfflineTaskPlannerTest, RequestWithoutSceneIsAnError) {
  OfflineTaskPlanner planner;
  PlanningRequest request;
  request.task = "go home";
  EXPECT_NE(planningErrorOf(planner, request).find("the request has no scene"), std::string::npos);
}

TEST(OfflineTaskPlannerTest, UnknownRobotIsAnError) {
  OfflineTaskPlanner planner;
  const Scene scene = test::deskScene();
  PlanningRequest request = requestFor(scene, "go home");
  request.robot = "r2d2";
  const std::string message = planningErrorOf(planner, request);
  EXPECT_NE(message.find("offline planner: "), std::string::npos) << message;
  EXPECT_NE(message.find("r2d2"), std::string::npos) << message;
  request.robot = scene.robots().front().name;
  EXPECT_EQ(planningErrorOf(planner, request), "no error");
}

TEST(OfflineTaskPlannerTest, StoppedBeforePlanningIsAnError) {
  OfflineTaskPlanner planner;
  const Scene scene = test::deskScene();
  auto flag = std::make_shared<std::atomic<bool>>(true);
  EXPECT_NE(planningErrorOf(planner, requestFor(scene, "go home"), StopCondition::onCancel(flag))
                .find("stopped"),
            std::string::npos);
}

TEST(OfflineTaskPlannerTest, UngroundableTaskNamesTheWords) {
  OfflineTaskPlanner planner;
  const Scene scene = test::deskScene();
  EXPECT_NE(planningErrorOf(planner, requestFor(scene, "put the cactus in the holder"))
                .find("could not ground \"the cactus\""),
            std::string::npos);
}

TEST(OfflineTaskPlannerTest, GraspFailuresLeadToOtherGraspDirections) {
  OfflineTaskPlanner planner;
  const Scene scene = test::deskScene();
  PlanningRequest request = requestFor(scene, "put the marker and eraser in the holder");
  PlanningStatistics statistics;
  const std::vector<GraspDirection> order = graspRetryOrder();
  for (std::size_t failures = 1; failures < order.size(); ++failures) {
    request.earlierAttempts.push_back(graspFailure("eraser"));
    const Plan plan = planner.plan(request, StopCondition::never(), statistics);
    ASSERT_EQ(plan.actions.size(), 4u);
    EXPECT_EQ(plan.actions[0].refinements.grasp, GraspDirection::kAuto);
    EXPECT_EQ(plan.actions[2].refinements.grasp, order[failures]) << failures;
  }
  request.earlierAttempts.push_back(graspFailure("eraser"));
  EXPECT_NE(planningErrorOf(planner, request)
                .find("nothing new to try: every grasp direction of eraser has failed"),
            std::string::npos);
}

TEST(OfflineTaskPlannerTest, RequestedGraspIsNotOverridden) {
  OfflineTaskPlanner planner;
  const Scene scene = test::deskScene();
  PlanningRequest request = requestFor(scene, "put the marker in the holder with a side grasp");
  request.earlierAttempts.push_back(graspFailure("marker"));
  EXPECT_NE(planningErrorOf(planner, request)
                .find("nothing new to try: the instruction asks for a side grasp of marker"),
            std::string::npos);
}

TEST(OfflineTaskPlannerTest, FailureItCannotAnswerIsAnError) {
  OfflineTaskPlanner planner;
  const Scene scene = test::deskScene();
  PlanningRequest request = requestFor(scene, "put the marker in the holder");
  request.earlierAttempts.push_back({"{}", "action 1: no collision-free path within 10 s"});
  const std::string message = planningErrorOf(planner, request);
  EXPECT_NE(message.find("nothing new to try"), std::string::npos) << message;
  EXPECT_NE(message.find("no collision-free path within 10 s"), std::string::npos) << message;
}

TEST(OfflineTaskPlannerTest, RoomOfContainersComesFromTheirCavities) {
  const SequencingOptions options = sequencingOptionsFor(test::deskScene());
  EXPECT_NEAR(options.containerFloorArea.at("holder"), 0.0564 * 0.0564, 1e-9);
  EXPECT_NEAR(options.objectFootprint.at("marker"), 0.018 * 0.018, 1e-9);
  EXPECT_NEAR(options.objectFootprint.at("eraser"), 0.015 * 0.02, 1e-9);
  EXPECT_EQ(options.objectFootprint.count("desk"), 0u);
}

}  // namespace
}  // namespace lang2manip
