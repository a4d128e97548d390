#include <gtest/gtest.h>

#include <atomic>
#include <memory>

#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/model/urdf_reader.hpp"

#include <filesystem>
#include "language/language_test_support.hpp"
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

/// A round as the repair loop reports it: `plan` was tried and its first action on `object`
/// failed at `stage`. The words name nothing: the offline planner reads the data.
PlanAttempt groundingFailure(const Plan& plan, const std::string& object, const std::string& stage = "grasp",
                             const std::vector<std::string>& blockers = {}) {
  PlanAttempt attempt;
  attempt.answer = "{}";
  attempt.failure = "words the planner does not read";
  attempt.plan = plan;
  std::size_t index = 0;
  while (index < plan.actions.size() && plan.actions[index].object != object) ++index;
  attempt.grounding = GroundingFailure{index, stage, object, "the reason in words", blockers};
  return attempt;
}

Plan firstPlan(OfflineTaskPlanner& planner, const PlanningRequest& request) {
  PlanningStatistics statistics;
  return planner.plan(request, StopCondition::never(), statistics);
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
  Plan tried = firstPlan(planner, request);
  for (std::size_t failures = 1; failures < order.size(); ++failures) {
    // Failures at any stage of an action on a picked object: another grasp may fix them (a
    // placement no pose of which is reachable too: the object is held differently).
    const char* stage = failures == 1 ? "grasp" : failures == 2 ? "motion" : "placement";
    request.earlierAttempts.push_back(groundingFailure(tried, "eraser", stage));
    const Plan plan = planner.plan(request, StopCondition::never(), statistics);
    ASSERT_EQ(plan.actions.size(), 4u);
    EXPECT_EQ(plan.actions[0].refinements.grasp, GraspDirection::kAuto);
    EXPECT_EQ(plan.actions[2].refinements.grasp, order[failures]) << failures;
    tried = plan;
  }
  request.earlierAttempts.push_back(groundingFailure(tried, "eraser"));
  EXPECT_NE(planningErrorOf(planner, request)
                .find("nothing new to try: every grasp direction of eraser has failed"),
            std::string::npos);
}

TEST(OfflineTaskPlannerTest, RequestedGraspIsNotOverridden) {
  OfflineTaskPlanner planner;
  const Scene scene = test::deskScene();
  PlanningRequest request = requestFor(scene, "put the marker in the holder with a side grasp");
  request.earlierAttempts.push_back(groundingFailure(firstPlan(planner, request), "marker"));
  EXPECT_NE(planningErrorOf(planner, request)
                .find("nothing new to try: the instruction asks for a side grasp of marker"),
            std::string::npos);
}

TEST(OfflineTaskPlannerTest, FailureItCannotAnswerIsAnError) {
  OfflineTaskPlanner planner;
  const Scene scene = test::deskScene();
  PlanningRequest request = requestFor(scene, "put the marker in the holder");
  // A failure in words only (an invalid plan, an unusable answer): nothing is parsed out of it,
  // even when the words mention a grasp of an object.
  PlanAttempt words;
  words.failure = "step 1 (pick marker): no collision-free grasp of marker";
  request.earlierAttempts = {words};
  std::string message = planningErrorOf(planner, request);
  EXPECT_NE(message.find("nothing new to try: the failure is not one of executing its plan"), std::string::npos) << message;
  EXPECT_NE(message.find("no collision-free grasp of marker"), std::string::npos) << message;

  const Plan plan = firstPlan(planner, requestFor(scene, "put the marker in the holder"));
  request.earlierAttempts = {groundingFailure(plan, "marker", "precondition")};
  message = planningErrorOf(planner, request);
  EXPECT_NE(message.find("the plan asks for something the world does not allow"), std::string::npos) << message;
  request.earlierAttempts = {groundingFailure(plan, "marker", "placement", {"eraser", "block"})};
  message = planningErrorOf(planner, request);
  EXPECT_NE(message.find("every position for marker is taken by eraser, block"), std::string::npos) << message;
  request.earlierAttempts = {groundingFailure(plan, "holder", "motion")};
  message = planningErrorOf(planner, request);
  EXPECT_NE(message.find("the failure is not about an object the plan picks"), std::string::npos) << message;
}

/// `attempt` failing at the place of `object` (its second action on it), blocked by `blockers`.
PlanAttempt blockedPlacement(const Plan& plan, const std::string& object, const std::vector<std::string>& blockers) {
  PlanAttempt attempt = groundingFailure(plan, object, "placement", blockers);
  std::size_t index = attempt.grounding->actionIndex + 1;
  while (index < plan.actions.size() && plan.actions[index].object != object) ++index;
  attempt.grounding->actionIndex = index;
  return attempt;
}

