#include "fake_llm_server.hpp"

#include <httplib.h>

#include <algorithm>
#include <atomic>

#include "lang2manip/core/json_limits.hpp"

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <regex>
#include <stdexcept>
#include <thread>

namespace lang2manip::test {

namespace {

using nlohmann::json;

/// Deterministic token counts: about four characters per token.
long tokensOf(const std::string& text) { return static_cast<long>(text.size() / 4 + 1); }

std::string requestedModel(const FakeReceivedRequest& request) {
  static const std::regex kGeminiPath("/v1beta/models/([^/:]+):generateContent");
  std::smatch match;
  if (std::regex_match(request.path, match, kGeminiPath)) return match[1];
  return request.json.is_object() ? request.json.value("model", "") : "";
}

std::string anthropicToolName(const FakeReceivedRequest& request) {
  if (request.json.contains("tool_choice")) return request.json["tool_choice"].value("name", "plan");
  return "plan";
}

json openAiBody(const FakeReceivedRequest& request, const json& message,
                const std::string& finish, const std::string& content) {
  return {{"id", "chatcmpl-fake"},
          {"object", "chat.completion"},
          {"created", 0},
          {"model", requestedModel(request)},
          {"choices", json::array({{{"index", 0}, {"message", message}, {"finish_reason", finish}}})},
          {"usage",
           {{"prompt_tokens", tokensOf(request.body)}, {"completion_tokens", tokensOf(content)}}}};
}

json anthropicBody(const FakeReceivedRequest& request, const json& block,
                   const std::string& stopReason, const std::string& content) {
  return {{"id", "msg_fake"},
          {"type", "message"},
          {"role", "assistant"},
          {"model", requestedModel(request)},
          {"content", json::array({block})},
          {"stop_reason", stopReason},
          {"stop_sequence", nullptr},
          {"usage", {{"input_tokens", tokensOf(request.body)}, {"output_tokens", tokensOf(content)}}}};
}

json geminiBody(const FakeReceivedRequest& request, const std::string& text,
                const std::string& finish) {
  return {{"candidates",
           json::array({{{"content", {{"role", "model"}, {"parts", json::array({{{"text", text}}})}}},
                         {"finishReason", finish},
                         {"index", 0}}})},
          {"usageMetadata",
           {{"promptTokenCount", tokensOf(request.body)},
            {"candidatesTokenCount", tokensOf(text)},
            {"totalTokenCount", tokensOf(request.body) + tokensOf(text)}}},
          {"modelVersion", requestedModel(request)}};
}

json ollamaBody(const FakeReceivedRequest& request, const std::string& content,
                const std::string& doneReason) {
  return {{"model", requestedModel(request)},
          {"created_at", "2024-01-01T00:00:00Z"},
          {"message", {{"role", "assistant"}, {"content", content}}},
          {"done", true},
          {"done_reason", doneReason},
          {"prompt_eval_count", tokensOf(request.body)},
          {"eval_count", tokensOf(content)}};
}

FakeHttpResponse bodyMaker(std::function<json(const FakeReceivedRequest&)> make) {
  FakeHttpResponse response;
  response.makeBody = [make = std::move(make)](const FakeReceivedRequest& request) {
    return make(request).dump();
  };
  return response;
}

const char* geminiStatusName(int status) {
  switch (status) {
    case 400: return "INVALID_ARGUMENT";
    case 401: return "UNAUTHENTICATED";
    case 403: return "PERMISSION_DENIED";
    case 404: return "NOT_FOUND";
    case 429: return "RESOURCE_EXHAUSTED";
    case 503: return "UNAVAILABLE";
    default: return "INTERNAL";
  }
}

std::string expectedPathPattern(FakeLlmProtocol protocol) {
  switch (protocol) {
    case FakeLlmProtocol::kOpenAi: return "/v1/chat/completions";
    case FakeLlmProtocol::kAnthropic: return "/v1/messages";
    case FakeLlmProtocol::kGemini: return "/v1beta/models/[^/:]+:generateContent";
    case FakeLlmProtocol::kOllama: return "/api/chat";
  }
  return "";
}

}  // namespace

std::vector<FakeLlmProtocol> allFakeLlmProtocols() {
  return {FakeLlmProtocol::kOpenAi, FakeLlmProtocol::kAnthropic, FakeLlmProtocol::kGemini,
          FakeLlmProtocol::kOllama};
}

std::string fakeLlmProvider(FakeLlmProtocol protocol) {
  switch (protocol) {
    case FakeLlmProtocol::kOpenAi: return "openai";
    case FakeLlmProtocol::kAnthropic: return "anthropic";
    case FakeLlmProtocol::kGemini: return "gemini";
    case FakeLlmProtocol::kOllama: return "ollama";
  }
  return "";
}

std::string FakeReceivedRequest::header(const std::string& name) const {
  return findHeader(headers, name);
}

FakeHttpResponse fakeAnswer(FakeLlmProtocol protocol, const std::string& content) {
  switch (protocol) {
    case FakeLlmProtocol::kOpenAi:
      return bodyMaker([content](const FakeReceivedRequest& request) {
        return openAiBody(request,
                          {{"role", "assistant"}, {"content", content}, {"refusal", nullptr}},
                          "stop", content);
      });
    case FakeLlmProtocol::kAnthropic:
      return bodyMaker([content](const FakeReceivedRequest& request) {
        // Deep content stays text: copying or dumping it as a value would exhaust the stack.
        const bool deep = findJsonLimitViolation(content, JsonLimits{}).has_value();
        const json input = deep ? json() : json::parse(content, nullptr, false);
        if (!input.is_object()) {
          return anthropicBody(request, {{"type", "text"}, {"text", content}}, "end_turn", content);
        }
        return anthropicBody(request,
                             {{"type", "tool_use"},
                              {"id", "toolu_fake"},
                              {"name", anthropicToolName(request)},
                              {"input", input}},
                             "tool_use", content);
      });
    case FakeLlmProtocol::kGemini:
      return bodyMaker([content](const FakeReceivedRequest& request) {
        return geminiBody(request, content, "STOP");
      });
    case FakeLlmProtocol::kOllama:
      return bodyMaker([content](const FakeReceivedRequest& request) {
        return ollamaBody(request, content, "stop");
      });
  }
  throw std::logic_error("unknown fake protocol");
}

FakeHttpResponse fakeTruncatedAnswer(FakeLlmProtocol protocol, const std::string& partialContent) {
  switch (protocol) {
    case FakeLlmProtocol::kOpenAi:
      return bodyMaker([partialContent](const FakeReceivedRequest& request) {
        return openAiBody(request,
                          {{"role", "assistant"}, {"content", partialContent}, {"refusal", nullptr}},
                          "length", partialContent);
      });
    case FakeLlmProtocol::kAnthropic:
      return bodyMaker([partialContent](const FakeReceivedRequest& request) {
        return anthropicBody(request, {{"type", "text"}, {"text", partialContent}}, "max_tokens",
                             partialContent);
      });
    case FakeLlmProtocol::kGemini:
      return bodyMaker([partialContent](const FakeReceivedRequest& request) {
        return geminiBody(request, partialContent, "MAX_TOKENS");
      });
    case FakeLlmProtocol::kOllama:
      return bodyMaker([partialContent](const FakeReceivedRequest& request) {
        return ollamaBody(request, partialContent, "length");
      });
  }
  throw std::logic_error("unknown fake protocol");
}

FakeHttpResponse fakeRefusal(FakeLlmProtocol protocol, const std::string& message) {
  switch (protocol) {
    case FakeLlmProtocol::kOpenAi:
      return bodyMaker([message](const FakeReceivedRequest& request) {
        return openAiBody(request,
                          {{"role", "assistant"}, {"content", nullptr}, {"refusal", message}},
                          "stop", message);
      });
    case FakeLlmProtocol::kAnthropic:
      return bodyMaker([message](const FakeReceivedRequest& request) {
        return anthropicBody(request, {{"type", "text"}, {"text", message}}, "refusal", message);
      });
    case FakeLlmProtocol::kGemini:
      return bodyMaker([](const FakeReceivedRequest& request) {
        return json{{"promptFeedback", {{"blockReason", "SAFETY"}}},
                    {"usageMetadata", {{"promptTokenCount", tokensOf(request.body)}}},
                    {"modelVersion", requestedModel(request)}};
      });
    case FakeLlmProtocol::kOllama:
      return fakeAnswer(protocol, message);
  }
  throw std::logic_error("unknown fake protocol");
}

FakeHttpResponse fakeError(FakeLlmProtocol protocol, int status, const std::string& message,
                           HttpHeaders headers) {
  json body;
  switch (protocol) {
    case FakeLlmProtocol::kOpenAi:
      body = {{"error", {{"message", message}, {"type", "invalid_request_error"}, {"code", nullptr}}}};
      break;
    case FakeLlmProtocol::kAnthropic:
      body = {{"type", "error"}, {"error", {{"type", "api_error"}, {"message", message}}}};
      break;
    case FakeLlmProtocol::kGemini:
      body = {{"error", {{"code", status}, {"message", message}, {"status", geminiStatusName(status)}}}};
      break;
    case FakeLlmProtocol::kOllama:
      body = {{"error", message}};
      break;
  }
  FakeHttpResponse response;
  response.status = status;
  response.body = body.dump();
  response.headers = std::move(headers);
  return response;
}

struct FakeLlmServer::State {
  FakeLlmProtocol protocol;
  std::unique_ptr<httplib::Server> server;
  bool tls = false;
  std::thread thread;
  int port = 0;
  mutable std::mutex mutex;
  std::condition_variable released;
  bool shuttingDown = false;
  std::deque<FakeHttpResponse> script;
  FakeHttpResponse fallback;
  std::vector<FakeReceivedRequest> received;
  std::shared_ptr<std::atomic<std::size_t>> chunkedBytes = std::make_shared<std::atomic<std::size_t>>(0);

