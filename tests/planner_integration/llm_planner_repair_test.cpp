// The LLM task planner through the repair loop against each protocol's fake server: every
// scripted misbehaviour ends in the paper's plan after repair, or in a clear error -- never a
// crash or a hang.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "fake_llm_server.hpp"
#include "lang2manip/llm/llm_client_factory.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/planning/planner_registry.hpp"
#include "lang2manip/symbolic/llm_task_planner.hpp"
#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/repair_loop.hpp"
#include "llm_test_support.hpp"

namespace lang2manip::test {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;

const char* const kPaperTask = "put the marker and eraser in the holder";

json pick(const std::string& object) { return {{"action", "pick"}, {"object", object}}; }
json placeInHolder(const std::string& object) {
  return {{"action", "place"}, {"object", object}, {"params", {{"relation", "in"}, {"target", "holder"}}}};
}
/// A vector, not a json initializer list: a one-action list would otherwise become an object.
std::string planText(const std::vector<json>& actions) { return json({{"actions", actions}}).dump(); }

const std::string kPaperPlan =
    planText({pick("marker"), placeInHolder("marker"), pick("eraser"), placeInHolder("eraser")});

class LlmPlannerRepairTest : public ::testing::TestWithParam<FakeLlmProtocol> {
 protected:
  LlmPlannerRepairTest()
      : server_(GetParam()), options_(fastOptions(server_)), problem_(readKauthamProblem(resolveProblem("panda_desk"))) {}

  /// planWithRepair with an LLM planner on the fake server, as `lang2manip plan` runs it.
  RepairResult plan(const std::string& model = "test-model", int rounds = 4) {
    const std::unique_ptr<LlmClient> client = makeLlmClient(server_.spec(model), options_);
    LlmTaskPlannerOptions plannerOptions;
    plannerOptions.plannerNames = plannerNames();
    LlmTaskPlanner planner(*client, plannerOptions);
    PlanningRequest request;
    request.task = kPaperTask;
    request.scene = &problem_.scene;
    RepairOptions repair;
    repair.maxRounds = rounds;
    return planWithRepair(planner, request, nullptr, repair, StopCondition::never());
  }

  /// The user message of the n-th request the server received (0-based), in any protocol.
  [[nodiscard]] std::string requestText(std::size_t index) const { return server_.requests().at(index).body; }

