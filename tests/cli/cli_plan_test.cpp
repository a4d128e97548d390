// `lang2manip plan`: the offline planner, each LLM protocol against its fake server on loopback,
// record / replay, and the errors of the --llm flags.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_run.hpp"
#include "fake_llm_server.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;

const std::string kPaperTask = "--task \"put the marker and eraser in the holder\"";
const std::string kApiKey = "sk-cli-SECRET-4242";

/// Every variable an LLM client reads, unset so the host's settings never leak into a test.
const std::string kCleanEnvironment =
    "env -u OPENAI_API_KEY -u OPENAI_BASE_URL -u ANTHROPIC_API_KEY -u ANTHROPIC_BASE_URL -u GEMINI_API_KEY "
    "-u GOOGLE_API_KEY -u GEMINI_BASE_URL -u OLLAMA_HOST -u OLLAMA_API_KEY -u SSL_CERT_FILE";

json pickEntry(const std::string& object) {
  return {{"action", "pick"}, {"object", object}, {"params", nullptr}, {"refinements", nullptr}, {"planner", nullptr}};
}
json placeInHolder(const std::string& object) {
  return {{"action", "place"}, {"object", object}, {"params", {{"relation", "in"}, {"target", "holder"}}}};
}
const std::string kPaperPlan =
    json({{"actions", {pickEntry("marker"), placeInHolder("marker"), pickEntry("eraser"), placeInHolder("eraser")}}}).dump();

/// The environment that points `protocol`'s client at `server`, with a key where one is needed.
std::string environmentFor(const FakeLlmServer& server) {
  switch (server.protocol()) {
    case FakeLlmProtocol::kOpenAi:
      return kCleanEnvironment + " OPENAI_BASE_URL=" + server.baseUrl() + " OPENAI_API_KEY=" + kApiKey;
    case FakeLlmProtocol::kAnthropic:
      return kCleanEnvironment + " ANTHROPIC_BASE_URL=" + server.baseUrl() + " ANTHROPIC_API_KEY=" + kApiKey;
    case FakeLlmProtocol::kGemini:
      return kCleanEnvironment + " GEMINI_BASE_URL=" + server.baseUrl() + " GEMINI_API_KEY=" + kApiKey;
    case FakeLlmProtocol::kOllama:
      return kCleanEnvironment + " OLLAMA_HOST=" + server.baseUrl();
  }
  return kCleanEnvironment;
}

/// The paper's plan as `plan --json` prints it: 4 actions, pick/place marker then eraser, in the holder.
void expectPaperPlanJson(const std::string& output) {
  const json plan = json::parse(output, nullptr, false);
  ASSERT_TRUE(plan.is_object()) << output;
  ASSERT_TRUE(plan.contains("actions")) << output;
  const json& actions = plan["actions"];
  ASSERT_EQ(actions.size(), 4U) << output;
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"pick", "marker"}, {"place", "marker"}, {"pick", "eraser"}, {"place", "eraser"}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(actions[i]["action"], expected[i].first) << i;
    EXPECT_EQ(actions[i]["object"], expected[i].second) << i;
    if (expected[i].first == "place") {
      EXPECT_EQ(actions[i]["params"]["relation"], "in") << i;
      EXPECT_EQ(actions[i]["params"]["target"], "holder") << i;
    }
  }
}

TEST(CliPlan, OfflinePlansThePaperTaskAsFourNumberedActions) {
  const RunResult result = run("plan " + kPaperTask, true, kCleanEnvironment);
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("plan for \"put the marker and eraser in the holder\" by offline (4 actions):"));
  EXPECT_THAT(result.output, HasSubstr("  1. pick marker\n  2. place marker in holder\n  3. pick eraser\n"
                                       "  4. place eraser in holder\n"));
  EXPECT_THAT(result.output, HasSubstr("rounds: 1 round of 3; LLM calls: 0, tokens: 0 in / 0 out"));
}

TEST(CliPlan, OfflineJsonIsThePlanDocument) {
  const RunResult result = run("plan panda_desk " + kPaperTask + " --json", false, kCleanEnvironment);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  expectPaperPlanJson(result.output);
  // Exactly the plan document: every field of the schema, nothing else.
  const json plan = json::parse(result.output);
  EXPECT_EQ(plan.size(), 3U) << "actions, reasoning and goals";
  EXPECT_EQ(plan["actions"][0].size(), 5U);
  // The goal statement: what the instruction asks for at the end.
  ASSERT_EQ(plan["goals"].size(), 2U);
  EXPECT_EQ(plan["goals"][0], json({{"kind", "relation"}, {"object", "marker"}, {"relation", "in"}, {"target", "holder"},
                                    {"distance", nullptr}, {"displacement", nullptr}, {"configuration", nullptr},
                                    {"position", nullptr}, {"angle", nullptr}, {"region", nullptr}, {"members", nullptr},
                                    {"shape", nullptr}, {"heading", nullptr}, {"evenly_spaced", nullptr}}));
}