TEST(OfflineTaskPlannerTest, APlacementBlockedByWhatThePlanPutThereFirstIsTriedInTheOtherOrder) {
  OfflineTaskPlanner planner;
  const Scene scene = test::deskScene();
  PlanningRequest request = requestFor(scene, "put the marker and the eraser in the holder");
  const Plan first = firstPlan(planner, request);
  ASSERT_EQ(first.actions.size(), 4u);
  ASSERT_EQ(first.actions[0].object, "marker");
  request.earlierAttempts = {blockedPlacement(first, "eraser", {"marker"})};
  const Plan second = firstPlan(planner, request);
  ASSERT_EQ(second.actions.size(), 4u);
  EXPECT_EQ(second.actions[0].object, "eraser") << "the eraser goes in first now";
  EXPECT_EQ(second.actions[2].object, "marker");
  // Both orders failed: nothing new.
  request.earlierAttempts.push_back(blockedPlacement(second, "marker", {"eraser"}));
  EXPECT_NE(planningErrorOf(planner, request).find("both orders of putting things into holder failed"), std::string::npos);
  // An order the user gave is kept.
  PlanningRequest ordered = requestFor(scene, "first put the marker in the holder, then put the eraser in the holder");
  const Plan orderedPlan = firstPlan(planner, ordered);
  ordered.earlierAttempts = {blockedPlacement(orderedPlan, "eraser", {"marker"})};
  EXPECT_NE(planningErrorOf(planner, ordered).find("the instruction fixes the order in which things go into holder"), std::string::npos)
      << planningErrorOf(planner, ordered);
}

TEST(OfflineTaskPlannerTest, APushThatFailedBecomesAPickAndPlaceByTheSameDisplacement) {
  OfflineTaskPlanner planner;
  const Scene scene = test::deskScene();
  PlanningRequest request = requestFor(scene, "move the eraser 5 cm to the left");
  const Plan pushed = firstPlan(planner, request);
  ASSERT_EQ(pushed.actions.size(), 1u);
  ASSERT_EQ(pushed.actions[0].type, ActionType::kPush);
  request.earlierAttempts.push_back(groundingFailure(pushed, "eraser", "motion"));  // no way behind it
  const Plan carried = firstPlan(planner, request);
  ASSERT_EQ(carried.actions.size(), 2u);
  EXPECT_EQ(carried.actions[0].type, ActionType::kPick);
  EXPECT_EQ(carried.actions[1].type, ActionType::kPlace);
  ASSERT_TRUE(carried.actions[1].params.position.has_value());
  const Pose base = scene.robots().front().basePose;
  const Vector3 start = base.inverse() * scene.object("eraser").pose.translation();
  EXPECT_TRUE(carried.actions[1].params.position->isApprox(start + Vector3(0.0, 0.05, 0.0), 1e-9));
  EXPECT_EQ(test::summarize(understandInstruction(request.task, describeObjects(scene))), describeGoal(carried.goals.front()));
  // Carrying it failed at the grasp: another grasp, still carried.
  request.earlierAttempts.push_back(groundingFailure(carried, "eraser", "grasp"));
  const Plan regrasped = firstPlan(planner, request);
  ASSERT_EQ(regrasped.actions.size(), 2u);
  EXPECT_EQ(regrasped.actions[0].refinements.grasp, graspRetryOrder()[1]);
}

/// The desk scene with a two-joint arm that has nothing on its flange in place of the Panda.
Scene bareArmAtTheDesk() {
  const char* const urdf = R"(<robot name="bare">
  <link name="base"/><link name="upper"/><link name="flange"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="flange"/><origin xyz="0.4 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
</robot>)";
  const Scene desk = test::deskScene();
  Scene scene;
  SceneRobot robot;
  robot.name = "bare";
  robot.model = readUrdfString(urdf, "bare.urdf", std::filesystem::temp_directory_path(), {});
  robot.configuration = VectorX::Zero(robot.model->variableCount());
  robot.basePose = desk.robots().front().basePose;
  scene.addRobot(robot);
  for (const SceneObject& object : desk.objects()) scene.addObject(object);
  return scene;
}

TEST(OfflineTaskPlannerTest, AnArmWithoutGripperIsNeverAskedToCarryWhatItFailedToPush) {
  OfflineTaskPlanner planner;
  const Scene scene = bareArmAtTheDesk();
  PlanningRequest request = requestFor(scene, "push the eraser 5 cm to the left");
  const Plan pushed = firstPlan(planner, request);
  ASSERT_EQ(pushed.actions.size(), 1u);
  request.earlierAttempts.push_back(groundingFailure(pushed, "eraser", "push"));
  const std::string error = planningErrorOf(planner, request);
  EXPECT_NE(error.find("the arm has no gripper to carry eraser instead of pushing it"), std::string::npos) << error;
}

TEST(OfflineTaskPlannerTest, AnObjectNoGraspFitsIsNotPickedAgain) {
  OfflineTaskPlanner planner;
  const Scene scene = test::deskScene();
  PlanningRequest request = requestFor(scene, "move the eraser 5 cm to the left");
  request.earlierAttempts.push_back(groundingFailure(firstPlan(planner, request), "eraser", "motion"));
  PlanAttempt carried = groundingFailure(firstPlan(planner, request), "eraser", "grasp");
  carried.grounding->objectUngraspable = true;  // too wide in every direction, as grounding measured it
  request.earlierAttempts.push_back(carried);
  EXPECT_NE(planningErrorOf(planner, request).find("nothing new to try: no grasp of eraser exists"), std::string::npos);
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