  void handle(const httplib::Request& httpRequest, httplib::Response& httpResponse);
};

void FakeLlmServer::State::handle(const httplib::Request& httpRequest,
                                  httplib::Response& httpResponse) {
  FakeReceivedRequest request;
  request.path = httpRequest.path;
  request.body = httpRequest.body;
  for (const auto& [name, value] : httpRequest.headers) request.headers.emplace_back(name, value);
  request.json = json::parse(request.body, nullptr, false);
  if (request.json.is_discarded()) request.json = nullptr;

  FakeHttpResponse response;
  std::unique_lock lock(mutex);
  received.push_back(request);
  if (!std::regex_match(request.path, std::regex(expectedPathPattern(protocol)))) {
    response = fakeError(protocol, 404, "fake LLM server: unknown path " + request.path);
  } else if (!script.empty()) {
    response = std::move(script.front());
    script.pop_front();
  } else {
    response = fallback;
  }
  if (response.delaySeconds > 0.0) {
    released.wait_for(lock, std::chrono::duration<double>(response.delaySeconds),
                      [this] { return shuttingDown; });
  }
  lock.unlock();
  httpResponse.status = response.status;
  for (const auto& [name, value] : response.headers) httpResponse.set_header(name, value);
  const std::string body = response.makeBody ? response.makeBody(request) : response.body;
  if (response.chunkedFillerBytes == 0) {
    httpResponse.set_content(body, "application/json");
    return;
  }
  const std::size_t total = body.size() + response.chunkedFillerBytes;
  httpResponse.set_chunked_content_provider(
      "application/json", [body, total, sent = std::size_t{0}, counter = chunkedBytes](
                              std::size_t /*offset*/, httplib::DataSink& sink) mutable {
        constexpr std::size_t kChunk = 16 * 1024;
        if (sent >= total) {
          sink.done();
          return true;
        }
        std::string chunk;
        if (sent < body.size()) {
          chunk = body.substr(sent, kChunk);
        } else {
          chunk.assign(std::min(kChunk, total - sent), ' ');
        }
        if (!sink.write(chunk.data(), chunk.size())) return false;
        sent += chunk.size();
        *counter += chunk.size();
        return true;
      });
}

FakeLlmServer::FakeLlmServer(FakeLlmProtocol protocol) : FakeLlmServer(protocol, FakeTlsFiles{}) {}

FakeLlmServer::FakeLlmServer(FakeLlmProtocol protocol, const FakeTlsFiles& tls)
    : state_(std::make_unique<State>()) {
  state_->protocol = protocol;
  state_->fallback = fakeError(protocol, 500, "fake LLM server: no scripted response left");
  state_->tls = !tls.certificateFile.empty();
  if (state_->tls) {
    auto server = std::make_unique<httplib::SSLServer>(tls.certificateFile.c_str(),
                                                       tls.privateKeyFile.c_str());
    if (!server->is_valid()) throw std::runtime_error("fake LLM server: bad TLS certificate or key");
    state_->server = std::move(server);
  } else {
    state_->server = std::make_unique<httplib::Server>();
  }
  httplib::Server& server = *state_->server;
  server.set_tcp_nodelay(true);
  server.Post(".*", [state = state_.get()](const httplib::Request& request,
                                           httplib::Response& response) {
    state->handle(request, response);
  });
  state_->port = server.bind_to_any_port("127.0.0.1");
  if (state_->port <= 0) throw std::runtime_error("fake LLM server: cannot bind to 127.0.0.1");
  state_->thread = std::thread([&server] { server.listen_after_bind(); });
  // cpp-httplib 0.11 has no wait_until_ready(): poll is_running().
  for (int i = 0; i < 2000 && !server.is_running(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (!server.is_running()) {
    server.stop();
    state_->thread.join();
    throw std::runtime_error("fake LLM server: did not start");
  }
}

FakeLlmServer::~FakeLlmServer() {
  {
    std::lock_guard lock(state_->mutex);
    state_->shuttingDown = true;
  }
  state_->released.notify_all();
  state_->server->stop();
  if (state_->thread.joinable()) state_->thread.join();
}

FakeLlmProtocol FakeLlmServer::protocol() const { return state_->protocol; }

int FakeLlmServer::port() const { return state_->port; }

std::string FakeLlmServer::baseUrl() const {
  const std::string origin =
      std::string(state_->tls ? "https" : "http") + "://127.0.0.1:" + std::to_string(state_->port);
  return state_->protocol == FakeLlmProtocol::kOpenAi ? origin + "/v1" : origin;
}

std::string FakeLlmServer::spec(const std::string& model) const {
  return fakeLlmProvider(state_->protocol) + ":" + model;
}

void FakeLlmServer::enqueue(FakeHttpResponse response) {
  std::lock_guard lock(state_->mutex);
  state_->script.push_back(std::move(response));
}

void FakeLlmServer::enqueueAnswer(const std::string& content) {
  enqueue(fakeAnswer(state_->protocol, content));
}

void FakeLlmServer::enqueueTruncated(const std::string& partialContent) {
  enqueue(fakeTruncatedAnswer(state_->protocol, partialContent));
}

void FakeLlmServer::enqueueRefusal(const std::string& message) {
  enqueue(fakeRefusal(state_->protocol, message));
}

void FakeLlmServer::enqueueError(int status, const std::string& message, HttpHeaders headers) {
  enqueue(fakeError(state_->protocol, status, message, std::move(headers)));
}

void FakeLlmServer::enqueueHang(double seconds) {
  FakeHttpResponse response = fakeAnswer(state_->protocol, "{}");
  response.delaySeconds = seconds;
  enqueue(std::move(response));
}

void FakeLlmServer::setFallback(FakeHttpResponse response) {
  std::lock_guard lock(state_->mutex);
  state_->fallback = std::move(response);
}

std::vector<FakeReceivedRequest> FakeLlmServer::requests() const {
  std::lock_guard lock(state_->mutex);
  return state_->received;
}

std::size_t FakeLlmServer::requestCount() const {
  std::lock_guard lock(state_->mutex);
  return state_->received.size();
}

std::size_t FakeLlmServer::chunkedBytesSent() const { return *state_->chunkedBytes; }

std::size_t FakeLlmServer::pendingCount() const {
  std::lock_guard lock(state_->mutex);
  return state_->script.size();
}

}  // namespace lang2manip::test