TEST(CliPlan, OfflinePlansOnOtherBuiltInProblems) {
  const RunResult result = run("plan ur5_desk " + kPaperTask + " --json", false, kCleanEnvironment);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  expectPaperPlanJson(result.output);
}

TEST(CliPlan, AnInstructionTheOfflinePlannerCannotGroundIsAClearErrorExitingAsRunDoes) {
  const RunResult result = run("plan --task \"put the flamingo in the holder\"", true, kCleanEnvironment);
  EXPECT_EQ(result.exitCode, 2) << "the task could not be done, as `run` says of it";
  EXPECT_THAT(result.output, HasSubstr("lang2manip: plan: offline could not plan"));
  EXPECT_THAT(result.output, HasSubstr("flamingo"));
  EXPECT_THAT(result.output, Not(HasSubstr("attempts:"))) << "the error is said once";
  const TempDirectory directory;
  EXPECT_EQ(run("run --task \"put the flamingo in the holder\" --out " + directory.path().string(), true, kCleanEnvironment).exitCode, 2);
}

TEST(CliPlan, EachProtocolPlansThePaperTaskThroughItsFakeServer) {
  for (const FakeLlmProtocol protocol : allFakeLlmProtocols()) {
    SCOPED_TRACE(fakeLlmProvider(protocol));
    FakeLlmServer server(protocol);
    server.enqueueAnswer(kPaperPlan);
    const RunResult asJson = run("plan " + kPaperTask + " --llm " + server.spec("test-model") + " --json", false,
                               environmentFor(server));
    ASSERT_EQ(asJson.exitCode, 0) << asJson.output;
    expectPaperPlanJson(asJson.output);
    ASSERT_EQ(server.requestCount(), 1U);
    const FakeReceivedRequest received = server.requests()[0];
    EXPECT_THAT(received.body, HasSubstr("put the marker and eraser in the holder"));
    EXPECT_THAT(received.body, HasSubstr("RRTConnect")) << "planner names come from the registry";

    server.enqueueAnswer(kPaperPlan);
    const RunResult text = run("plan " + kPaperTask + " --llm " + server.spec("test-model"), true,
                               environmentFor(server));
    EXPECT_EQ(text.exitCode, 0) << text.output;
    EXPECT_THAT(text.output, HasSubstr("by " + server.spec("test-model") + " (4 actions)"));
    EXPECT_THAT(text.output, HasSubstr("4. place eraser in holder"));
    EXPECT_THAT(text.output, HasSubstr("rounds: 1 round of 3; LLM calls: 1, tokens: "));
    EXPECT_THAT(text.output, Not(HasSubstr(kApiKey)));
  }
}

TEST(CliPlan, BaseUrlFlagOverridesTheEnvironmentAndRepairsAreReported) {
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  server.enqueueAnswer("Sure! First I pick the marker.");
  server.enqueueAnswer(kPaperPlan);
  const std::string environment =
      kCleanEnvironment + " OPENAI_BASE_URL=http://127.0.0.1:1/v1 OPENAI_API_KEY=" + kApiKey;
  const RunResult result = run("plan " + kPaperTask + " --llm openai:test-model --llm-base-url " + server.baseUrl(),
                               true, environment);
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("round 1 rejected (unusable answer): "));
  EXPECT_THAT(result.output, HasSubstr("no JSON object found"));
  EXPECT_THAT(result.output, HasSubstr("rounds: 2 rounds of 3; LLM calls: 2"));
  EXPECT_EQ(server.requestCount(), 2U);
}

TEST(CliPlan, FailingEveryRoundExitsNonZeroListingTheAttempts) {
  FakeLlmServer server(FakeLlmProtocol::kOllama);
  server.enqueueAnswer("I would rather not.");
  server.enqueueAnswer(R"({"actions": [{"action": "place", "object": "marker", "params": {"relation": "in", "target": "holder"}}]})");
  const RunResult result =
      run("plan " + kPaperTask + " --llm ollama:llama3.1 --rounds 2", true, environmentFor(server));
  EXPECT_EQ(result.exitCode, 2) << result.output;
  EXPECT_THAT(result.output, HasSubstr("lang2manip: plan: no acceptable plan from ollama:llama3.1 after 2 rounds"));
  EXPECT_THAT(result.output, HasSubstr("round 1 (unusable answer)"));
  EXPECT_THAT(result.output, HasSubstr("round 2 (invalid plan)"));
  EXPECT_THAT(result.output, HasSubstr("marker is not held"));
}

