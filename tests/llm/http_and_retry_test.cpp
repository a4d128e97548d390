#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "lang2manip/llm/http_transport.hpp"
#include "lang2manip/llm/llm_client.hpp"
#include "lang2manip/llm/retry_policy.hpp"
#include "llm_test_support.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;

TEST(BaseUrl, ParsesSchemeHostPortAndPath) {
  const HttpEndpoint openAi = parseBaseUrl("https://api.openai.com/v1/", "test");
  EXPECT_EQ(openAi.scheme, "https");
  EXPECT_EQ(openAi.host, "api.openai.com");
  EXPECT_EQ(openAi.port, 443);
  EXPECT_EQ(openAi.basePath, "/v1");
  const HttpEndpoint local = parseBaseUrl("HTTP://127.0.0.1:8080", "test");
  EXPECT_EQ(local.scheme, "http");
  EXPECT_EQ(local.port, 8080);
  EXPECT_EQ(local.basePath, "");
  EXPECT_EQ(local.toString(), "http://127.0.0.1:8080");
  EXPECT_EQ(parseBaseUrl("http://[::1]:11434", "test").host, "[::1]");
  EXPECT_EQ(parseBaseUrl("http://[::1]", "test").port, 80);
}

TEST(BaseUrl, RejectsWhatItCannotUseNamingTheSource) {
  for (const char* bad : {"api.openai.com", "ftp://x", "http://", "http://h:0", "http://h:abc",
                          "http://h/v1?x=1", "https://user:pw@h/"}) {
    const LlmError error = test::expectLlmError([&] { parseBaseUrl(bad, "OPENAI_BASE_URL"); });
    EXPECT_EQ(error.kind(), LlmErrorKind::kConfiguration) << bad;
    EXPECT_THAT(error.what(), HasSubstr("OPENAI_BASE_URL: bad base URL")) << bad;
  }
}

TEST(RetryPolicy, BackoffGrowsExponentiallyUpToTheCap) {
  RetryOptions options;
  options.initialBackoffSeconds = 0.5;
  options.backoffMultiplier = 2.0;
  options.maxBackoffSeconds = 3.0;
  EXPECT_DOUBLE_EQ(backoffSeconds(options, 1), 0.5);
  EXPECT_DOUBLE_EQ(backoffSeconds(options, 2), 1.0);
  EXPECT_DOUBLE_EQ(backoffSeconds(options, 3), 2.0);
  EXPECT_DOUBLE_EQ(backoffSeconds(options, 4), 3.0);
  EXPECT_DOUBLE_EQ(backoffSeconds(options, 40), 3.0);
}

TEST(RetryPolicy, ReadsRetryAfterInSecondsOrMilliseconds) {
  EXPECT_EQ(retryAfterSeconds({{"Retry-After", "7"}}), 7.0);
  EXPECT_EQ(retryAfterSeconds({{"retry-after", "0.25"}}), 0.25);
  EXPECT_EQ(retryAfterSeconds({{"retry-after-ms", "150"}, {"Retry-After", "1"}}), 0.15);
  EXPECT_FALSE(retryAfterSeconds({{"Retry-After", "Wed, 21 Oct 2015 07:28:00 GMT"}}));
  EXPECT_FALSE(retryAfterSeconds({{"Retry-After", "-3"}}));
  EXPECT_FALSE(retryAfterSeconds({}));
}

TEST(RetryPolicy, RetriesOnlyTransientStatuses) {
  for (const int status : {408, 429, 500, 502, 503, 529}) EXPECT_TRUE(isRetryableStatus(status));
  for (const int status : {200, 400, 401, 403, 404, 422}) EXPECT_FALSE(isRetryableStatus(status));
}

TEST(RetryPolicy, SleepWakesOnCancel) {
  auto flag = std::make_shared<std::atomic<bool>>(false);
  std::thread canceller([flag] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    flag->store(true);
  });
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(sleepUnlessStopped(30.0, StopCondition::onCancel(flag)));
  canceller.join();
  EXPECT_LT(test::secondsSince(start), 1.0);
  EXPECT_TRUE(sleepUnlessStopped(0.01, StopCondition::never()));
}

TEST(RetryPolicy, RejectsOutOfRangeOptions) {
  RetryOptions options;
  options.backoffMultiplier = 0.5;
  EXPECT_THAT(test::expectLlmError([&] { checkRetryOptions(options); }).what(),
              HasSubstr("backoffMultiplier"));
  options = RetryOptions{};
  options.totalTimeoutSeconds = std::numeric_limits<double>::infinity();
  EXPECT_THAT(test::expectLlmError([&] { checkRetryOptions(options); }).what(),
              HasSubstr("totalTimeoutSeconds"));
}

TEST(LlmErrorKindNames, RoundTrip) {
  for (const LlmErrorKind kind :
       {LlmErrorKind::kConfiguration, LlmErrorKind::kAuthentication, LlmErrorKind::kModelNotFound,
        LlmErrorKind::kRateLimited, LlmErrorKind::kServer, LlmErrorKind::kTimeout,
        LlmErrorKind::kCancelled, LlmErrorKind::kTransport, LlmErrorKind::kBadResponse,
        LlmErrorKind::kReplayMiss}) {
    EXPECT_EQ(llmErrorKindFromName(llmErrorKindName(kind)), kind);
  }
  EXPECT_FALSE(llmErrorKindFromName("nope"));
}

}  // namespace
}  // namespace lang2manip