  FakeLlmServer server_;
  LlmClientOptions options_;
  KauthamProblem problem_;
};

/// The result is the paper's plan: pick/place marker, pick/place eraser, both in the holder.
void expectPaperPlan(const RepairResult& result) {
  ASSERT_TRUE(result.succeeded()) << result.failure;
  const std::vector<SymbolicAction>& actions = result.plan->actions;
  ASSERT_EQ(actions.size(), 4U);
  const std::vector<std::string> described = {describeAction(actions[0]), describeAction(actions[1]),
                                              describeAction(actions[2]), describeAction(actions[3])};
  EXPECT_EQ(described, (std::vector<std::string>{"pick marker", "place marker in holder", "pick eraser",
                                                 "place eraser in holder"}));
  EXPECT_TRUE(result.failure.empty());
}

/// A first answer that fails, a valid second answer: repaired in round 2, with the failure fed
/// back to the model in the second request.
void expectRepairedInRoundTwo(const RepairResult& result, RoundOutcome firstOutcome, const std::string& failure,
                              const std::string& secondRequest) {
  expectPaperPlan(result);
  ASSERT_EQ(result.rounds.size(), 2U) << result.failure;
  EXPECT_EQ(result.rounds[0].outcome, firstOutcome) << result.rounds[0].attempt.failure;
  EXPECT_THAT(result.rounds[0].attempt.failure, HasSubstr(failure));
  EXPECT_EQ(result.rounds[1].outcome, RoundOutcome::kAccepted);
  EXPECT_EQ(result.statistics.llmCalls, 2);
  EXPECT_THAT(secondRequest, HasSubstr("was not accepted")) << "the repair request describes the failure";
}

TEST_P(LlmPlannerRepairTest, ValidPlanIsAcceptedInTheFirstRound) {
  server_.enqueueAnswer(kPaperPlan);
  const RepairResult result = plan();
  expectPaperPlan(result);
  EXPECT_EQ(result.rounds.size(), 1U);
  EXPECT_EQ(result.statistics.llmCalls, 1);
  EXPECT_GT(result.statistics.inputTokens, 0);
  EXPECT_GT(result.statistics.outputTokens, 0);
  EXPECT_GT(result.statistics.llmSeconds, 0.0);
  // The prompt carries the task, the observation and the registry's planner names.
  const std::string request = requestText(0);
  EXPECT_THAT(request, HasSubstr(kPaperTask));
  EXPECT_THAT(request, HasSubstr("marker: kind marker (a cylinder), blue, movable"));
  EXPECT_THAT(request, HasSubstr("RRTConnect"));
  EXPECT_THAT(request, Not(HasSubstr("was not accepted")));
}

TEST_P(LlmPlannerRepairTest, MalformedJsonIsRepaired) {
  server_.enqueueAnswer(R"({"actions": [{"action": "pick", "object": "marker"}, {"action": )");
  server_.enqueueAnswer(kPaperPlan);
  const RepairResult result = plan();
  expectRepairedInRoundTwo(result, RoundOutcome::kUnusableAnswer, "not valid JSON", requestText(1));
}

/// Answers nlohmann cannot hold (1e400 is an out_of_range, not a parse_error), nesting that would
/// exhaust the stack, and invalid UTF-8: each is fed back, then the good plan is accepted.
TEST_P(LlmPlannerRepairTest, AnswersThatBreakTheJsonLibraryAreRepaired) {
  server_.enqueueAnswer(R"({"actions": [{"action": "push", "object": "marker", "params": {"distance": 1e400}}]})");
  server_.enqueueAnswer(std::string(100000, '[') + std::string(100000, ']'));
  server_.enqueueAnswer(std::string(50000, '{') + "\"a\":1" + std::string(50000, '}'));
  server_.enqueueAnswer(R"({"actions": [{"action": 18446744073709551616, "object": -1e308}]})");
  server_.enqueueAnswer(kPaperPlan);
  const RepairResult result = plan("test-model", 5);
  expectPaperPlan(result);
  ASSERT_EQ(result.rounds.size(), 5U);
  EXPECT_THAT(result.rounds[0].attempt.failure, HasSubstr("number overflow parsing '1e400'"));
  EXPECT_THAT(result.rounds[1].attempt.failure, HasSubstr("nested deeper than 128 levels"));
  EXPECT_THAT(result.rounds[2].attempt.failure, HasSubstr("nested deeper than 128 levels"));
  EXPECT_THAT(result.rounds[3].attempt.failure, HasSubstr("actions[0].action: expected a string, got number"));
  for (int i = 0; i < 4; ++i) EXPECT_EQ(result.rounds[static_cast<std::size_t>(i)].outcome, RoundOutcome::kUnusableAnswer);
}

TEST_P(LlmPlannerRepairTest, TruncatedAnswerIsRepaired) {
  server_.enqueueTruncated(R"({"actions": [{"action": "pick", "obj)");
  server_.enqueueAnswer(kPaperPlan);
  const RepairResult result = plan();
  expectRepairedInRoundTwo(result, RoundOutcome::kUnusableAnswer, "cut off at the output token limit",
                           requestText(1));
}

TEST_P(LlmPlannerRepairTest, MissingArgumentsAreRepaired) {
  server_.enqueueAnswer(planText({{{"action", "pick"}}, {{"action", "place"}, {"object", "marker"}}}));
  server_.enqueueAnswer(kPaperPlan);
  const RepairResult result = plan();
  expectRepairedInRoundTwo(result, RoundOutcome::kUnusableAnswer, "actions[0].object: missing", requestText(1));
  EXPECT_THAT(result.rounds[0].attempt.failure, HasSubstr("actions[1].params: place needs a relation"));
}

TEST_P(LlmPlannerRepairTest, UnknownObjectIsRepaired) {
  server_.enqueueAnswer(planText({pick("cup"), placeInHolder("cup")}));
  server_.enqueueAnswer(kPaperPlan);
  const RepairResult result = plan();
  expectRepairedInRoundTwo(result, RoundOutcome::kUnusableAnswer, "actions[0].object: unknown object \"cup\"",
                           requestText(1));
  EXPECT_THAT(requestText(1), HasSubstr("unknown object \\\"cup\\\""));
}

TEST_P(LlmPlannerRepairTest, PlaceBeforePickIsRepaired) {
  server_.enqueueAnswer(planText({placeInHolder("marker"), pick("marker"), pick("eraser"), placeInHolder("eraser")}));
  server_.enqueueAnswer(kPaperPlan);
  const RepairResult result = plan();
  expectRepairedInRoundTwo(result, RoundOutcome::kInvalidPlan,
                           "step 1 (place marker in holder): marker is not held; pick it first", requestText(1));
  EXPECT_TRUE(result.rounds[0].attempt.plan.has_value()) << "the invalid plan parsed; validation rejected it";
}

TEST_P(LlmPlannerRepairTest, RefusalIsRepaired) {
  server_.enqueueRefusal("I cannot help with that.");
  server_.enqueueAnswer(kPaperPlan);
  // Ollama has no refusal signal: the words arrive as the answer, which is not a plan.
  const std::string why =
      GetParam() == FakeLlmProtocol::kOllama ? "no JSON object found" : "the model refused to answer";
  const RepairResult result = plan();
  expectRepairedInRoundTwo(result, RoundOutcome::kUnusableAnswer, why, requestText(1));
}

TEST_P(LlmPlannerRepairTest, UnknownMotionPlannerIsRepaired) {
  json marker = pick("marker");
  marker["planner"] = "WarpDrive";
  server_.enqueueAnswer(planText({marker, placeInHolder("marker"), pick("eraser"), placeInHolder("eraser")}));
  server_.enqueueAnswer(kPaperPlan);
  const RepairResult result = plan();
  expectRepairedInRoundTwo(result, RoundOutcome::kUnusableAnswer, "actions[0].planner: unknown planner \"WarpDrive\"",
                           requestText(1));
}

TEST_P(LlmPlannerRepairTest, UnauthorizedIsAClearErrorWithoutRetry) {
  server_.enqueueError(401, "invalid api key");
  server_.enqueueAnswer(kPaperPlan);
  const RepairResult result = plan();
  EXPECT_FALSE(result.succeeded());
  ASSERT_EQ(result.rounds.size(), 1U);
  EXPECT_EQ(result.rounds[0].outcome, RoundOutcome::kPlannerError);
  EXPECT_THAT(result.failure, HasSubstr("refused the credentials"));
  EXPECT_THAT(result.failure, HasSubstr("HTTP 401"));
  EXPECT_THAT(result.failure, Not(HasSubstr(kTestApiKey)));
  EXPECT_EQ(server_.requestCount(), 1U) << "authentication errors are not retried";
}

TEST_P(LlmPlannerRepairTest, UnknownModelIsAClearErrorNamingIt) {
  server_.enqueueError(404, "model not found");
  const RepairResult result = plan("no-such-model");
  EXPECT_FALSE(result.succeeded());
  ASSERT_EQ(result.rounds.size(), 1U);
  EXPECT_THAT(result.failure, HasSubstr("model \"no-such-model\" not found"));
  EXPECT_EQ(server_.requestCount(), 1U);
}

TEST_P(LlmPlannerRepairTest, RateLimitHonoursRetryAfterThenSucceeds) {
  server_.enqueueError(429, "slow down", {{"Retry-After", "0.2"}});
  server_.enqueueAnswer(kPaperPlan);
  const auto start = std::chrono::steady_clock::now();
  const RepairResult result = plan();
  expectPaperPlan(result);
  EXPECT_GE(secondsSince(start), 0.2) << "the client waited as asked";
  EXPECT_EQ(result.rounds.size(), 1U) << "retries happen inside one planner round";
  EXPECT_EQ(server_.requestCount(), 2U);
}

TEST_P(LlmPlannerRepairTest, ServerErrorIsRetriedThenSucceeds) {
  server_.enqueueError(500, "internal error");
  server_.enqueueAnswer(kPaperPlan);
  const RepairResult result = plan();
  expectPaperPlan(result);
  EXPECT_EQ(result.rounds.size(), 1U);
  EXPECT_EQ(server_.requestCount(), 2U);
}

TEST_P(LlmPlannerRepairTest, PersistentServerErrorsEndInAClearError) {
  for (int i = 0; i < 3; ++i) server_.enqueueError(503, "overloaded");
  const RepairResult result = plan();
  EXPECT_FALSE(result.succeeded());
  EXPECT_EQ(result.rounds.size(), 1U);
  EXPECT_THAT(result.failure, HasSubstr("HTTP 503"));
  EXPECT_THAT(result.failure, HasSubstr("gave up after 3 attempts"));
}

TEST_P(LlmPlannerRepairTest, HangPastTheTimeoutIsAClearTimeoutInBoundedTime) {
  options_.http.requestTimeoutSeconds = 0.3;
  options_.retry.maxAttempts = 2;
  server_.enqueueHang(30.0);
  server_.enqueueHang(30.0);
  const auto start = std::chrono::steady_clock::now();
  const RepairResult result = plan();
  EXPECT_LT(secondsSince(start), 5.0);
  EXPECT_FALSE(result.succeeded());
  ASSERT_EQ(result.rounds.size(), 1U);
  EXPECT_EQ(result.rounds[0].outcome, RoundOutcome::kPlannerError);
  EXPECT_THAT(result.failure, HasSubstr("within 0.3 s"));
  EXPECT_EQ(server_.requestCount(), 2U);
}

TEST_P(LlmPlannerRepairTest, OneHangThenAnAnswerIsRetriedWithinTheRound) {
  options_.http.requestTimeoutSeconds = 0.3;
  server_.enqueueHang(30.0);
  server_.enqueueAnswer(kPaperPlan);
  const RepairResult result = plan();
  expectPaperPlan(result);
  EXPECT_EQ(result.rounds.size(), 1U);
}

TEST_P(LlmPlannerRepairTest, RoundsAreBoundedAndTheFailureListsEveryAttempt) {
  server_.enqueueAnswer("Sure, I will do that.");
  server_.enqueueAnswer(planText({placeInHolder("marker")}));
  server_.enqueueAnswer(planText({pick("cup")}));
  server_.enqueueAnswer(kPaperPlan);
  const RepairResult result = plan("test-model", 3);
  EXPECT_FALSE(result.succeeded());
  EXPECT_EQ(result.rounds.size(), 3U);
  EXPECT_EQ(server_.requestCount(), 3U);
  EXPECT_THAT(result.failure, HasSubstr("after 3 rounds"));
  EXPECT_THAT(result.failure, HasSubstr("round 1 (unusable answer)"));
  EXPECT_THAT(result.failure, HasSubstr("round 2 (invalid plan)"));
  EXPECT_THAT(result.failure, HasSubstr("round 3 (unusable answer)"));
  // The third request carries both earlier attempts.
  EXPECT_THAT(requestText(2), HasSubstr("Sure, I will do that."));
  EXPECT_THAT(requestText(2), HasSubstr("marker is not held"));
}

INSTANTIATE_TEST_SUITE_P(AllProtocols, LlmPlannerRepairTest, ::testing::ValuesIn(allFakeLlmProtocols()),
                         [](const ::testing::TestParamInfo<FakeLlmProtocol>& parameter) {
                           return fakeLlmProvider(parameter.param);
                         });

}  // namespace
}  // namespace lang2manip::test
