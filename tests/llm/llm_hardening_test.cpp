// Hostile or broken servers, for every protocol: deeply nested bodies, odd token counts,
// oversized answers, redirects and empty error bodies, servers echoing the API key. Each ends in
// a clear error or a well-defined value -- never a crash, a hang, an unbounded buffer or a leak.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <sstream>

#include "fake_llm_server.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/llm/http_llm_client.hpp"
#include "lang2manip/llm/llm_client_factory.hpp"
#include "lang2manip/llm/secret_redaction.hpp"
#include "llm_test_support.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

using nlohmann::json;
using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::Not;


/// A successful answer body with the token counts `input` and `output` (JSON values; discarded
/// = the field is left out) where the protocol puts them.
std::string bodyWithUsage(FakeLlmProtocol protocol, const json& input, const json& output) {
  json usage = json::object();
  const auto put = [&usage](const char* key, const json& value) {
    if (!value.is_discarded()) usage[key] = value;
  };
  switch (protocol) {
    case FakeLlmProtocol::kOpenAi:
      put("prompt_tokens", input);
      put("completion_tokens", output);
      return json{{"model", "test-model"},
                  {"choices", {{{"index", 0}, {"message", {{"role", "assistant"}, {"content", "{}"}}},
                                {"finish_reason", "stop"}}}},
                  {"usage", usage}}
          .dump();
    case FakeLlmProtocol::kAnthropic:
      put("input_tokens", input);
      put("output_tokens", output);
      return json{{"model", "test-model"},
                  {"content", {{{"type", "tool_use"}, {"id", "t"}, {"name", "plan"}, {"input", json::object()}}}},
                  {"stop_reason", "tool_use"},
                  {"usage", usage}}
          .dump();
    case FakeLlmProtocol::kGemini:
      put("promptTokenCount", input);
      put("candidatesTokenCount", output);
      return json{{"candidates", {{{"content", {{"role", "model"}, {"parts", {{{"text", "{}"}}}}}},
                                   {"finishReason", "STOP"}}}},
                  {"usageMetadata", usage}}
          .dump();
    case FakeLlmProtocol::kOllama: {
      json body = {{"model", "test-model"},
                   {"message", {{"role", "assistant"}, {"content", "{}"}}},
                   {"done", true},
                   {"done_reason", "stop"}};
      if (!input.is_discarded()) body["prompt_eval_count"] = input;
      if (!output.is_discarded()) body["eval_count"] = output;
      return body.dump();
    }
  }
  return "";
}

FakeHttpResponse rawResponse(int status, std::string body, HttpHeaders headers = {}) {
  FakeHttpResponse response;
  response.status = status;
  response.body = std::move(body);
  response.headers = std::move(headers);
  return response;
}

class LlmHardeningTest : public ::testing::TestWithParam<FakeLlmProtocol> {
 protected:
  LlmHardeningTest() : server_(GetParam()), options_(fastOptions(server_)) {}

  std::unique_ptr<LlmClient> client() { return makeLlmClient(server_.spec(), options_); }
  LlmReply call() { return client()->complete(planRequest(), StopCondition::never()); }
  LlmError failingCall() {
    auto llm = client();
    return expectLlmError([&] { llm->complete(planRequest(), StopCondition::never()); });
  }

  FakeLlmServer server_;
  LlmClientOptions options_;
  TempDirectory directory_;
};

const std::string kDeep = std::string(100000, '[') + std::string(100000, ']');  // 200 kB

TEST_P(LlmHardeningTest, DeeplyNestedBodiesAreRefusedBeforeParsing) {
  options_.retry.maxAttempts = 1;
  server_.enqueue(rawResponse(200, kDeep));
  LlmError error = failingCall();
  EXPECT_EQ(error.kind(), LlmErrorKind::kBadResponse);
  EXPECT_THAT(error.what(), HasSubstr("HTTP 200: answer body: nested deeper than 128 levels (at byte 128)"));

  // Deep values where protocols copy or dump them (usage, tool input), inside a normal-looking body.
  const std::string deepFields = R"({"choices": [{"message": {"content": "{}"}}], "usage": )" + kDeep +
                                 R"(, "usageMetadata": )" + kDeep +
                                 R"(, "content": [{"type": "tool_use", "name": "plan", "input": )" + kDeep +
                                 R"(}], "message": {"content": "{}"}, "prompt_eval_count": )" + kDeep + "}";
  server_.enqueue(rawResponse(200, deepFields));
  error = failingCall();
  EXPECT_EQ(error.kind(), LlmErrorKind::kBadResponse);
  EXPECT_THAT(error.what(), HasSubstr("nested deeper than 128 levels"));

  // The same as an error body: the status and a bounded quote, no crash.
  for (const int status : {400, 401, 404, 503}) {
    server_.enqueue(rawResponse(status, kDeep));
    error = failingCall();
    EXPECT_EQ(error.httpStatus(), status);
    EXPECT_THAT(error.what(), HasSubstr("HTTP " + std::to_string(status)));
    EXPECT_LT(std::string(error.what()).size(), 800U);
  }
  // 1e400 is out of range for nlohmann (not a parse_error): a bad response too.
  server_.enqueue(rawResponse(200, R"({"usage": {"prompt_tokens": 1e400}})"));
  error = failingCall();
  EXPECT_EQ(error.kind(), LlmErrorKind::kBadResponse);
  EXPECT_THAT(error.what(), HasSubstr("answer body is not JSON (number overflow"));
}

