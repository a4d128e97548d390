#include "lang2manip/llm/llm_client_factory.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>

#include "fake_llm_server.hpp"
#include "lang2manip/core/error.hpp"
#include "llm_test_support.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;

/// Options reading variables from `variables` only.
LlmClientOptions withEnvironment(std::map<std::string, std::string> variables) {
  LlmClientOptions options;
  options.environment = [variables = std::move(variables)](const std::string& name) {
    const auto found = variables.find(name);
    return found == variables.end() ? std::nullopt : std::optional<std::string>(found->second);
  };
  options.retry.maxAttempts = 1;
  return options;
}

LlmError configurationError(const std::string& spec, const LlmClientOptions& options) {
  const LlmError error = expectLlmError([&] { makeLlmClient(spec, options); });
  EXPECT_EQ(error.kind(), LlmErrorKind::kConfiguration) << error.what();
  return error;
}

TEST(LlmClientFactory, UnknownProviderListsTheValidOnes) {
  const LlmError error = configurationError("mistral:large", withEnvironment({}));
  EXPECT_THAT(error.what(), HasSubstr("unknown LLM provider \"mistral\""));
  EXPECT_THAT(error.what(), HasSubstr("openai, anthropic, gemini, ollama"));
}

TEST(LlmClientFactory, SpecWithoutProviderOrModelIsRejected) {
  EXPECT_THAT(configurationError("gpt-4o", withEnvironment({})).what(),
              HasSubstr("is not PROVIDER:MODEL"));
  EXPECT_THAT(configurationError("openai:", withEnvironment({})).what(),
              HasSubstr("names no model"));
}

TEST(LlmClientFactory, MissingKeyNamesTheVariableToSet) {
  EXPECT_THAT(configurationError("openai:gpt-4o", withEnvironment({})).what(),
              HasSubstr("set OPENAI_API_KEY"));
  EXPECT_THAT(configurationError("anthropic:claude", withEnvironment({})).what(),
              HasSubstr("set ANTHROPIC_API_KEY"));
  EXPECT_THAT(configurationError("gemini:flash", withEnvironment({})).what(),
              HasSubstr("set GEMINI_API_KEY or GOOGLE_API_KEY"));
  EXPECT_THAT(configurationError("anthropic:claude", withEnvironment({{"ANTHROPIC_API_KEY", ""}})).what(),
              HasSubstr("set ANTHROPIC_API_KEY"))
      << "an empty variable counts as unset";
}

TEST(LlmClientFactory, NamesClientsAfterTheSpec) {
  EXPECT_EQ(makeLlmClient("openai:gpt-4o", withEnvironment({{"OPENAI_API_KEY", "k"}}))->name(),
            "openai:gpt-4o");
  EXPECT_EQ(makeLlmClient("ollama:llama3.1", withEnvironment({}))->name(), "ollama:llama3.1");
}

TEST(LlmClientFactory, BadBaseUrlsAreConfigurationErrors) {
  LlmClientOptions options = withEnvironment({{"OPENAI_API_KEY", "k"}});
  options.baseUrl = "ftp://example.com";
  EXPECT_THAT(configurationError("openai:m", options).what(), HasSubstr("not http or https"));
  options.baseUrl = "localhost:8080/v1";
  EXPECT_THAT(configurationError("openai:m", options).what(), HasSubstr("no scheme"));
  options.baseUrl = "http://host:99999";
  EXPECT_THAT(configurationError("openai:m", options).what(), HasSubstr("out of range"));
  EXPECT_THAT(configurationError("anthropic:m", withEnvironment({{"ANTHROPIC_API_KEY", "k"},
                                                                 {"ANTHROPIC_BASE_URL", "http://"}}))
                  .what(),
              HasSubstr("ANTHROPIC_BASE_URL"));
}

TEST(LlmClientFactory, OutOfRangeOptionsAreConfigurationErrors) {
  LlmClientOptions options = withEnvironment({});
  options.retry.maxAttempts = 0;
  EXPECT_THAT(configurationError("ollama:m", options).what(), HasSubstr("maxAttempts"));
  options = withEnvironment({});
  options.http.requestTimeoutSeconds = -1.0;
  EXPECT_THAT(configurationError("ollama:m", options).what(), HasSubstr("requestTimeoutSeconds"));
}

