#include "lang2manip/llm/llm_recording.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "fake_llm_server.hpp"
#include "lang2manip/llm/llm_client_factory.hpp"
#include "lang2manip/llm/llm_json.hpp"
#include "llm_test_support.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;

std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

class LlmRecordingTest : public ::testing::TestWithParam<FakeLlmProtocol> {
 protected:
  std::filesystem::path file() const { return directory_.path() / "calls.jsonl"; }
  TempDirectory directory_;
};

TEST_P(LlmRecordingTest, RecordThenReplayGivesTheSameAnswersWithoutNetwork) {
  std::string spec;
  std::vector<LlmReply> recorded;
  {
    FakeLlmServer server(GetParam());
    spec = server.spec("m1");
    server.enqueueAnswer(kPlanAnswer);
    server.enqueueTruncated(R"({"act)");
    server.enqueueError(404, "no such model");
    LlmClientOptions options = fastOptions(server);
    options.recordFile = file().string();
    auto client = makeLlmClient(spec, options);
    recorded.push_back(client->complete(planRequest("first task"), StopCondition::never()));
    recorded.push_back(client->complete(planRequest("second task"), StopCondition::never()));
    EXPECT_EQ(expectLlmError([&] { client->complete(planRequest("third"), StopCondition::never()); }).kind(),
              LlmErrorKind::kModelNotFound);
  }  // the server is gone from here on

  const std::string text = readFile(file());
  EXPECT_THAT(text, Not(HasSubstr(kTestApiKey)));
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3);
  const json firstLine = json::parse(text.substr(0, text.find('\n')));
  EXPECT_EQ(firstLine["client"], spec);
  EXPECT_EQ(firstLine["request"]["schema"], smallPlanSchema());
  EXPECT_EQ(firstLine["request"]["system"], "You plan robot manipulation.");
  EXPECT_EQ(firstLine["request"]["messages"][0]["content"], "first task");
  EXPECT_EQ(firstLine["request"]["seed"], 7);
  EXPECT_EQ(firstLine["reply"]["finish"], "stop");
  EXPECT_EQ(firstLine["reply"]["content"], recorded[0].content);
  EXPECT_GT(firstLine["reply"]["usage"]["outputTokens"].get<long>(), 0);

  LlmClientOptions options;
  options.replayFile = file().string();
  auto replay = makeLlmClient(spec, options);
  const LlmReply first = replay->complete(planRequest("first task"), StopCondition::never());
  EXPECT_TRUE(first.replayed);
  EXPECT_EQ(first.content, recorded[0].content);
  EXPECT_EQ(first.usage.inputTokens, recorded[0].usage.inputTokens);
  EXPECT_EQ(first.model, recorded[0].model);
  const LlmReply second = replay->complete(planRequest("second task"), StopCondition::never());
  EXPECT_EQ(second.finish, FinishReason::kLength);
  EXPECT_EQ(second.content, recorded[1].content);
  const LlmError error =
      expectLlmError([&] { replay->complete(planRequest("third"), StopCondition::never()); });
  EXPECT_EQ(error.kind(), LlmErrorKind::kModelNotFound);
  EXPECT_EQ(error.httpStatus(), 404);
}

std::string protocolName(const ::testing::TestParamInfo<FakeLlmProtocol>& parameter) {
  return fakeLlmProvider(parameter.param);
}

INSTANTIATE_TEST_SUITE_P(AllProtocols, LlmRecordingTest, ::testing::ValuesIn(allFakeLlmProtocols()),
                         protocolName);

class LlmReplayTest : public ::testing::Test {
 protected:
  /// One recorded reply for planRequest(task) by `client`.
  static std::string line(const std::string& task, const std::string& content,
                          const std::string& client = "openai:m") {
    LlmReply reply;
    reply.content = content;
    return json{{"client", client},
                {"request", llmRequestToJson(planRequest(task))},
                {"reply", llmReplyToJson(reply)}}
               .dump();
  }
  std::unique_ptr<LlmClient> replay(const std::string& spec = "openai:m") const {
    LlmClientOptions options;
    options.replayFile = file().string();
    return makeLlmClient(spec, options);
  }
  std::filesystem::path file() const { return directory_.path() / "calls.jsonl"; }
  TempDirectory directory_;
};

TEST_F(LlmReplayTest, RequestNotInTheFileIsAReplayMiss) {
  writeFile(file(), line("put the marker in the holder", "{}") + "\n");
  const LlmError error = expectLlmError(
      [&] { replay()->complete(planRequest("stack the boxes"), StopCondition::never()); });
  EXPECT_EQ(error.kind(), LlmErrorKind::kReplayMiss);
  EXPECT_THAT(error.what(), HasSubstr("no recorded answer for this request"));
  EXPECT_THAT(error.what(), HasSubstr("stack the boxes"));
  EXPECT_THAT(error.what(), HasSubstr("--llm-record"));
}