/// The rule of LlmUsage: known only for a whole number in [0, 2^53].
TEST_P(LlmHardeningTest, TokenCountsThatAreNotNonNegativeIntegersAreUnknown) {
  const std::vector<std::pair<std::string, std::optional<long>>> cases = {
      {"12", 12L},
      {"0", 0L},
      {"12.0", 12L},
      {"9007199254740992", 9007199254740992L},
      {"9007199254740993", std::nullopt},
      {"18446744073709551615", std::nullopt},
      {"-3", std::nullopt},
      {"-9223372036854775808", std::nullopt},
      {"1.5", std::nullopt},
      {"1e300", std::nullopt},
      {"-1e300", std::nullopt},
      {"\"12\"", std::nullopt},
      {"true", std::nullopt},
      {"null", std::nullopt},
      {"[7]", std::nullopt},
      {"{}", std::nullopt},
      {"(absent)", std::nullopt},
  };
  for (const auto& [text, expected] : cases) {
    const json value = text == "(absent)" ? json(json::value_t::discarded) : json::parse(text);
    server_.enqueue(rawResponse(200, bodyWithUsage(GetParam(), value, 7)));
    server_.enqueue(rawResponse(200, bodyWithUsage(GetParam(), 5, value)));
    const LlmReply asInput = call();
    const LlmReply asOutput = call();
    EXPECT_EQ(asInput.usage.inputTokens, expected) << text;
    EXPECT_EQ(asInput.usage.outputTokens, 7L) << text;
    EXPECT_EQ(asOutput.usage.inputTokens, 5L) << text;
    EXPECT_EQ(asOutput.usage.outputTokens, expected) << text;
    EXPECT_EQ(tokenCountText(asInput.usage.inputTokens), expected ? std::to_string(*expected) : "unknown");
  }
}

TEST(GeminiTokenCountTest, ThoughtsAddToTheOutputAndAnUnknownPartMakesItUnknown) {
  FakeLlmServer server(FakeLlmProtocol::kGemini);
  auto client = makeLlmClient(server.spec(), fastOptions(server));
  const auto outputFor = [&](const json& usage) {
    json body = json::parse(bodyWithUsage(FakeLlmProtocol::kGemini, 1, 1));
    body["usageMetadata"] = usage;
    server.enqueue(rawResponse(200, body.dump()));
    return client->complete(planRequest(), StopCondition::never()).usage.outputTokens;
  };
  EXPECT_EQ(outputFor({{"candidatesTokenCount", 5}, {"thoughtsTokenCount", 3}}), 8L);
  EXPECT_EQ(outputFor({{"candidatesTokenCount", 5}}), 5L);
  EXPECT_EQ(outputFor({{"candidatesTokenCount", 5}, {"thoughtsTokenCount", nullptr}}), 5L);
  EXPECT_EQ(outputFor({{"candidatesTokenCount", 5}, {"thoughtsTokenCount", -1}}), std::nullopt);
  EXPECT_EQ(outputFor({{"candidatesTokenCount", 5}, {"thoughtsTokenCount", 1e300}}), std::nullopt);
  EXPECT_EQ(outputFor({{"thoughtsTokenCount", 3}}), std::nullopt);
  EXPECT_EQ(outputFor({{"candidatesTokenCount", 9007199254740992L}, {"thoughtsTokenCount", 9007199254740992L}}),
            18014398509481984L);
}

