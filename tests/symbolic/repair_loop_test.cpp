#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <deque>

#include "lang2manip/core/error.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/symbolic/llm_task_planner.hpp"
#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/plan_parser.hpp"
#include "lang2manip/symbolic/repair_loop.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;

const char* const kPaperTask = "put the marker and eraser in the holder";

json placeIn(const std::string& object) {
  return {{"action", "place"}, {"object", object}, {"params", {{"relation", "in"}, {"target", "holder"}}}};
}
json pickStep(const std::string& object) { return {{"action", "pick"}, {"object", object}}; }

std::string goodPlanText() {
  return json({{"actions", {pickStep("marker"), placeIn("marker"), pickStep("eraser"), placeIn("eraser")}}}).dump();
}
std::string placeBeforePickText() {
  return json({{"actions", {placeIn("marker"), pickStep("eraser"), placeIn("eraser")}}}).dump();
}

PlanParseContext repairDeskContext() {
  PlanParseContext context;
  context.objects = {"desk", "marker", "eraser", "holder"};
  return context;
}

RepairOptions rounds(int count) {
  RepairOptions options;
  options.maxRounds = count;
  return options;
}

LlmTaskPlannerOptions withPlanners(std::vector<std::string> names) {
  LlmTaskPlannerOptions options;
  options.plannerNames = std::move(names);
  return options;
}

/// A planner that answers from a script; a text that does not parse becomes an unusable answer,
/// as a real planner reports it. Records what it was asked.
class ScriptedPlanner final : public TaskPlanner {
 public:
  explicit ScriptedPlanner(std::vector<std::string> answers) : answers_(answers.begin(), answers.end()) {}
  [[nodiscard]] std::string name() const override { return "scripted"; }
  Plan plan(const PlanningRequest& request, const StopCondition&, PlanningStatistics& statistics) override {
    requests.push_back(request);
    statistics.llmCalls += 1;
    statistics.inputTokens = addTokenCounts(statistics.inputTokens, 100L);
    statistics.outputTokens = addTokenCounts(statistics.outputTokens, 10L);
    if (answers_.empty()) throw PlanningError("script exhausted");
    const std::string answer = answers_.front();
    answers_.pop_front();
    try {
      return parsePlanText(answer, repairDeskContext());
    } catch (const PlanParseError& error) {
      throw UnusableAnswerError(answer, error.what());
    }
  }
  std::vector<PlanningRequest> requests;

 private:
  std::deque<std::string> answers_;
};

/// An executor that fails the first `failures` executions with a placement failure.
class ScriptedExecutor final : public PlanExecutor {
 public:
  explicit ScriptedExecutor(int failures) : failures_(failures) {}
  std::optional<GroundingFailure> execute(const Plan& plan, const StopCondition&) override {
    executed.push_back(plan);
    if (failures_-- <= 0) return std::nullopt;
    return GroundingFailure{1, "placement", "marker", "no collision-free placement of marker in holder: holder is full", {"eraser"}};
  }
  std::vector<Plan> executed;

 private:
  int failures_;
};

class RepairLoopTest : public ::testing::Test {
 protected:
  RepairLoopTest() : problem_(readKauthamProblem(resolveProblem("panda_desk"))) {
    request_.task = kPaperTask;
    request_.scene = &problem_.scene;
  }
  KauthamProblem problem_;
  PlanningRequest request_;
};