TEST(LlmClientFactory, RecordAndReplayTogetherAreRejected) {
  LlmClientOptions options = withEnvironment({});
  options.recordFile = "a.jsonl";
  options.replayFile = "b.jsonl";
  EXPECT_THAT(configurationError("ollama:m", options).what(), HasSubstr("cannot be used together"));
}

TEST(LlmClientFactory, ReadsBaseUrlAndKeyFromTheEnvironment) {
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  server.enqueueAnswer(kPlanAnswer);
  auto client = makeLlmClient(
      "openai:m", withEnvironment({{"OPENAI_BASE_URL", server.baseUrl()}, {"OPENAI_API_KEY", "env-key"}}));
  client->complete(planRequest(), StopCondition::never());
  EXPECT_EQ(server.requests().at(0).header("Authorization"), "Bearer env-key");
}

TEST(LlmClientFactory, OptionsOverrideTheEnvironment) {
  FakeLlmServer server(FakeLlmProtocol::kAnthropic);
  server.enqueueAnswer(kPlanAnswer);
  LlmClientOptions options = withEnvironment(
      {{"ANTHROPIC_BASE_URL", "http://127.0.0.1:1"}, {"ANTHROPIC_API_KEY", "env-key"}});
  options.baseUrl = server.baseUrl();
  options.apiKey = "option-key";
  makeLlmClient("anthropic:m", options)->complete(planRequest(), StopCondition::never());
  EXPECT_EQ(server.requests().at(0).header("x-api-key"), "option-key");
}

TEST(LlmClientFactory, GeminiFallsBackToGoogleApiKey) {
  FakeLlmServer server(FakeLlmProtocol::kGemini);
  server.enqueueAnswer(kPlanAnswer);
  auto client = makeLlmClient("gemini:flash", withEnvironment({{"GEMINI_BASE_URL", server.baseUrl()},
                                                               {"GOOGLE_API_KEY", "google-key"}}));
  client->complete(planRequest(), StopCondition::never());
  EXPECT_EQ(server.requests().at(0).header("x-goog-api-key"), "google-key");
  EXPECT_EQ(server.requests().at(0).path, "/v1beta/models/flash:generateContent");
}

TEST(LlmClientFactory, OllamaHostWithoutSchemeMeansHttpAndNoKeyIsNeeded) {
  FakeLlmServer server(FakeLlmProtocol::kOllama);
  server.enqueueAnswer(kPlanAnswer);
  auto client = makeLlmClient(
      "ollama:llama3.1", withEnvironment({{"OLLAMA_HOST", "127.0.0.1:" + std::to_string(server.port())}}));
  client->complete(planRequest(), StopCondition::never());
  EXPECT_EQ(server.requests().at(0).header("Authorization"), "");
}

TEST(LlmClientFactory, OpenAiCompatibleLocalServerNeedsNoKey) {
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  server.enqueueAnswer(kPlanAnswer);
  auto client = makeLlmClient("openai:local", withEnvironment({{"OPENAI_BASE_URL", server.baseUrl()}}));
  client->complete(planRequest(), StopCondition::never());
  EXPECT_EQ(server.requests().at(0).header("Authorization"), "");
}

TEST(LlmClientFactory, MalformedRequestsAreInputErrors) {
  auto client = makeLlmClient("ollama:m", withEnvironment({}));
  LlmRequest request = planRequest();
  request.messages.clear();
  EXPECT_THROW(client->complete(request, StopCondition::never()), InputError);
  request = planRequest();
  request.schemaName = "plan with spaces";
  EXPECT_THROW(client->complete(request, StopCondition::never()), InputError);
  request = planRequest();
  request.maxTokens = 0;
  EXPECT_THROW(client->complete(request, StopCondition::never()), InputError);
}

}  // namespace
}  // namespace lang2manip::test