TEST_P(LlmHardeningTest, AnswerLargerThanTheCapIsRefusedAndNeverRecorded) {
  options_.http.maxResponseBytes = 64 * 1024;
  options_.recordFile = (directory_.path() / "calls.jsonl").string();
  server_.enqueueAnswer("{\"reasoning\": \"" + std::string(200 * 1024, 'x') + "\", \"actions\": []}");
  LlmError error = failingCall();
  EXPECT_EQ(error.kind(), LlmErrorKind::kBadResponse);
  EXPECT_THAT(error.what(), HasSubstr("HTTP 200 OK answer from http://127.0.0.1:"));
  EXPECT_THAT(error.what(), HasSubstr("is larger than the response size limit of 65536 bytes (Content-Length"));
  EXPECT_EQ(server_.requestCount(), 1U) << "an oversized answer is not retried";
  const std::string record = readFileText(options_.recordFile);
  EXPECT_LT(record.size(), 4096U) << "only the error is recorded, not the answer";
  EXPECT_THAT(record, HasSubstr("\"kind\":\"bad_response\""));

  // An error body over the cap is refused the same way.
  server_.enqueue(rawResponse(500, std::string(100 * 1024, 'e')));
  error = failingCall();
  EXPECT_THAT(error.what(), HasSubstr("HTTP 500 Internal Server Error answer from"));
  EXPECT_EQ(server_.requestCount(), 2U);
}

TEST_P(LlmHardeningTest, CapAppliesWhileReceivingAChunkedAnswer) {
  options_.http.maxResponseBytes = 64 * 1024;
  FakeHttpResponse endless = fakeAnswer(GetParam(), kPlanAnswer);
  endless.chunkedFillerBytes = std::size_t{200} << 20;  // 200 MB offered, never held anywhere
  server_.enqueue(endless);
  const auto start = std::chrono::steady_clock::now();
  const LlmError error = failingCall();
  EXPECT_EQ(error.kind(), LlmErrorKind::kBadResponse);
  EXPECT_THAT(error.what(), HasSubstr("larger than the response size limit of 65536 bytes (at least"));
  EXPECT_LT(server_.chunkedBytesSent(), std::size_t{32} << 20) << "the client stopped reading at the cap";
  EXPECT_LT(secondsSince(start), 10.0);

  // Below the cap a chunked answer (trailing whitespace is valid JSON) is read as usual.
  FakeHttpResponse small = fakeAnswer(GetParam(), kPlanAnswer);
  small.chunkedFillerBytes = 20 * 1024;
  server_.enqueue(small);
  EXPECT_EQ(json::parse(call().content), json::parse(kPlanAnswer));
}

TEST_P(LlmHardeningTest, RedirectsAreNamedWithTheirLocationAndNotFollowed) {
  for (const auto& [status, reason] : std::vector<std::pair<int, std::string>>{
           {301, "Moved Permanently"}, {302, "Found"}, {307, "Temporary Redirect"}, {308, "Permanent Redirect"}}) {
    server_.enqueue(rawResponse(status, "", {{"Location", "https://elsewhere.example/v1"}}));
    const std::size_t before = server_.requestCount();
    const LlmError error = failingCall();
    EXPECT_EQ(error.kind(), LlmErrorKind::kBadResponse);
    EXPECT_EQ(error.httpStatus(), status);
    EXPECT_THAT(error.what(), HasSubstr("HTTP " + std::to_string(status) + " " + reason +
                                        ": no body; the server redirects to https://elsewhere.example/v1, and "
                                        "redirects are not followed (check the base URL)"));
    EXPECT_EQ(server_.requestCount(), before + 1);
  }
  server_.enqueue(rawResponse(303, ""));
  EXPECT_THAT(failingCall().what(), HasSubstr("HTTP 303 See Other: no body; a redirect without a Location header"));
}

TEST_P(LlmHardeningTest, EveryHttpFailureNamesStatusReasonAndBodyOrNoBody) {
  options_.retry.maxAttempts = 1;
  const std::vector<std::pair<int, std::string>> statuses = {
      {400, "Bad Request"}, {401, "Unauthorized"}, {403, "Forbidden"}, {404, "Not Found"},
      {409, "Conflict"}, {422, "Unprocessable"}, {429, "Too Many Requests"}, {500, "Internal Server Error"},
      {502, "Bad Gateway"}, {503, "Service Unavailable"}};
  for (const auto& [status, reason] : statuses) {
    for (const std::string body : {"", "   ", "upstream went away"}) {
      server_.enqueue(rawResponse(status, body));
      const LlmError error = failingCall();
      const std::string message = error.what();
      EXPECT_EQ(error.httpStatus(), status) << message;
      EXPECT_THAT(message, HasSubstr("HTTP " + std::to_string(status) + " " + reason)) << message;
      EXPECT_THAT(message, HasSubstr(body == "upstream went away" ? ": upstream went away" : ": no body")) << message;
      EXPECT_THAT(message, Not(HasSubstr(": )"))) << message;
      EXPECT_THAT(message, Not(EndsWith(": "))) << message;
    }
  }
}

