// How the OpenAI-compatible client copes with servers that support less than OpenAI does.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fake_llm_server.hpp"
#include "lang2manip/llm/llm_client_factory.hpp"
#include "llm_test_support.hpp"

namespace lang2manip::test {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

TEST(OpenAiCompatibility, FallsBackToJsonObjectWhenJsonSchemaIsRejected) {
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  server.enqueueError(400, "response_format type json_schema is not supported by this server");
  server.enqueueAnswer(kPlanAnswer);
  server.enqueueAnswer(kPlanAnswer);
  auto client = makeLlmClient(server.spec(), fastOptions(server));
  EXPECT_EQ(client->complete(planRequest(), StopCondition::never()).attempts, 2);
  const json second = server.requests().at(1).json;
  EXPECT_EQ(second["response_format"], json({{"type", "json_object"}}));
  EXPECT_THAT(second["messages"][0]["content"].get<std::string>(),
              HasSubstr("follows this JSON Schema"));
  EXPECT_THAT(second["messages"][0]["content"].get<std::string>(), HasSubstr("\"actions\""));
  // The client remembers: the next call goes straight to json_object.
  EXPECT_EQ(client->complete(planRequest(), StopCondition::never()).attempts, 1);
  EXPECT_EQ(server.requests().at(2).json["response_format"]["type"], "json_object");
}

TEST(OpenAiCompatibility, SwitchesToMaxCompletionTokensAndDropsTemperatureWhenAsked) {
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  server.enqueueError(400, "Unsupported parameter: 'max_tokens' is not supported with this model. "
                           "Use 'max_completion_tokens' instead.");
  server.enqueueError(400, "Unsupported value: 'temperature' does not support 0 with this model.");
  server.enqueueAnswer(kPlanAnswer);
  auto client = makeLlmClient(server.spec(), fastOptions(server));
  EXPECT_EQ(client->complete(planRequest(), StopCondition::never()).attempts, 3);
  const json last = server.requests().at(2).json;
  EXPECT_EQ(last["max_completion_tokens"], 512);
  EXPECT_FALSE(last.contains("max_tokens"));
  EXPECT_FALSE(last.contains("temperature"));
  EXPECT_EQ(last["response_format"]["type"], "json_schema");
}

TEST(OpenAiCompatibility, RejectionItCannotAdaptToIsAConfigurationError) {
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  server.enqueueError(400, "messages: too long");
  auto client = makeLlmClient(server.spec(), fastOptions(server));
  const LlmError error =
      expectLlmError([&] { client->complete(planRequest(), StopCondition::never()); });
  EXPECT_EQ(error.kind(), LlmErrorKind::kConfiguration);
  EXPECT_EQ(error.httpStatus(), 400);
  EXPECT_THAT(error.what(), HasSubstr("the server rejected the request (HTTP 400 Bad Request: messages: too long)"));
  EXPECT_EQ(server.requestCount(), 1U);
}

TEST(AnthropicAnswers, TextInsteadOfTheToolIsTheContentForTheCallerToJudge) {
  FakeLlmServer server(FakeLlmProtocol::kAnthropic);
  server.enqueueAnswer("Here is my plan: pick the marker.");
  auto client = makeLlmClient(server.spec(), fastOptions(server));
  const LlmReply reply = client->complete(planRequest(), StopCondition::never());
  EXPECT_EQ(reply.content, "Here is my plan: pick the marker.");
  EXPECT_EQ(reply.finish, FinishReason::kStop);
}

TEST(AnthropicAnswers, NeitherToolNorTextIsABadResponse) {
  FakeLlmServer server(FakeLlmProtocol::kAnthropic);
  FakeHttpResponse empty;
  empty.body = R"({"content": [], "stop_reason": "end_turn"})";
  server.enqueue(empty);
  auto client = makeLlmClient(server.spec(), fastOptions(server));
  const LlmError error =
      expectLlmError([&] { client->complete(planRequest(), StopCondition::never()); });
  EXPECT_EQ(error.kind(), LlmErrorKind::kBadResponse);
  EXPECT_THAT(error.what(), HasSubstr("no tool_use block named \"plan\" and no text"));
}

TEST(GeminiAnswers, SafetyStopIsAContentFilter) {
  FakeLlmServer server(FakeLlmProtocol::kGemini);
  FakeHttpResponse blocked;
  blocked.body = R"({"candidates":[{"finishReason":"SAFETY","index":0}]})";
  server.enqueue(blocked);
  auto client = makeLlmClient(server.spec(), fastOptions(server));
  const LlmReply reply = client->complete(planRequest(), StopCondition::never());
  EXPECT_EQ(reply.finish, FinishReason::kContentFilter);
  EXPECT_THAT(reply.refusal, HasSubstr("SAFETY"));
}

TEST(FakeLlmServer, UnknownPathIsA404AndUnscriptedRequestsA500) {
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  LlmClientOptions options = fastOptions(server);
  options.baseUrl = "http://127.0.0.1:" + std::to_string(server.port());  // no /v1
  const LlmError wrongPath = expectLlmError(
      [&] { makeLlmClient(server.spec(), options)->complete(planRequest(), StopCondition::never()); });
  EXPECT_EQ(wrongPath.kind(), LlmErrorKind::kModelNotFound);
  EXPECT_THAT(wrongPath.what(), HasSubstr("unknown path /chat/completions"));
  options.retry.maxAttempts = 1;
  options.baseUrl = server.baseUrl();
  const LlmError unscripted = expectLlmError(
      [&] { makeLlmClient(server.spec(), options)->complete(planRequest(), StopCondition::never()); });
  EXPECT_THAT(unscripted.what(), HasSubstr("no scripted response left"));
}

}  // namespace
}  // namespace lang2manip::test
