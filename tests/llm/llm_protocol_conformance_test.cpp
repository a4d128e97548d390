// Every protocol client against its fake server: the same cases for all four.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "fake_llm_server.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/llm/llm_client_factory.hpp"
#include "llm_test_support.hpp"

namespace lang2manip::test {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;

class LlmProtocolTest : public ::testing::TestWithParam<FakeLlmProtocol> {
 protected:
  LlmProtocolTest() : server_(GetParam()), options_(fastOptions(server_)) {}

  std::unique_ptr<LlmClient> client(const std::string& model = "test-model") {
    return makeLlmClient(server_.spec(model), options_);
  }

  LlmError failingCall(const StopCondition& stop = StopCondition::never()) {
    auto llm = client();
    return expectLlmError([&] { llm->complete(planRequest(), stop); });
  }

  FakeLlmServer server_;
  LlmClientOptions options_;
};

/// Where each protocol carries the schema, the key and the system prompt.
void expectProtocolRequest(FakeLlmProtocol protocol, const FakeReceivedRequest& received) {
  const json& body = received.json;
  const json schema = smallPlanSchema();
  switch (protocol) {
    case FakeLlmProtocol::kOpenAi:
      EXPECT_EQ(received.path, "/v1/chat/completions");
      EXPECT_EQ(received.header("Authorization"), std::string("Bearer ") + kTestApiKey);
      EXPECT_EQ(body["response_format"]["type"], "json_schema");
      EXPECT_EQ(body["response_format"]["json_schema"]["name"], "plan");
      EXPECT_EQ(body["response_format"]["json_schema"]["strict"], true);
      EXPECT_EQ(body["response_format"]["json_schema"]["schema"], schema);
      EXPECT_EQ(body["messages"][0]["role"], "system");
      EXPECT_EQ(body["messages"][1]["content"], "put the marker in the holder");
      EXPECT_EQ(body["seed"], 7);
      EXPECT_EQ(body["model"], "test-model");
      break;
    case FakeLlmProtocol::kAnthropic:
      EXPECT_EQ(received.path, "/v1/messages");
      EXPECT_EQ(received.header("x-api-key"), kTestApiKey);
      EXPECT_EQ(received.header("anthropic-version"), "2023-06-01");
      EXPECT_EQ(body["tools"][0]["name"], "plan");
      EXPECT_EQ(body["tools"][0]["input_schema"], schema);
      EXPECT_EQ(body["tool_choice"], json({{"type", "tool"}, {"name", "plan"}}));
      EXPECT_EQ(body["system"], "You plan robot manipulation.");
      EXPECT_EQ(body["max_tokens"], 512);
      EXPECT_EQ(body["model"], "test-model");
      break;
    case FakeLlmProtocol::kGemini:
      EXPECT_EQ(received.path, "/v1beta/models/test-model:generateContent");
      EXPECT_EQ(received.header("x-goog-api-key"), kTestApiKey);
      EXPECT_EQ(body["generationConfig"]["responseMimeType"], "application/json");
      EXPECT_EQ(body["generationConfig"]["responseSchema"]["type"], "OBJECT");
      EXPECT_FALSE(body["generationConfig"]["responseSchema"].contains("additionalProperties"));
      EXPECT_EQ(body["systemInstruction"]["parts"][0]["text"], "You plan robot manipulation.");
      EXPECT_EQ(body["contents"][0]["role"], "user");
      EXPECT_EQ(body["generationConfig"]["maxOutputTokens"], 512);
      break;
    case FakeLlmProtocol::kOllama:
      EXPECT_EQ(received.path, "/api/chat");
      EXPECT_EQ(received.header("Authorization"), std::string("Bearer ") + kTestApiKey);
      EXPECT_EQ(body["format"], schema);
      EXPECT_EQ(body["stream"], false);
      EXPECT_EQ(body["options"]["seed"], 7);
      EXPECT_EQ(body["messages"][0]["role"], "system");
      EXPECT_EQ(body["model"], "test-model");
      break;
  }
}

TEST_P(LlmProtocolTest, ValidAnswerCarriesContentUsageAndModel) {
  server_.enqueueAnswer(kPlanAnswer);
  const LlmReply reply = client()->complete(planRequest(), StopCondition::never());
  EXPECT_EQ(json::parse(reply.content), json::parse(kPlanAnswer));
  EXPECT_EQ(reply.finish, FinishReason::kStop);
  EXPECT_EQ(reply.model, "test-model");
  EXPECT_EQ(reply.attempts, 1);
  EXPECT_GT(reply.usage.inputTokens, 0);
  EXPECT_GT(reply.usage.outputTokens, 0);
  EXPECT_FALSE(reply.replayed);
  ASSERT_EQ(server_.requestCount(), 1U);
  expectProtocolRequest(GetParam(), server_.requests()[0]);
}

TEST_P(LlmProtocolTest, FreeTextRequestSendsNoSchema) {
  server_.enqueueAnswer("hello");
  LlmRequest request = planRequest();
  request.schema = nullptr;
  EXPECT_EQ(client()->complete(request, StopCondition::never()).content, "hello");
  const json body = server_.requests().at(0).json;
  EXPECT_FALSE(body.contains("response_format"));
  EXPECT_FALSE(body.contains("tools"));
  EXPECT_FALSE(body.contains("format"));
  EXPECT_FALSE(body.value("generationConfig", json::object()).contains("responseSchema"));
}

TEST_P(LlmProtocolTest, BodyThatIsNotJsonIsABadResponse) {
  FakeHttpResponse broken;
  broken.body = R"({"choices": [{"message": )";
  server_.enqueue(broken);
  const LlmError error = failingCall();
  EXPECT_EQ(error.kind(), LlmErrorKind::kBadResponse);
  EXPECT_THAT(error.what(), HasSubstr("not JSON"));
  EXPECT_THAT(error.what(), HasSubstr(server_.spec()));
  EXPECT_EQ(server_.requestCount(), 1U) << "a malformed answer is not retried";
}

TEST_P(LlmProtocolTest, BodyWithoutTheAnswerFieldNamesTheField) {
  FakeHttpResponse empty;
  empty.body = R"({"id": "x"})";
  server_.enqueue(empty);
  const LlmError error = failingCall();
  EXPECT_EQ(error.kind(), LlmErrorKind::kBadResponse);
  const char* field = GetParam() == FakeLlmProtocol::kOpenAi      ? "choices"
                      : GetParam() == FakeLlmProtocol::kAnthropic ? "content"
                      : GetParam() == FakeLlmProtocol::kGemini    ? "candidates"
                                                                  : "message";
  EXPECT_THAT(error.what(), HasSubstr(std::string("answer has no ") + field));
}

TEST_P(LlmProtocolTest, OddlyShapedBodiesAreBadResponsesNeverCrashes) {
  const std::vector<std::string> bodies = {
      R"([1, 2])", R"({"choices": "x"})", R"({"choices": [1]})", R"({"choices": [{"message": 5}]})",
      R"({"choices": [{"message": {"content": 5}}]})", R"({"content": "x"})",
      R"({"content": [1, {"type": 2}], "stop_reason": 3})", R"({"candidates": [1]})",
      R"({"candidates": [{"content": {"parts": "x"}, "finishReason": "STOP"}]})",
      R"({"candidates": [{"content": {"parts": [{"text": 1, "thought": "no"}]}}]})",
      R"({"message": {"content": null}})", R"({"message": {"content": "{}"}, "done": false})",
      R"({"usage": 1, "usageMetadata": [], "message": []})"};
  options_.retry.maxAttempts = 1;
  auto llm = client();
  for (const std::string& body : bodies) {
    FakeHttpResponse odd;
    odd.body = body;
    server_.enqueue(odd);
    try {
      llm->complete(planRequest(), StopCondition::never());
    } catch (const LlmError& error) {
      EXPECT_EQ(error.kind(), LlmErrorKind::kBadResponse) << body << ": " << error.what();
      continue;
    }
    ADD_FAILURE() << "accepted " << body;
  }
}

TEST_P(LlmProtocolTest, TruncatedAnswerEndsInLength) {
  server_.enqueueTruncated(R"({"actions":[{"action":"pi)");
  const LlmReply reply = client()->complete(planRequest(), StopCondition::never());
  EXPECT_EQ(reply.finish, FinishReason::kLength);
  EXPECT_EQ(reply.content, R"({"actions":[{"action":"pi)");
}

TEST_P(LlmProtocolTest, RefusalIsReportedAsSuch) {
  server_.enqueueRefusal("I cannot help with moving that object.");
  const LlmReply reply = client()->complete(planRequest(), StopCondition::never());
  switch (GetParam()) {
    case FakeLlmProtocol::kOpenAi:
    case FakeLlmProtocol::kAnthropic:
      EXPECT_EQ(reply.finish, FinishReason::kRefusal);
      EXPECT_EQ(reply.refusal, "I cannot help with moving that object.");
      break;
    case FakeLlmProtocol::kGemini:
      EXPECT_EQ(reply.finish, FinishReason::kRefusal);
      EXPECT_THAT(reply.refusal, HasSubstr("blocked (SAFETY)"));
      break;
    case FakeLlmProtocol::kOllama:
      // Ollama has no refusal signal: the words come back as content for the plan parser.
      EXPECT_EQ(reply.finish, FinishReason::kStop);
      EXPECT_EQ(reply.content, "I cannot help with moving that object.");
      break;
  }
}

TEST_P(LlmProtocolTest, UnauthorizedIsAnAuthenticationErrorWithoutTheKey) {
  server_.enqueueError(401, std::string("Incorrect API key provided: ") + kTestApiKey);
  const LlmError error = failingCall();
  EXPECT_EQ(error.kind(), LlmErrorKind::kAuthentication);
  EXPECT_EQ(error.httpStatus(), 401);
  EXPECT_THAT(error.what(), Not(HasSubstr(kTestApiKey)));
  EXPECT_THAT(error.what(), HasSubstr("[redacted]"));
  const char* variable = GetParam() == FakeLlmProtocol::kOpenAi      ? "OPENAI_API_KEY"
                         : GetParam() == FakeLlmProtocol::kAnthropic ? "ANTHROPIC_API_KEY"
                         : GetParam() == FakeLlmProtocol::kGemini    ? "GEMINI_API_KEY"
                                                                     : "OLLAMA_API_KEY";
  EXPECT_THAT(error.what(), HasSubstr(variable));
  EXPECT_EQ(server_.requestCount(), 1U) << "401 is not retried";
}

TEST_P(LlmProtocolTest, ForbiddenIsAnAuthenticationError) {
  server_.enqueueError(403, "permission denied");
  EXPECT_EQ(failingCall().kind(), LlmErrorKind::kAuthentication);
}

TEST_P(LlmProtocolTest, UnknownModelIsModelNotFoundNamingTheModel) {
  server_.enqueueError(404, "model 'no-such-model' not found");
  auto llm = client("no-such-model");
  const LlmError error = expectLlmError([&] { llm->complete(planRequest(), StopCondition::never()); });
  EXPECT_EQ(error.kind(), LlmErrorKind::kModelNotFound);
  EXPECT_EQ(error.httpStatus(), 404);
  EXPECT_THAT(error.what(), HasSubstr("model \"no-such-model\" not found"));
  EXPECT_EQ(server_.requestCount(), 1U);
}

TEST_P(LlmProtocolTest, RateLimitHonoursRetryAfterThenSucceeds) {
  server_.enqueueError(429, "slow down", {{"Retry-After", "0.3"}});
  server_.enqueueAnswer(kPlanAnswer);
  const auto start = std::chrono::steady_clock::now();
  const LlmReply reply = client()->complete(planRequest(), StopCondition::never());
  EXPECT_GE(secondsSince(start), 0.3) << "Retry-After was not honoured";
  EXPECT_EQ(reply.attempts, 2);
  EXPECT_EQ(server_.requestCount(), 2U);
  EXPECT_EQ(server_.requests()[0].body, server_.requests()[1].body);
}

TEST_P(LlmProtocolTest, RetriesAreLoggedWithoutTheKey) {
  std::vector<std::string> messages;
  setLogSink([&messages](LogLevel, std::string_view message) { messages.emplace_back(message); });
  setLogLevel(LogLevel::kDebug);
  server_.enqueueError(503, std::string("overloaded, key ") + kTestApiKey);
  server_.enqueueAnswer(kPlanAnswer);
  client()->complete(planRequest(), StopCondition::never());
  setLogLevel(LogLevel::kWarn);
  setLogSink({});
  ASSERT_EQ(messages.size(), 1U);
  EXPECT_THAT(messages[0], HasSubstr("retrying in"));
  EXPECT_THAT(messages[0], HasSubstr("attempt 2 of 3"));
  EXPECT_THAT(messages[0], Not(HasSubstr(kTestApiKey)));
}

TEST_P(LlmProtocolTest, ServerErrorIsRetriedThenSucceeds) {
  server_.enqueueError(500, "internal error");
  server_.enqueueAnswer(kPlanAnswer);
  const LlmReply reply = client()->complete(planRequest(), StopCondition::never());
  EXPECT_EQ(reply.attempts, 2);
  EXPECT_EQ(json::parse(reply.content), json::parse(kPlanAnswer));
}

TEST_P(LlmProtocolTest, PersistentServerErrorGivesUpAfterMaxAttempts) {
  server_.setFallback(fakeError(GetParam(), 503, "overloaded"));
  const LlmError error = failingCall();
  EXPECT_EQ(error.kind(), LlmErrorKind::kServer);
  EXPECT_EQ(error.httpStatus(), 503);
  EXPECT_THAT(error.what(), HasSubstr("gave up after 3 attempts"));
  EXPECT_THAT(error.what(), HasSubstr("overloaded"));
  EXPECT_EQ(server_.requestCount(), 3U);
}

TEST_P(LlmProtocolTest, PersistentRateLimitEndsRateLimited) {
  server_.setFallback(fakeError(GetParam(), 429, "quota exceeded"));
  const LlmError error = failingCall();
  EXPECT_EQ(error.kind(), LlmErrorKind::kRateLimited);
  EXPECT_EQ(server_.requestCount(), 3U);
}

TEST_P(LlmProtocolTest, RetryAfterLongerThanAllowedEndsAtOnce) {
  options_.retry.maxRetryAfterSeconds = 5.0;
  server_.enqueueError(429, "come back tomorrow", {{"Retry-After", "86400"}});
  const auto start = std::chrono::steady_clock::now();
  const LlmError error = failingCall();
  EXPECT_EQ(error.kind(), LlmErrorKind::kRateLimited);
  EXPECT_THAT(error.what(), HasSubstr("asks to wait 86400 s, more than the 5 s allowed"));
  EXPECT_LT(secondsSince(start), 2.0);
}

TEST_P(LlmProtocolTest, HangPastTheTimeoutEndsInTimeoutQuickly) {
  options_.http.requestTimeoutSeconds = 0.3;
  options_.retry.maxAttempts = 2;
  server_.enqueueHang(30.0);
  server_.enqueueHang(30.0);
  const auto start = std::chrono::steady_clock::now();
  const LlmError error = failingCall();
  EXPECT_EQ(error.kind(), LlmErrorKind::kTimeout);
  EXPECT_THAT(error.what(), HasSubstr("within 0.3 s"));
  EXPECT_LT(secondsSince(start), 3.0);
  EXPECT_EQ(server_.requestCount(), 2U) << "a timeout is retried";
}

TEST_P(LlmProtocolTest, HangPastTheCallsTimeBudgetNamesTheBudget) {
  options_.http.requestTimeoutSeconds = 5.0;
  options_.retry.totalTimeoutSeconds = 0.3;
  server_.enqueueHang(30.0);
  const auto start = std::chrono::steady_clock::now();
  const LlmError error = failingCall();
  EXPECT_EQ(error.kind(), LlmErrorKind::kTimeout);
  EXPECT_THAT(error.what(), HasSubstr("no answer within the time budget of 0.3 s for one call (1 attempt; "));
  EXPECT_LT(secondsSince(start), 2.0);
}

TEST_P(LlmProtocolTest, CancellationDuringBackoffEndsTheWait) {
  options_.retry.totalTimeoutSeconds = 120.0;
  server_.enqueueError(429, "slow down", {{"Retry-After", "30"}});
  auto flag = std::make_shared<std::atomic<bool>>(false);
  std::thread canceller([flag] {
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
    flag->store(true);
  });
  const auto start = std::chrono::steady_clock::now();
  const LlmError error = failingCall(StopCondition::onCancel(flag));
  canceller.join();
  EXPECT_EQ(error.kind(), LlmErrorKind::kCancelled);
  EXPECT_THAT(error.what(), HasSubstr("cancelled while waiting to retry"));
  EXPECT_LT(secondsSince(start), 2.0);
  EXPECT_EQ(server_.requestCount(), 1U);
}

TEST_P(LlmProtocolTest, CancellationDuringARequestEndsIt) {
  server_.enqueueHang(30.0);
  auto flag = std::make_shared<std::atomic<bool>>(false);
  std::thread canceller([flag] {
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
    flag->store(true);
  });
  const auto start = std::chrono::steady_clock::now();
  const LlmError error = failingCall(StopCondition::onCancel(flag));
  canceller.join();
  EXPECT_EQ(error.kind(), LlmErrorKind::kCancelled);
  EXPECT_LT(secondsSince(start), 2.0);
}

TEST_P(LlmProtocolTest, DeadlineOfTheStopConditionEndsInTimeout) {
  server_.enqueueHang(30.0);
  const auto start = std::chrono::steady_clock::now();
  const LlmError error = failingCall(StopCondition::afterSeconds(0.2));
  EXPECT_EQ(error.kind(), LlmErrorKind::kTimeout);
  EXPECT_LT(secondsSince(start), 2.0);
}

TEST_P(LlmProtocolTest, AlreadyCancelledCallSendsNothing) {
  auto flag = std::make_shared<std::atomic<bool>>(true);
  EXPECT_EQ(failingCall(StopCondition::onCancel(flag)).kind(), LlmErrorKind::kCancelled);
  EXPECT_EQ(server_.requestCount(), 0U);
}

TEST_P(LlmProtocolTest, UnreachableServerIsATransportError) {
  options_.baseUrl = "http://127.0.0.1:1";
  options_.retry.maxAttempts = 2;
  const LlmError error = failingCall();
  EXPECT_EQ(error.kind(), LlmErrorKind::kTransport);
  EXPECT_THAT(error.what(), HasSubstr("cannot connect to http://127.0.0.1:1"));
  EXPECT_THAT(error.what(), HasSubstr("2 attempts"));
}

INSTANTIATE_TEST_SUITE_P(AllProtocols, LlmProtocolTest,
                         ::testing::ValuesIn(allFakeLlmProtocols()), protocolName);

}  // namespace
}  // namespace lang2manip::test
