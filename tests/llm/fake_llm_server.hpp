#pragma once
/// @file A fake LLM server on loopback for tests: one cpp-httplib server on an ephemeral port
/// speaking the real request/response JSON of one protocol (OpenAI chat completions, Anthropic
/// messages, Gemini generateContent, Ollama chat). Each test scripts it with a queue of responses
/// and afterwards inspects the requests it received. Link the test target with
/// lang2manip_fake_llm_server; cpp-httplib stays out of this header.
///
/// Example:
///   FakeLlmServer server(FakeLlmProtocol::kOpenAi);
///   server.enqueueAnswer(R"({"actions":[]})");
///   LlmClientOptions options;
///   options.baseUrl = server.baseUrl();
///   options.apiKey = "test-key";
///   auto client = makeLlmClient(server.spec("gpt-test"), options);

#include <cstddef>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lang2manip/llm/http_transport.hpp"

namespace lang2manip::test {

enum class FakeLlmProtocol { kOpenAi, kAnthropic, kGemini, kOllama };

/// All four, for parameterized tests.
std::vector<FakeLlmProtocol> allFakeLlmProtocols();

/// "openai", "anthropic", "gemini", "ollama" (the makeLlmClient provider names).
std::string fakeLlmProvider(FakeLlmProtocol protocol);

/// One request as the server received it.
struct FakeReceivedRequest {
  std::string path;
  HttpHeaders headers;
  std::string body;
  /// The body parsed (null when it is not JSON).
  nlohmann::json json;

  /// Header value (case-insensitive name), "" when absent.
  [[nodiscard]] std::string header(const std::string& name) const;
};

/// One scripted response.
struct FakeHttpResponse {
  int status = 200;
  HttpHeaders headers;
  /// The body, unless makeBody is set.
  std::string body;
  /// Builds the body from the request (e.g. to echo the model or the tool name).
  std::function<std::string(const FakeReceivedRequest&)> makeBody;
  /// When > 0 the response is sent chunked (no Content-Length): the body, then this many spaces
  /// generated while they are sent (so a test can offer 200 MB without holding them).
  std::size_t chunkedFillerBytes = 0;
  /// Waits this long before answering (a hang when longer than the client's timeout); the wait
  /// ends early when the server shuts down, so a test never outlives its server.
  double delaySeconds = 0.0;
};

/// Response bodies in each protocol's format; usable without a server.
/// A successful answer whose structured content is `content` (JSON text; for Anthropic, content
/// that is not a JSON object becomes a text block instead of the tool input).
FakeHttpResponse fakeAnswer(FakeLlmProtocol protocol, const std::string& content);
/// An answer cut off by the token limit (finish_reason length, stop_reason max_tokens,
/// finishReason MAX_TOKENS, done_reason length) with `partialContent`.
FakeHttpResponse fakeTruncatedAnswer(FakeLlmProtocol protocol, const std::string& partialContent);
/// A refusal: OpenAI message.refusal, Anthropic stop_reason "refusal", Gemini promptFeedback
/// blockReason SAFETY. Ollama has no refusal signal: the model's plain-text words as content.
FakeHttpResponse fakeRefusal(FakeLlmProtocol protocol, const std::string& message);
/// An HTTP error with the protocol's error body carrying `message`.
FakeHttpResponse fakeError(FakeLlmProtocol protocol, int status, const std::string& message,
                           HttpHeaders headers = {});

/// PEM files for an HTTPS fake server.
struct FakeTlsFiles {
  std::string certificateFile;
  std::string privateKeyFile;
};

class FakeLlmServer {
 public:
  /// Starts listening on 127.0.0.1 at an ephemeral port; returns once the server is running.
  explicit FakeLlmServer(FakeLlmProtocol protocol);
  /// The same over HTTPS with the given certificate (baseUrl() then starts with https://).
  FakeLlmServer(FakeLlmProtocol protocol, const FakeTlsFiles& tls);
  /// Releases delayed handlers, stops the server and joins its thread.
  ~FakeLlmServer();
  FakeLlmServer(const FakeLlmServer&) = delete;
  FakeLlmServer& operator=(const FakeLlmServer&) = delete;

  [[nodiscard]] FakeLlmProtocol protocol() const;
  [[nodiscard]] int port() const;
  /// What to pass as LlmClientOptions::baseUrl ("http://127.0.0.1:PORT", with "/v1" for OpenAI).
  [[nodiscard]] std::string baseUrl() const;
  /// "PROVIDER:MODEL" for makeLlmClient.
  [[nodiscard]] std::string spec(const std::string& model = "test-model") const;

  /// Appends to the script (first in, first out).
  void enqueue(FakeHttpResponse response);
  void enqueueAnswer(const std::string& content);
  void enqueueTruncated(const std::string& partialContent);
  void enqueueRefusal(const std::string& message);
  void enqueueError(int status, const std::string& message, HttpHeaders headers = {});
  /// A 200 answer after `seconds` (a hang for a client with a shorter timeout).
  void enqueueHang(double seconds);
  /// The answer once the script is used up (default: HTTP 500 "fake LLM server: no scripted
  /// response left").
  void setFallback(FakeHttpResponse response);

  /// Every request received so far, in order (also those to unknown paths).
  [[nodiscard]] std::vector<FakeReceivedRequest> requests() const;
  [[nodiscard]] std::size_t requestCount() const;
  /// Scripted responses not yet used.
  [[nodiscard]] std::size_t pendingCount() const;
  /// Bytes the client accepted of chunked responses so far (see chunkedFillerBytes).
  [[nodiscard]] std::size_t chunkedBytesSent() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace lang2manip::test
