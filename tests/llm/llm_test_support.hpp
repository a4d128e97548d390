#pragma once
/// @file Shared pieces of the LLM tests: a small strict-mode schema, a request, fast options.

#include <gtest/gtest.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>

#include "fake_llm_server.hpp"
#include "lang2manip/llm/llm_client.hpp"
#include "lang2manip/llm/llm_client_factory.hpp"

namespace lang2manip::test {

inline constexpr const char* kTestApiKey = "sk-test-SECRET-0123456789";

/// {"actions":[{"action":..., "object":...}]} in OpenAI strict form.
inline nlohmann::json smallPlanSchema() {
  return nlohmann::json::parse(R"({
    "type": "object",
    "additionalProperties": false,
    "required": ["actions"],
    "properties": {
      "actions": {
        "type": "array",
        "items": {
          "type": "object",
          "additionalProperties": false,
          "required": ["action", "object"],
          "properties": {
            "action": {"type": "string", "enum": ["pick", "place"]},
            "object": {"type": ["string", "null"]}
          }
        }
      }
    }
  })");
}

inline LlmRequest planRequest(const std::string& task = "put the marker in the holder") {
  LlmRequest request;
  request.system = "You plan robot manipulation.";
  request.messages = {{LlmMessage::Role::kUser, task}};
  request.schema = smallPlanSchema();
  request.seed = 7;
  request.maxTokens = 512;
  return request;
}

inline const std::string kPlanAnswer = R"({"actions":[{"action":"pick","object":"marker"}]})";

/// Short timeouts and backoffs so that failure cases take milliseconds.
inline LlmClientOptions fastOptions(const FakeLlmServer& server) {
  LlmClientOptions options;
  options.baseUrl = server.baseUrl();
  options.apiKey = kTestApiKey;
  options.http.connectTimeoutSeconds = 2.0;
  options.http.requestTimeoutSeconds = 5.0;
  options.retry.maxAttempts = 3;
  options.retry.initialBackoffSeconds = 0.01;
  options.retry.maxBackoffSeconds = 0.05;
  options.retry.maxRetryAfterSeconds = 60.0;
  options.retry.totalTimeoutSeconds = 20.0;
  options.environment = [](const std::string&) { return std::optional<std::string>(); };
  return options;
}

/// Seconds since `start`.
inline double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Runs `call`, expecting an LlmError; returns it (fails the test when none is thrown).
template <typename Call>
LlmError expectLlmError(Call&& call) {
  try {
    call();
  } catch (const LlmError& error) {
    return error;
  }
  ADD_FAILURE() << "expected an LlmError";
  return LlmError(LlmErrorKind::kTransport, "no error thrown");
}

/// Names a test instantiated for every fake protocol after the protocol ("openai", ...).
inline std::string protocolName(const ::testing::TestParamInfo<FakeLlmProtocol>& parameter) {
  return fakeLlmProvider(parameter.param);
}

}  // namespace lang2manip::test