TEST_F(RepairLoopTest, GarbageThenPlaceBeforePickThenAGoodPlanIsAcceptedInRoundThree) {
  ScriptedPlanner planner({"Sure! I will put them in the holder.", placeBeforePickText(), goodPlanText()});
  ScriptedExecutor executor(0);
  const RepairResult result = planWithRepair(planner, request_, &executor, rounds(5), StopCondition::never());
  ASSERT_TRUE(result.succeeded()) << result.failure;
  EXPECT_EQ(result.plan->actions.size(), 4U);
  ASSERT_EQ(result.rounds.size(), 3U);
  EXPECT_EQ(result.rounds[0].outcome, RoundOutcome::kUnusableAnswer);
  EXPECT_EQ(result.rounds[1].outcome, RoundOutcome::kInvalidPlan);
  EXPECT_EQ(result.rounds[2].outcome, RoundOutcome::kAccepted);
  EXPECT_EQ(executor.executed.size(), 1U);  // invalid plans are never executed
  // The planner saw the earlier attempts with their failures in words.
  ASSERT_EQ(planner.requests.size(), 3U);
  ASSERT_EQ(planner.requests[2].earlierAttempts.size(), 2U);
  EXPECT_EQ(planner.requests[2].earlierAttempts[0].answer, "Sure! I will put them in the holder.");
  EXPECT_THAT(planner.requests[2].earlierAttempts[0].failure, HasSubstr("no JSON object found"));
  EXPECT_THAT(planner.requests[2].earlierAttempts[1].failure,
              HasSubstr("step 1 (place marker in holder): marker is not held; pick it first"));
  EXPECT_EQ(result.statistics.llmCalls, 3);
  EXPECT_EQ(result.statistics.inputTokens, 300);
  EXPECT_EQ(result.statistics.outputTokens, 30);
  EXPECT_TRUE(result.failure.empty());
}

TEST_F(RepairLoopTest, BoundedRoundsEndInAFailureListingEveryAttempt) {
  ScriptedPlanner planner({"no plan", placeBeforePickText(), "{\"actions\": [{\"action\": \"grab\"}]}", goodPlanText()});
  const RepairResult result = planWithRepair(planner, request_, nullptr, rounds(3), StopCondition::never());
  EXPECT_FALSE(result.succeeded());
  EXPECT_EQ(result.rounds.size(), 3U);
  EXPECT_THAT(result.failure, HasSubstr("no acceptable plan from scripted after 3 rounds"));
  EXPECT_THAT(result.failure, HasSubstr("round 1 (unusable answer): "));
  EXPECT_THAT(result.failure, HasSubstr("round 2 (invalid plan): the plan is not valid in the current state: step 1"));
  EXPECT_THAT(result.failure, HasSubstr("round 3 (unusable answer): the plan has 1 problem:   actions[0].action: unknown action \"grab\""));
}

TEST_F(RepairLoopTest, GroundingFailuresAreFedBackInWordsAndAsData) {
  ScriptedPlanner planner({goodPlanText(), goodPlanText()});
  ScriptedExecutor executor(1);
  const RepairResult result = planWithRepair(planner, request_, &executor, rounds(3), StopCondition::never());
  ASSERT_TRUE(result.succeeded()) << result.failure;
  ASSERT_EQ(result.rounds.size(), 2U);
  EXPECT_EQ(result.rounds[0].outcome, RoundOutcome::kGroundingFailed);
  ASSERT_EQ(planner.requests[1].earlierAttempts.size(), 1U);
  EXPECT_EQ(planner.requests[1].earlierAttempts[0].failure,
            "step 2 (place marker in holder) could not be executed at the placement stage for marker: "
            "no collision-free placement of marker in holder: holder is full");
  const PlanAttempt& attempt = planner.requests[1].earlierAttempts[0];
  ASSERT_TRUE(attempt.plan.has_value());
  EXPECT_EQ(attempt.plan->actions.size(), executor.executed[0].actions.size());
  ASSERT_TRUE(attempt.grounding.has_value());
  EXPECT_EQ(attempt.grounding->actionIndex, 1U);
  EXPECT_EQ(attempt.grounding->stage, "placement");
  EXPECT_EQ(attempt.grounding->object, "marker");
  EXPECT_EQ(attempt.grounding->blockingObjects, std::vector<std::string>{"eraser"});
}

