// OpenAI-compatible chat completions: OpenAI, Ollama's /v1, llama.cpp server, vLLM, LM Studio.
#include <algorithm>
#include <atomic>
#include <cctype>

#include "lang2manip/llm/llm_protocol.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/llm/llm_support.hpp"

namespace lang2manip {

namespace {

using nlohmann::json;

bool mentions(const std::string& text, const char* word) {
  return text.find(word) != std::string::npos;
}

FinishReason openAiFinish(const std::string& reason) {
  if (reason == "stop" || reason == "tool_calls" || reason == "function_call") {
    return FinishReason::kStop;
  }
  if (reason == "length") return FinishReason::kLength;
  if (reason == "content_filter") return FinishReason::kContentFilter;
  return FinishReason::kOther;
}

class OpenAiProtocol final : public LlmProtocol {
 public:
  [[nodiscard]] std::string provider() const override { return "openai"; }

  [[nodiscard]] HttpRequest buildRequest(const LlmRequest& request, const std::string& model,
                                         const std::string& apiKey) const override {
    const bool jsonObject = jsonObjectMode_.load();
    json body = {{"model", model}, {"messages", messages(request, jsonObject)}};
    body[maxCompletionTokens_.load() ? "max_completion_tokens" : "max_tokens"] = request.maxTokens;
    if (!omitTemperature_.load()) body["temperature"] = request.temperature;
    if (request.seed) body["seed"] = *request.seed;
    if (!request.schema.is_null()) body["response_format"] = responseFormat(request, jsonObject);
    HttpRequest http{"/chat/completions", {}, body.dump()};
    if (!apiKey.empty()) http.headers.emplace_back("Authorization", "Bearer " + apiKey);
    return http;
  }

  [[nodiscard]] LlmReply parseReply(const json& body, const LlmRequest& /*request*/,
                                    const std::string& who) const override {
    const json& choice = requireFirstElement(body, "choices", "", who);
    const json& message = requireMember(choice, "message", "choices[0]", who);
    LlmReply reply;
    reply.model = optionalString(body, "model");
    const json usage = body.value("usage", json());
    reply.usage.inputTokens = tokenCount(usage, "prompt_tokens");
    reply.usage.outputTokens = tokenCount(usage, "completion_tokens");
    reply.refusal = optionalString(message, "refusal");
    reply.finish = openAiFinish(optionalString(choice, "finish_reason"));
    if (!reply.refusal.empty()) {
      reply.finish = FinishReason::kRefusal;
      return reply;
    }
    const auto content = message.find("content");
    if (content != message.end() && content->is_string()) {
      reply.content = content->get<std::string>();
    } else if (reply.finish != FinishReason::kLength) {
      throw LlmError(LlmErrorKind::kBadResponse,
                     who + ": answer has no choices[0].message.content (string) and no refusal");
    }
    return reply;
  }

  bool adaptToRejection(const std::string& serverMessage) override {
    const std::string message = lowercase(serverMessage);
    if (mentions(message, "max_completion_tokens") && !maxCompletionTokens_.exchange(true)) {
      return true;
    }
    if (mentions(message, "temperature") && !omitTemperature_.exchange(true)) return true;
    if ((mentions(message, "response_format") || mentions(message, "json_schema")) &&
        !jsonObjectMode_.exchange(true)) {
      return true;
    }
    return false;
  }

 private:
  static json messages(const LlmRequest& request, bool jsonObject) {
    json list = json::array();
    std::string system = request.system;
    if (jsonObject) {
      // json_object mode needs the word JSON in the prompt and cannot enforce the schema.
      system += (system.empty() ? "" : "\n\n");
      system += "Answer with one JSON document that follows this JSON Schema:\n" +
                request.schema.dump();
    }
    if (!system.empty()) list.push_back({{"role", "system"}, {"content", system}});
    for (const LlmMessage& message : request.messages) {
      list.push_back({{"role", chatRoleName(message.role)}, {"content", message.content}});
    }
    return list;
  }

  static json responseFormat(const LlmRequest& request, bool jsonObject) {
    if (jsonObject) return {{"type", "json_object"}};
    return {{"type", "json_schema"},
            {"json_schema",
             {{"name", request.schemaName}, {"strict", true}, {"schema", request.schema}}}};
  }

  std::atomic<bool> jsonObjectMode_{false};
  std::atomic<bool> maxCompletionTokens_{false};
  std::atomic<bool> omitTemperature_{false};
};

}  // namespace

std::string chatRoleName(LlmMessage::Role role) {
  return role == LlmMessage::Role::kAssistant ? "assistant" : "user";
}

std::unique_ptr<LlmProtocol> makeOpenAiProtocol() { return std::make_unique<OpenAiProtocol>(); }

}  // namespace lang2manip