TEST(CliPlan, RecordThenReplayWithoutServerOrKeyGivesTheSamePlan) {
  const TempDirectory directory;
  const std::string file = (directory.path() / "calls.jsonl").string();
  std::string recorded;
  {
    FakeLlmServer server(FakeLlmProtocol::kAnthropic);
    server.enqueueAnswer(kPaperPlan);
    const RunResult result = run("plan " + kPaperTask + " --llm anthropic:claude-test --json --llm-record " + file,
                                 false, environmentFor(server));
    ASSERT_EQ(result.exitCode, 0) << result.output;
    recorded = result.output;
  }
  EXPECT_THAT(readFileText(file), Not(HasSubstr(kApiKey))) << "keys are never recorded";
  // The server is gone and no key or base URL is set.
  const RunResult replayed =
      run("plan " + kPaperTask + " --llm anthropic:claude-test --json --llm-replay " + file, false, kCleanEnvironment);
  ASSERT_EQ(replayed.exitCode, 0) << replayed.output;
  EXPECT_EQ(replayed.output, recorded);
  expectPaperPlanJson(replayed.output);
  const RunResult text =
      run("plan " + kPaperTask + " --llm anthropic:claude-test --llm-replay " + file, true, kCleanEnvironment);
  EXPECT_EQ(text.exitCode, 0) << text.output;
  EXPECT_THAT(text.output, HasSubstr("by anthropic:claude-test (replayed from " + file + ")"));
}

TEST(CliPlan, ReplayMissIsAClearError) {
  const TempDirectory directory;
  const std::string file = (directory.path() / "calls.jsonl").string();
  {
    FakeLlmServer server(FakeLlmProtocol::kGemini);
    server.enqueueAnswer(kPaperPlan);
    ASSERT_EQ(run("plan " + kPaperTask + " --llm gemini:test --llm-record " + file, true, environmentFor(server)).exitCode, 0);
  }
  const RunResult result =
      run("plan --task \"put the eraser in the holder\" --llm gemini:test --llm-replay " + file, true, kCleanEnvironment);
  EXPECT_EQ(result.exitCode, 2) << "as `run` ends when its planner has no answer";
  EXPECT_THAT(result.output, HasSubstr("no recorded answer for this request (1 calls recorded"));
  EXPECT_THAT(result.output, HasSubstr("Record it first with --llm-record"));
  const RunResult missingFile = run("plan " + kPaperTask + " --llm gemini:test --llm-replay " +
                                        (directory.path() / "nope.jsonl").string(),
                                    true, kCleanEnvironment);
  EXPECT_EQ(missingFile.exitCode, 1);
  EXPECT_THAT(missingFile.output, HasSubstr("nope.jsonl: LLM replay file does not exist"));
}

TEST(CliPlan, UnknownLlmListsTheValidChoices) {
  for (const char* spec : {"gpt4", "openia:gpt-4o", "Offline"}) {
    const RunResult result = run("plan " + kPaperTask + " --llm " + spec, true, kCleanEnvironment);
    EXPECT_EQ(result.exitCode, 1) << spec;
    EXPECT_THAT(result.output, HasSubstr(std::string("--llm \"") + spec + "\": unknown task planner")) << spec;
    EXPECT_THAT(result.output, HasSubstr("offline (the default, no network) or PROVIDER:MODEL with PROVIDER one of "
                                         "openai, anthropic, gemini, ollama"));
  }
  const RunResult noModel = run("plan " + kPaperTask + " --llm openai:", true, kCleanEnvironment);
  EXPECT_EQ(noModel.exitCode, 1);
  EXPECT_THAT(noModel.output, HasSubstr("no model named; write openai:MODEL"));
}

TEST(CliPlan, MissingApiKeyNamesTheVariable) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"anthropic:claude-test", "set ANTHROPIC_API_KEY"},
      {"gemini:gemini-test", "set GEMINI_API_KEY or GOOGLE_API_KEY"},
      {"openai:gpt-4o", "set OPENAI_API_KEY"}};
  for (const auto& [spec, message] : cases) {
    const RunResult result = run("plan " + kPaperTask + " --llm " + spec, true, kCleanEnvironment);
    EXPECT_EQ(result.exitCode, 1) << spec;
    EXPECT_THAT(result.output, HasSubstr("no API key; " + message)) << spec;
    EXPECT_THAT(result.output, Not(HasSubstr("option"))) << "there is no option for a key: " << spec;
  }
}