TEST_F(LlmReplayTest, AnyChangeOfTheRequestIsAMiss) {
  writeFile(file(), line("task", "{}") + "\n");
  LlmRequest request = planRequest("task");
  request.temperature = 0.5;
  EXPECT_EQ(expectLlmError([&] { replay()->complete(request, StopCondition::never()); }).kind(),
            LlmErrorKind::kReplayMiss);
  request = planRequest("task");
  request.schema["required"] = json::array();
  EXPECT_EQ(expectLlmError([&] { replay()->complete(request, StopCondition::never()); }).kind(),
            LlmErrorKind::kReplayMiss);
}

TEST_F(LlmReplayTest, RequestRecordedForAnotherModelIsAMissSayingSo) {
  writeFile(file(), line("task", "{}", "openai:other") + "\n");
  const LlmError error =
      expectLlmError([&] { replay("openai:m")->complete(planRequest("task"), StopCondition::never()); });
  EXPECT_EQ(error.kind(), LlmErrorKind::kReplayMiss);
  EXPECT_THAT(error.what(), HasSubstr("recorded for openai:other, not openai:m"));
}

TEST_F(LlmReplayTest, RepeatedRequestsGetTheAnswersInOrderThenTheLastAgain) {
  writeFile(file(), line("task", "\"one\"") + "\n" + line("task", "\"two\"") + "\n\n");
  auto client = replay();
  EXPECT_EQ(client->complete(planRequest("task"), StopCondition::never()).content, "\"one\"");
  EXPECT_EQ(client->complete(planRequest("task"), StopCondition::never()).content, "\"two\"");
  EXPECT_EQ(client->complete(planRequest("task"), StopCondition::never()).content, "\"two\"");
}

TEST_F(LlmReplayTest, MalformedLinesAreNamedByFileAndLine) {
  writeFile(file(), line("task", "{}") + "\n{not json\n");
  LlmError error = expectLlmError([&] { replay(); });
  EXPECT_EQ(error.kind(), LlmErrorKind::kConfiguration);
  EXPECT_THAT(error.what(), HasSubstr(file().string() + ":2: not a JSON object"));

  json bad = json::parse(line("task", "{}"));
  bad["request"]["messages"][0]["role"] = "robot";
  writeFile(file(), bad.dump() + "\n");
  error = expectLlmError([&] { replay(); });
  EXPECT_THAT(error.what(), HasSubstr(":1: request.messages[0].role: \"robot\""));

  bad = json::parse(line("task", "{}"));
  bad["reply"].erase("finish");
  writeFile(file(), bad.dump() + "\n");
  EXPECT_THAT(expectLlmError([&] { replay(); }).what(), HasSubstr(":1: reply.finish: missing"));

  bad = json::parse(line("task", "{}"));
  bad.erase("reply");
  bad["error"] = {{"kind", "exploded"}, {"message", "x"}};
  writeFile(file(), bad.dump() + "\n");
  EXPECT_THAT(expectLlmError([&] { replay(); }).what(),
              HasSubstr(":1: error.kind: \"exploded\" is not an LLM error kind"));
}

TEST_F(LlmReplayTest, MissingFileIsAConfigurationError) {
  const LlmError error = expectLlmError([&] { replay(); });
  EXPECT_EQ(error.kind(), LlmErrorKind::kConfiguration);
  EXPECT_THAT(error.what(), HasSubstr("cannot open the LLM replay file"));
}

TEST_F(LlmReplayTest, CancelledCallsAreNotRecorded) {
  FakeLlmServer server(FakeLlmProtocol::kOllama);
  LlmClientOptions options = fastOptions(server);
  options.recordFile = file().string();
  auto flag = std::make_shared<std::atomic<bool>>(true);
  auto client = makeLlmClient(server.spec(), options);
  EXPECT_EQ(expectLlmError([&] { client->complete(planRequest(), StopCondition::onCancel(flag)); }).kind(),
            LlmErrorKind::kCancelled);
  EXPECT_EQ(readFile(file()), "");
}

TEST_F(LlmReplayTest, UnwritableRecordFileIsAConfigurationError) {
  LlmClientOptions options;
  options.recordFile = (directory_.path() / "no-such-dir" / "calls.jsonl").string();
  const LlmError error = expectLlmError([&] { makeLlmClient("ollama:m", options); });
  EXPECT_EQ(error.kind(), LlmErrorKind::kConfiguration);
  EXPECT_THAT(error.what(), HasSubstr("cannot open the LLM record file"));
}

}  // namespace
}  // namespace lang2manip::test
