#include <gmock/gmock.h>
#include <tuple>

#include <gtest/gtest.h>

#include "lang2manip/core/error.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/symbolic/observation.hpp"
#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/plan_prompt.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;
using ::testing::Contains;
using ::testing::HasSubstr;

const json* findNamed(const json& list, const std::string& name) {
  for (const json& item : list) {
    if (item["name"] == name) return &item;
  }
  return nullptr;
}

bool hasRelation(const json& observation, const std::string& subject, const std::string& relation, const std::string& object) {
  for (const json& fact : observation["relations"]) {
    if (fact["subject"] == subject && fact["relation"] == relation && fact["object"] == object) return true;
  }
  return false;
}

TEST(ObservationTest, PaperSceneObservation) {
  const KauthamProblem problem = readKauthamProblem(resolveProblem("panda_desk"));
  const json observation = observeEnvironment(problem.scene);
  ASSERT_EQ(observation["robots"].size(), 1U);
  const json& robot = observation["robots"][0];
  EXPECT_EQ(robot["dofs"], 8);
  EXPECT_EQ(robot["joints"][0]["name"], "panda_joint1");
  EXPECT_DOUBLE_EQ(robot["joints"][0]["lower"].get<double>(), -2.8973);
  EXPECT_EQ(robot["configuration"], "home");
  EXPECT_EQ(robot["links"][0]["parent"], nullptr);
  ASSERT_EQ(robot["end_effectors"].size(), 1U);
  const json& hand = robot["end_effectors"][0];
  EXPECT_EQ(hand["tool_frame"], "panda_hand_tcp");
  EXPECT_EQ(hand["gripper"]["state"], "open");
  EXPECT_EQ(hand["holding"], nullptr);
  // The tool of the ready pose is in front of the base and above the desk.
  EXPECT_GT(hand["position_in_base"][0].get<double>(), 0.2);
  EXPECT_GT(hand["pose"]["position"][2].get<double>(), 0.9);

  const json* marker = findNamed(observation["objects"], "marker");
  ASSERT_NE(marker, nullptr);
  EXPECT_EQ((*marker)["on"], "desk");
  EXPECT_TRUE((*marker)["movable"].get<bool>());
  EXPECT_EQ((*marker)["side_of_robot"], "front-right");
  EXPECT_NEAR((*marker)["position_in_base"][0].get<double>(), 0.42, 1e-3);
  EXPECT_EQ((*findNamed(observation["objects"], "holder"))["role"], "container");
  EXPECT_EQ((*findNamed(observation["objects"], "desk"))["role"], "support");

  EXPECT_TRUE(hasRelation(observation, "marker", "on", "desk"));
  EXPECT_TRUE(hasRelation(observation, "marker", "right_of", "eraser"));
  EXPECT_FALSE(hasRelation(observation, "marker", "left_of", "eraser"));
  EXPECT_TRUE(hasRelation(observation, "eraser", "left_of", "holder") || hasRelation(observation, "holder", "right_of", "eraser") ||
              hasRelation(observation, "eraser", "behind", "holder"));
  EXPECT_FALSE(hasRelation(observation, "marker", "left_of", "desk"));
}

TEST(ObservationTest, TextSaysWhatTheJsonSays) {
  const KauthamProblem problem = readKauthamProblem(resolveProblem("panda_desk"));
  const std::string text = observationText(observeEnvironment(problem.scene));
  EXPECT_THAT(text, HasSubstr("Robot panda"));
  EXPECT_THAT(text, HasSubstr("panda_joint1 revolute 0.000 [-2.897, 2.897]"));
  EXPECT_THAT(text, HasSubstr("gripper open"));
  EXPECT_THAT(text, HasSubstr("configuration: home"));
  EXPECT_THAT(text, HasSubstr("marker: kind marker (a cylinder), blue, movable"));
  EXPECT_THAT(text, HasSubstr("holder: kind pen_holder (a cup), grey, movable container"));
  EXPECT_THAT(text, HasSubstr("  marker on desk\n"));
  EXPECT_THAT(text, HasSubstr("  marker right_of eraser\n"));
  EXPECT_THAT(text, HasSubstr("panda_link0 > panda_link1"));
}

TEST(ObservationTest, HeldObjectsAreReported) {
  KauthamProblem problem = readKauthamProblem(resolveProblem("panda_desk"));
  Scene& scene = problem.scene;
  scene.attach({"marker", scene.robots().front().name, "panda_hand_tcp", Pose::Identity()});
  const json observation = observeEnvironment(scene);
  EXPECT_EQ(observation["robots"][0]["end_effectors"][0]["holding"], "marker");
  EXPECT_TRUE((*findNamed(observation["objects"], "marker"))["held"].get<bool>());
  EXPECT_TRUE(hasRelation(observation, "robot", "holding", "marker"));
}