TEST(CliPlan, LlmFlagsNeedAnLlmPlanner) {
  for (const char* flags : {"--llm-replay x.jsonl", "--llm-record x.jsonl", "--llm-base-url http://127.0.0.1:9",
                            "--llm-timeout 5"}) {
    const RunResult result = run("plan " + kPaperTask + " " + flags, true, kCleanEnvironment);
    EXPECT_EQ(result.exitCode, 1) << flags;
    EXPECT_THAT(result.output, HasSubstr("needs an LLM task planner (--llm PROVIDER:MODEL)")) << flags;
  }
}

TEST(CliPlan, BadRoundsAndTimeoutsAreRejected) {
  RunResult result = run("plan " + kPaperTask + " --rounds 0", true, kCleanEnvironment);
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("--rounds 0: must be at least 1"));
  for (const char* timeout : {"0", "-2"}) {
    result = run("plan " + kPaperTask + " --llm ollama:m --llm-timeout " + timeout, true, kCleanEnvironment);
    EXPECT_EQ(result.exitCode, 1) << timeout;
    EXPECT_THAT(result.output, HasSubstr(std::string("--llm-timeout ") + timeout + ": must be a positive number"));
  }
  result = run("plan --llm ollama:m", true, kCleanEnvironment);
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("--task is required"));
}

TEST(CliPlan, ResponseSizeLimitIsAnOptionAndAClearError) {
  FakeLlmServer server(FakeLlmProtocol::kOllama);
  server.enqueueAnswer(R"({"reasoning": ")" + std::string(10000, 'x') + R"(", "actions": []})");
  RunResult result =
      run("plan " + kPaperTask + " --llm ollama:m --llm-max-response-bytes 2000", true, environmentFor(server));
  EXPECT_EQ(result.exitCode, 2) << result.output;
  EXPECT_THAT(result.output, HasSubstr("is larger than the response size limit of 2000 bytes"));
  for (const char* bytes : {"0", "-5"}) {
    result = run("plan " + kPaperTask + " --llm ollama:m --llm-max-response-bytes " + bytes, true, kCleanEnvironment);
    EXPECT_EQ(result.exitCode, 1) << bytes;
    EXPECT_THAT(result.output, HasSubstr(std::string("--llm-max-response-bytes ") + bytes + ": must be a positive"));
  }
  result = run("plan " + kPaperTask + " --llm-max-response-bytes 100", true, kCleanEnvironment);
  EXPECT_THAT(result.output, HasSubstr("needs an LLM task planner"));
}

TEST(CliPlan, TokenCountsTheServerDidNotGiveArePrintedAsUnknown) {
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  FakeHttpResponse noUsage;
  noUsage.body = json{{"choices", {{{"message", {{"role", "assistant"}, {"content", kPaperPlan}}}, {"finish_reason", "stop"}}}},
                      {"usage", {{"prompt_tokens", -1}, {"completion_tokens", 1e300}}}}
                     .dump();
  server.enqueue(noUsage);
  const RunResult result = run("plan " + kPaperTask + " --llm openai:test-model", true, environmentFor(server));
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("tokens: unknown in / unknown out"));
  EXPECT_THAT(result.output, Not(HasSubstr("-9223372036854775808")));
}

TEST(CliPlan, HangingServerEndsAtTheTimeoutWithAClearError) {
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  for (int i = 0; i < 4; ++i) server.enqueueHang(30.0);
  const auto start = std::chrono::steady_clock::now();
  const RunResult result =
      run("plan " + kPaperTask + " --llm openai:test-model --llm-timeout 0.5", true, environmentFor(server));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(result.exitCode, 2) << result.output;
  EXPECT_LT(seconds, 10.0);
  EXPECT_THAT(result.output, HasSubstr("lang2manip: plan: the LLM call of openai:test-model failed"));
  // Whichever fires first, the per-attempt limit or the call's budget, the message gives the 0.5 s.
  EXPECT_THAT(result.output, ::testing::ContainsRegex("(within|time budget of) 0.5 s"));
  EXPECT_THAT(result.output, Not(HasSubstr(kApiKey)));
}

TEST(CliPlan, UnauthorizedNamesTheKeyVariableWithoutPrintingTheKey) {
  FakeLlmServer server(FakeLlmProtocol::kAnthropic);
  server.enqueueError(401, "invalid x-api-key");
  const RunResult result = run("plan " + kPaperTask + " --llm anthropic:claude-test", true, environmentFor(server));
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_THAT(result.output, HasSubstr("check the API key in ANTHROPIC_API_KEY"));
  EXPECT_THAT(result.output, Not(HasSubstr(kApiKey)));
  EXPECT_EQ(server.requestCount(), 1U);
}

}  // namespace
}  // namespace lang2manip::test