/// A server echoing the key: in the answer, in an error body (JSON or not, where a quote is cut
/// near the key), in a header. The key appears in no error, log line, reply or record line.
TEST_P(LlmHardeningTest, EchoedApiKeyIsRedactedEverywhere) {
  const std::string key = kTestApiKey;
  options_.recordFile = (directory_.path() / "calls.jsonl").string();
  std::vector<std::string> logged;
  setLogLevel(LogLevel::kInfo);
  setLogSink([&logged](LogLevel, std::string_view message) { logged.emplace_back(message); });
  auto llm = client();

  server_.enqueueError(500, "overloaded for key " + key);  // retried: a log line quotes it
  server_.enqueueAnswer(R"({"actions": [], "reasoning": "your key is )" + key + R"("})");
  const LlmReply reply = llm->complete(planRequest("echo in answer"), StopCondition::never());
  EXPECT_THAT(reply.content, Not(HasSubstr(key)));
  EXPECT_THAT(reply.content, HasSubstr("your key is [redacted]"));

  std::vector<std::string> errors;
  const auto failing = [&](FakeHttpResponse response) {
    server_.enqueue(std::move(response));
    errors.emplace_back(expectLlmError([&] { llm->complete(planRequest("echo"), StopCondition::never()); }).what());
  };
  failing(fakeError(GetParam(), 401, "invalid key " + key));
  failing(rawResponse(200, std::string(100, 'x') + key + " is not JSON"));  // quote cut at 120 bytes
  failing(rawResponse(302, "", {{"Location", "https://evil.example/?key=" + key}}));
  failing(rawResponse(404, "Bearer " + key));
  setLogSink({});
  setLogLevel(LogLevel::kWarn);

  const std::string secretPart = "SECRET-0123";
  for (const std::string& error : errors) {
    EXPECT_THAT(error, Not(HasSubstr(secretPart))) << error;
    EXPECT_THAT(error, Not(HasSubstr("sk-test-SEC"))) << error;
  }
  EXPECT_THAT(errors[0], HasSubstr("invalid key [redacted]"));
  EXPECT_THAT(errors[2], HasSubstr("https://evil.example/?key=[redacted]"));
  ASSERT_FALSE(logged.empty());
  for (const std::string& line : logged) EXPECT_THAT(line, Not(HasSubstr(secretPart))) << line;
  EXPECT_THAT(logged[0], HasSubstr("overloaded for key [redacted]"));
  const std::string record = readFileText(options_.recordFile);
  EXPECT_THAT(record, Not(HasSubstr(secretPart)));
  EXPECT_THAT(record, HasSubstr("[redacted]"));
}

INSTANTIATE_TEST_SUITE_P(AllProtocols, LlmHardeningTest, ::testing::ValuesIn(allFakeLlmProtocols()), protocolName);

TEST(TokenCountTest, SumsAreUnknownWithAnUnknownPartAndSaturate) {
  constexpr long kMax = std::numeric_limits<long>::max();
  EXPECT_EQ(addTokenCounts(3L, 4L), 7L);
  EXPECT_EQ(addTokenCounts(std::nullopt, 4L), std::nullopt);
  EXPECT_EQ(addTokenCounts(3L, std::nullopt), std::nullopt);
  EXPECT_EQ(addTokenCounts(kMax, 1L), kMax);
  EXPECT_EQ(addTokenCounts(std::numeric_limits<long>::min(), -1L), std::numeric_limits<long>::min());
  EXPECT_EQ(tokenCountText(std::nullopt), "unknown");
  EXPECT_EQ(tokenCountText(0L), "0");
}

TEST(SecretRedactorTest, ReplacesEveryFormAndIgnoresTooShortSecrets) {
  std::vector<std::string> secrets{"short", "abc\"def/ghi-123"};
  SecretRedactor::collectSecretHeaderValues({{"Authorization", "Bearer tok-0123456789"}, {"Accept", "application/json"}},
                                            secrets);
  const SecretRedactor redactor(secrets);
  EXPECT_EQ(redactor.redact("a short text"), "a short text");
  EXPECT_EQ(redactor.redact("k=abc\"def/ghi-123;"), "k=[redacted];");
  EXPECT_EQ(redactor.redact(R"({"k":"abc\"def/ghi-123"})"), R"({"k":"[redacted]"})");
  EXPECT_EQ(redactor.redact("tok-0123456789 and Bearer tok-0123456789"), "[redacted] and [redacted]");
  EXPECT_EQ(redactor.redact("application/json"), "application/json");
  EXPECT_TRUE(isSecretHeader("X-Goog-Api-Key"));
  EXPECT_FALSE(isSecretHeader("Content-Type"));
}

}  // namespace
}  // namespace lang2manip::test