TEST_F(RepairLoopTest, PlannerErrorsEndTheLoopWithoutMoreRounds) {
  ScriptedPlanner planner({});
  const RepairResult result = planWithRepair(planner, request_, nullptr, rounds(3), StopCondition::never());
  EXPECT_FALSE(result.succeeded());
  EXPECT_EQ(result.rounds.size(), 1U);
  EXPECT_THAT(result.failure, HasSubstr("scripted could not plan: script exhausted"));
  EXPECT_THAT(result.failure, Not(HasSubstr("attempts:"))) << "the only round is the error itself";
}

TEST_F(RepairLoopTest, APlannerErrorAfterRejectedRoundsListsTheEarlierAttempts) {
  ScriptedPlanner planner({"no plan here"});
  const RepairResult result = planWithRepair(planner, request_, nullptr, rounds(3), StopCondition::never());
  EXPECT_FALSE(result.succeeded());
  EXPECT_EQ(result.rounds.size(), 2U);
  EXPECT_THAT(result.failure, ::testing::StartsWith("scripted could not plan: script exhausted; earlier attempts:\n"
                                                    "  round 1 (unusable answer): "));
  EXPECT_THAT(result.failure, Not(HasSubstr("round 2")));
}

TEST_F(RepairLoopTest, AStoppedConditionEndsBeforeAskingAndBadOptionsAreRejected) {
  ScriptedPlanner planner({goodPlanText()});
  auto flag = std::make_shared<std::atomic<bool>>(true);
  const RepairResult result = planWithRepair(planner, request_, nullptr, RepairOptions{}, StopCondition::onCancel(flag));
  EXPECT_FALSE(result.succeeded());
  EXPECT_TRUE(planner.requests.empty());
  EXPECT_THAT(result.failure, HasSubstr("stopped (deadline or cancellation) before round 1"));
  EXPECT_THROW(planWithRepair(planner, request_, nullptr, rounds(0), StopCondition::never()), InputError);
  PlanningRequest noScene = request_;
  noScene.scene = nullptr;
  EXPECT_THROW(planWithRepair(planner, noScene, nullptr, RepairOptions{}, StopCondition::never()), InputError);
}

/// An LlmClient answering from a script of replies (or errors); records the requests.
class ScriptedLlmClient final : public LlmClient {
 public:
  explicit ScriptedLlmClient(std::vector<LlmReply> replies) : replies_(replies.begin(), replies.end()) {}
  [[nodiscard]] std::string name() const override { return "test:scripted"; }
  LlmReply complete(const LlmRequest& request, const StopCondition&) override {
    requests.push_back(request);
    if (replies_.empty()) throw LlmError(LlmErrorKind::kServer, "HTTP 500 after 3 attempts", 500);
    LlmReply reply = replies_.front();
    replies_.pop_front();
    return reply;
  }
  std::vector<LlmRequest> requests;

 private:
  std::deque<LlmReply> replies_;
};

LlmReply reply(const std::string& content, FinishReason finish = FinishReason::kStop) {
  LlmReply r;
  r.content = content;
  r.finish = finish;
  r.usage = {1000, 50};
  r.latencySeconds = 0.5;
  return r;
}