TEST(ObservationTest, EveryBuiltInProblemIsObserved) {
  for (const BuiltinProblem& builtin : builtinProblems()) {
    SCOPED_TRACE(builtin.shortName);
    const KauthamProblem problem = readKauthamProblem(builtin.file);
    const json observation = observeEnvironment(problem.scene);
    EXPECT_FALSE(observation["robots"][0]["end_effectors"].empty());
    EXPECT_EQ(observation["objects"].size(), problem.scene.objects().size());
    EXPECT_TRUE(hasRelation(observation, "holder", "on", "desk"));
    EXPECT_FALSE(observationText(observation).empty());
  }
}

TEST(ObservationTest, UnknownRobotIsAnInputError) {
  const KauthamProblem problem = readKauthamProblem(resolveProblem("panda_desk"));
  ObservationOptions options;
  options.robot = "r2d2";
  EXPECT_THROW(observeEnvironment(problem.scene, options), InputError);
}

TEST(PlanPromptTest, SystemPromptHasGrammarSchemaRulesExampleAndVersion) {
  const std::string system = planSystemPrompt({"RRTConnect", "PRM"});
  EXPECT_THAT(system, HasSubstr("ACTION GRAMMAR"));
  EXPECT_THAT(system, HasSubstr("RULES"));
  EXPECT_THAT(system, HasSubstr("EXAMPLE"));
  EXPECT_THAT(system, HasSubstr(planJsonSchema().dump()));
  EXPECT_THAT(system, HasSubstr(kPlanPromptVersion));
  EXPECT_THAT(system, HasSubstr("RRTConnect, PRM"));
  // The fixed part does not depend on the planners.
  EXPECT_EQ(planSystemPrompt().substr(0, 2000), system.substr(0, 2000));
}

TEST(PlanPromptTest, TheSpatialConventionsAreTheSameInThePromptAndTheObservationAndFollowTheOptions) {
  const KauthamProblem problem = readKauthamProblem(resolveProblem("panda_desk"));
  const std::string conventions = spatialConventions();
  EXPECT_THAT(conventions, HasSubstr("front = +x"));
  EXPECT_THAT(conventions, HasSubstr("come within 0.100 m"));  // next_to: SpatialOptions::nearDistance
  EXPECT_THAT(planSystemPrompt(), HasSubstr("SPATIAL CONVENTIONS: " + conventions));
  EXPECT_THAT(observationText(observeEnvironment(problem.scene)), HasSubstr("Conventions: " + conventions));
  ObservationOptions options;
  options.spatial.nearDistance = 0.25;
  const std::string wider = observationText(observeEnvironment(problem.scene, options));
  EXPECT_THAT(wider, HasSubstr("come within 0.250 m"));
}

TEST(PlanPromptTest, MessagesCarryTaskObservationAndEarlierAttempts) {
  std::vector<PlanAttempt> attempts(4);
  const std::pair<const char*, const char*> texts[] = {
      {"garbage", "(answer): no JSON object found"},
      {"{\"actions\":[]}", "actions: empty"},
      {"{...}", "step 1 (place marker in holder): marker is not held; pick it first"},
      {"{....}", "fourth failure"}};
  for (std::size_t i = 0; i < attempts.size(); ++i) std::tie(attempts[i].answer, attempts[i].failure) = texts[i];
  const auto messages = planMessages("put the marker and eraser in the holder", "OBS", attempts, 3);
  ASSERT_EQ(messages.size(), 7U);
  EXPECT_THAT(messages[0].content, HasSubstr("TASK: put the marker and eraser in the holder"));
  EXPECT_THAT(messages[0].content, HasSubstr("OBS"));
  EXPECT_THAT(messages[0].content, HasSubstr("1 earlier answers were also rejected"));
  EXPECT_EQ(messages[1].role, LlmMessage::Role::kAssistant);
  EXPECT_EQ(messages[1].content, "{\"actions\":[]}");
  EXPECT_THAT(messages[4].content, HasSubstr("Your answer 3 was not accepted:\nstep 1 (place marker in holder): marker is not held"));
  EXPECT_THAT(messages[6].content, HasSubstr("fourth failure"));
  const std::string rendered = renderPrompt("SYSTEM", messages);
  EXPECT_THAT(rendered, HasSubstr("=== system ===\nSYSTEM"));
  EXPECT_THAT(rendered, HasSubstr("=== assistant ===\n{...}"));
}

}  // namespace
}  // namespace lang2manip
