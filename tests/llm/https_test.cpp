// HTTPS with certificate verification, against a fake server with a certificate made here.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fake_llm_server.hpp"
#include "lang2manip/llm/llm_client_factory.hpp"
#include "llm_test_support.hpp"
#include "test_certificate.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;

class HttpsTest : public ::testing::Test {
 protected:
  LlmReply call(const FakeLlmServer& server, const LlmClientOptions& options) {
    return makeLlmClient(server.spec(), options)->complete(planRequest(), StopCondition::never());
  }
  TempDirectory directory_;
};

TEST_F(HttpsTest, UntrustedCertificateIsRefused) {
  const FakeTlsFiles tls = writeSelfSignedCertificate(directory_.path(), "server", "IP:127.0.0.1");
  FakeLlmServer server(FakeLlmProtocol::kOpenAi, tls);
  server.enqueueAnswer(kPlanAnswer);
  LlmClientOptions options = fastOptions(server);
  options.retry.maxAttempts = 1;
  ASSERT_THAT(options.baseUrl, HasSubstr("https://"));
  const LlmError error = expectLlmError([&] { call(server, options); });
  EXPECT_EQ(error.kind(), LlmErrorKind::kTransport);
  EXPECT_THAT(error.what(), HasSubstr("certificate"));
  EXPECT_THAT(error.what(), HasSubstr("failed verification"));
  EXPECT_EQ(server.requestCount(), 0U) << "nothing may be sent to an unverified server";
}

TEST_F(HttpsTest, TrustedCertificateWorksThroughOptionsOrSslCertFile) {
  const FakeTlsFiles tls = writeSelfSignedCertificate(directory_.path(), "server", "IP:127.0.0.1");
  FakeLlmServer server(FakeLlmProtocol::kAnthropic, tls);
  server.enqueueAnswer(kPlanAnswer);
  server.enqueueAnswer(kPlanAnswer);
  LlmClientOptions options = fastOptions(server);
  options.http.caCertFile = tls.certificateFile;
  EXPECT_EQ(call(server, options).finish, FinishReason::kStop);
  options.http.caCertFile.clear();
  options.environment = [file = tls.certificateFile](const std::string& name) {
    return name == "SSL_CERT_FILE" ? std::optional<std::string>(file) : std::nullopt;
  };
  EXPECT_EQ(call(server, options).finish, FinishReason::kStop);
  EXPECT_EQ(server.requests().at(0).header("x-api-key"), kTestApiKey);
}

TEST_F(HttpsTest, CertificateForAnotherHostIsRefused) {
  const FakeTlsFiles tls =
      writeSelfSignedCertificate(directory_.path(), "other", "DNS:llm.example.invalid");
  FakeLlmServer server(FakeLlmProtocol::kGemini, tls);
  server.enqueueAnswer(kPlanAnswer);
  LlmClientOptions options = fastOptions(server);
  options.http.caCertFile = tls.certificateFile;
  options.retry.maxAttempts = 1;
  const LlmError error = expectLlmError([&] { call(server, options); });
  EXPECT_EQ(error.kind(), LlmErrorKind::kTransport);
  EXPECT_EQ(server.requestCount(), 0U);
}

}  // namespace
}  // namespace lang2manip::test