TEST_F(RepairLoopTest, LlmPlannerRepairsTruncatedRefusedAndUnknownObjectAnswers) {
  LlmReply refused = reply("", FinishReason::kRefusal);
  refused.refusal = "I can't help with that.";
  std::string unknownObject = goodPlanText();
  unknownObject.replace(unknownObject.find("eraser"), 6, "cup");
  ScriptedLlmClient client({reply(goodPlanText().substr(0, 50), FinishReason::kLength), refused,
                            reply(unknownObject), reply("```json\n" + goodPlanText() + "\n```")});
  LlmTaskPlanner planner(client, withPlanners({"RRTConnect"}));
  const RepairResult result = planWithRepair(planner, request_, nullptr, rounds(4), StopCondition::never());
  ASSERT_TRUE(result.succeeded()) << result.failure;
  ASSERT_EQ(result.rounds.size(), 4U);
  EXPECT_THAT(result.rounds[0].attempt.failure, HasSubstr("cut off at the output token limit"));
  EXPECT_THAT(result.rounds[1].attempt.failure, HasSubstr("the model refused to answer: I can't help with that."));
  EXPECT_THAT(result.rounds[2].attempt.failure, HasSubstr("actions[2].object: unknown object \"cup\""));
  EXPECT_EQ(result.statistics.llmCalls, 4);
  EXPECT_EQ(result.statistics.inputTokens, 4000);
  EXPECT_EQ(result.statistics.outputTokens, 200);
  EXPECT_DOUBLE_EQ(result.statistics.llmSeconds, 2.0);

  ASSERT_EQ(client.requests.size(), 4U);
  const LlmRequest& first = client.requests[0];
  EXPECT_EQ(first.schema, planJsonSchema());
  EXPECT_THAT(first.system, HasSubstr("ACTION GRAMMAR"));
  EXPECT_THAT(first.system, HasSubstr("RRTConnect"));
  ASSERT_EQ(first.messages.size(), 1U);
  EXPECT_THAT(first.messages[0].content, HasSubstr(std::string("TASK: ") + kPaperTask));
  EXPECT_THAT(first.messages[0].content, HasSubstr("holder: kind pen_holder"));
  const LlmRequest& last = client.requests[3];
  ASSERT_EQ(last.messages.size(), 7U);
  EXPECT_EQ(last.messages[5].content, unknownObject);
  EXPECT_THAT(last.messages[6].content, HasSubstr("unknown object \"cup\" (objects: desk, marker, eraser, holder)"));
}

/// Every kind of malformed answer -- numbers nlohmann cannot hold (1e400: out_of_range, not a
/// parse_error), nesting that would exhaust the stack, invalid UTF-8, wrong types, huge values,
/// huge names -- is an unusable answer the loop feeds back; the next good answer succeeds.
TEST_F(RepairLoopTest, LlmPlannerRepairsEveryKindOfMalformedAnswer) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  std::string deepInField = goodPlanText();  // valid nesting depth outside, 100,000 levels inside
  deepInField.replace(deepInField.find("\"params\":{"), 10, "\"params\":" + deep + ",\"x\":{");
  const std::string withinLimitDeep = std::string(100, '[') + "1" + std::string(100, ']');
  const std::vector<std::pair<std::string, std::string>> malformed = {
      {R"({"actions": [{"action": "push", "object": "marker", "params": {"distance": 1e400}}]})",
       "not valid JSON: number overflow parsing '1e400'"},
      {R"({"actions": [{"action": "pick", "object": "marker"}], "reasoning": -1e400})", "number overflow"},
      {deep, "the JSON document: nested deeper than 128 levels"},
      {"Here is the plan:\n```json\n" + deep + "\n```", "nested deeper than 128 levels"},
      {deepInField, "nested deeper than 128 levels"},
      {R"({"actions": [{"action": "pick", "object": "marker", "params": )" + withinLimitDeep + "}]}",
       "actions[0].params: expected an object or null, got array [[[["},
      {"{\"actions\": [{\"action\": \"pick\xff\"}]}", "not valid JSON"},
      {R"({"actions": [{"action": 5, "object": ["marker"], "params": "x", "refinements": 7, "planner": {}}]})",
       "actions[0].action: expected a string, got number 5"},
      {R"({"actions": [{"action": "push", "object": "marker", "params": {"direction": {"x": 1e308, "y": 1e308, "z": 1e308}, "distance": 18446744073709551615}}]})",
       "actions[0].params.direction: not a unit vector (length inf)"},
      {R"({"actions": [{"action": "place", "object": "marker", "params": {"relation": "in", "target": "holder", "distance": -9223372036854775809}}]})",
       "actions[0].params.distance"},
      {R"({"actions": {"a": 1}})", "actions: expected an array of actions, got object {\"a\":1}"},
      {"null", "no JSON object found in the answer"},
      {"[12]", "actions[0]: expected an action object, got number 12"},
      {"[[]]", "actions[0]: expected an action object, got array []"},
      {"\"pick the marker\"", "no JSON object found in the answer"},
      {R"({"actions": [{"action": ")" + std::string(1 << 20, 'p') + R"("}]})", "unknown action \"pppp"},
      {"", "empty answer"},
  };
  std::vector<LlmReply> replies;
  for (const auto& [answer, failure] : malformed) replies.push_back(reply(answer));
  replies.push_back(reply(goodPlanText()));
  ScriptedLlmClient client(replies);
  LlmTaskPlanner planner(client);
  const int maxRounds = static_cast<int>(replies.size());
  RepairResult result;
  ASSERT_NO_THROW(result = planWithRepair(planner, request_, nullptr, rounds(maxRounds), StopCondition::never()));
  ASSERT_TRUE(result.succeeded()) << result.failure;
  ASSERT_EQ(result.rounds.size(), replies.size());
  for (std::size_t i = 0; i < malformed.size(); ++i) {
    const RepairRound& round = result.rounds[i];
    EXPECT_EQ(round.outcome, RoundOutcome::kUnusableAnswer) << i;
    EXPECT_THAT(round.attempt.failure, HasSubstr(malformed[i].second)) << i << ": " << round.attempt.failure;
    EXPECT_LT(round.attempt.failure.size(), 2000U) << i << ": failures quote bounded parts of the answer";
  }
  EXPECT_EQ(result.rounds.back().outcome, RoundOutcome::kAccepted);
}

