#include "lang2manip/llm/llm_recording.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <functional>
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
  EXPECT_THAT(error.what(), HasSubstr(file().string() + ":2: record: not valid JSON: parse error at line 1, column 3"));

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

/// Each malformed line, as line 2 after a good one: a configuration error "FILE:2: ..." saying
/// what is wrong -- never a crash (a deep line used to overflow the stack), a silent default or
/// an unbounded read.
TEST_F(LlmReplayTest, EveryKindOfMalformedLineIsNamedByFileLineAndProblem) {
  const json good = json::parse(line("task", "{}"));
  const auto with = [&](const std::function<void(json&)>& change) {
    json changed = good;
    change(changed);
    return changed.dump();
  };
  std::string deepSchema = with([](json& l) { l["request"]["schema"] = "DEEP"; });
  deepSchema.replace(deepSchema.find("\"DEEP\""), 6, std::string(100000, '[') + std::string(100000, ']'));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {deepSchema, "record: nested deeper than 128 levels"},
      {"{\"client\": \"openai:m\", ", "record: not valid JSON: parse error at line 1, column 24"},
      {std::string(100000, '[') + std::string(100000, ']'), "record: nested deeper than 128 levels (at byte 128)"},
      {"{\"client\":\"openai:m\",\"request\":" + std::string(100000, '{') , "record: nested deeper than 128 levels"},
      {"[1, 2]", "record: expected a JSON object {\"client\", \"request\", \"reply\" or \"error\"}, got array [1,2]"},
      {"{\"n\": 1e400}", "record: not valid JSON: number overflow"},
      {"\"\xff\"", "record: not valid JSON: "},
      {with([](json& l) { l.erase("request"); }), "request: missing"},
      {with([](json& l) { l["client"] = 5; }), "client: missing or not a string"},
      {with([](json& l) { l["request"]["messages"] = "hi"; }), "request.messages: expected an array"},
      {with([](json& l) { l["request"]["maxTokens"] = 1e10; }), "request.maxTokens: expected an integer in [1, 2147483647], got 10000000000.0"},
      {with([](json& l) { l["request"]["maxTokens"] = 4294967297ULL; }), "request.maxTokens: expected an integer in [1, 2147483647]"},
      {with([](json& l) { l["reply"]["usage"]["inputTokens"] = -1; }), "reply.usage.inputTokens: expected an integer in [0, 9007199254740992], got -1"},
      {with([](json& l) { l["reply"]["usage"]["outputTokens"] = "12"; }), "reply.usage.outputTokens: expected an integer"},
      {with([](json& l) { l["reply"]["attempts"] = 0; }), "reply.attempts: expected an integer in [1, 2147483647], got 0"},
      {with([](json& l) { l["reply"]["content"] = json::array(); }), "reply.content: expected a string"},
      {with([](json& l) { l.erase("reply"); }), "neither reply nor error"},
      {with([](json& l) { l.erase("reply"); l["error"] = {{"kind", "timeout"}}; }), "error.message: missing or not a string"},
  };
  for (const auto& [text, expected] : cases) {
    writeFile(file(), good.dump() + "\n" + text + "\n");
    const LlmError error = expectLlmError([&] { replay(); });
    EXPECT_EQ(error.kind(), LlmErrorKind::kConfiguration);
    EXPECT_THAT(error.what(), HasSubstr(file().string() + ":2: " + expected)) << text.substr(0, 80);
    EXPECT_LT(std::string(error.what()).size(), 400U) << "messages quote bounded parts only";
  }
}

TEST_F(LlmReplayTest, ALineLongerThanTheLimitIsRefusedWithoutReadingItWhole) {
  writeFile(file(), line("task", "{}") + "\n" + line("task", "\"" + std::string(5000, 'x') + "\"") + "\n");
  const JsonLimits limits{kDefaultJsonMaxDepth, 2000};
  const LlmError error = expectLlmError([&] { makeReplayLlmClient(file().string(), "", limits); });
  EXPECT_EQ(error.kind(), LlmErrorKind::kConfiguration);
  EXPECT_THAT(error.what(), HasSubstr(file().string() + ":2: line longer than 2000 bytes, the limit for one recorded call"));
  // The default limit reads the same file.
  EXPECT_NO_THROW(makeReplayLlmClient(file().string()));
  // A directory is not a replay file.
  EXPECT_THAT(expectLlmError([&] { makeReplayLlmClient(directory_.path().string()); }).what(),
              HasSubstr("is a directory"));
  // Nor is a device, which would never end.
  EXPECT_THAT(expectLlmError([&] { makeReplayLlmClient("/dev/zero"); }).what(),
              HasSubstr("/dev/zero: LLM replay file is a character device, not a regular file"));
}

TEST_F(LlmReplayTest, UnknownTokenCountsRoundTripAsNull) {
  LlmReply reply;
  reply.content = "{}";
  reply.usage.inputTokens = 12;
  const json written = llmReplyToJson(reply);
  EXPECT_EQ(written["usage"]["inputTokens"], 12);
  EXPECT_TRUE(written["usage"]["outputTokens"].is_null());
  const LlmReply read = llmReplyFromJson(written);
  EXPECT_EQ(read.usage.inputTokens, 12);
  EXPECT_FALSE(read.usage.outputTokens.has_value());
}

TEST_F(LlmReplayTest, MissingFileIsAConfigurationError) {
  const LlmError error = expectLlmError([&] { replay(); });
  EXPECT_EQ(error.kind(), LlmErrorKind::kConfiguration);
  EXPECT_THAT(error.what(), HasSubstr(": LLM replay file does not exist"));
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

TEST_F(LlmReplayTest, ARecordFileThatIsALinkOrAFifoIsRefusedNotWrittenThrough) {
  const std::filesystem::path elsewhere = directory_.path() / "elsewhere";
  std::ofstream(elsewhere) << "precious\n";
  std::filesystem::create_symlink(elsewhere, file());
  LlmClientOptions options;
  options.recordFile = file().string();
  EXPECT_THAT(expectLlmError([&] { makeLlmClient("ollama:m", options); }).what(), HasSubstr("it is a symbolic link"));
  EXPECT_EQ(readFile(elsewhere), "precious\n");
  std::filesystem::remove(file());
  ASSERT_EQ(::mkfifo(file().c_str(), 0600), 0);
  EXPECT_THAT(expectLlmError([&] { makeLlmClient("ollama:m", options); }).what(), ::testing::AnyOf(HasSubstr("not a regular file"), HasSubstr("No such device")));
}

}  // namespace
}  // namespace lang2manip::test