TEST_F(RepairLoopTest, UnknownTokenCountsMakeTheTotalUnknown) {
  LlmReply unknown = reply(placeBeforePickText());
  unknown.usage.inputTokens = std::nullopt;
  ScriptedLlmClient client({unknown, reply(goodPlanText())});
  LlmTaskPlanner planner(client);
  const RepairResult result = planWithRepair(planner, request_, nullptr, rounds(2), StopCondition::never());
  ASSERT_TRUE(result.succeeded()) << result.failure;
  EXPECT_FALSE(result.statistics.inputTokens.has_value()) << "a total leaving out a call would be wrong";
  EXPECT_EQ(result.statistics.outputTokens, 100L);
  EXPECT_EQ(tokenCountText(result.statistics.inputTokens), "unknown");
  EXPECT_EQ(result.rounds[1].statistics.inputTokens, 1000L);
}

TEST_F(RepairLoopTest, LlmCallFailuresEndTheLoopWithTheReason) {
  ScriptedLlmClient client({});
  LlmTaskPlanner planner(client);
  const RepairResult result = planWithRepair(planner, request_, nullptr, rounds(3), StopCondition::never());
  EXPECT_FALSE(result.succeeded());
  EXPECT_EQ(result.rounds.size(), 1U);
  EXPECT_THAT(result.failure, HasSubstr("the LLM call of test:scripted failed: HTTP 500 after 3 attempts"));
}

TEST_F(RepairLoopTest, LlmPlannerChecksPlannerNamesAndNeedsAScene) {
  std::string named = goodPlanText();
  named.replace(named.find("\"action\":\"pick\""), 0, "\"planner\":\"Teleport\",");
  ScriptedLlmClient client({reply(named)});
  LlmTaskPlanner planner(client, withPlanners({"RRTConnect"}));
  PlanningStatistics statistics;
  try {
    planner.plan(request_, StopCondition::never(), statistics);
    FAIL() << "expected UnusableAnswerError";
  } catch (const UnusableAnswerError& error) {
    EXPECT_THAT(error.what(), HasSubstr("actions[0].planner: unknown planner \"Teleport\" (planners: RRTConnect"));
    EXPECT_EQ(error.answer(), named);
  }
  PlanningRequest noScene = request_;
  noScene.scene = nullptr;
  EXPECT_THROW(planner.plan(noScene, StopCondition::never(), statistics), InputError);
}

}  // namespace
}  // namespace lang2manip
