// Anthropic messages with a forced tool whose input_schema is the answer's schema.
#include "lang2manip/llm/llm_protocol.hpp"
#include "lang2manip/llm/llm_support.hpp"

namespace lang2manip {

namespace {

using nlohmann::json;

constexpr const char* kAnthropicVersion = "2023-06-01";

FinishReason anthropicFinish(const std::string& reason) {
  if (reason == "end_turn" || reason == "tool_use" || reason == "stop_sequence") {
    return FinishReason::kStop;
  }
  if (reason == "max_tokens") return FinishReason::kLength;
  if (reason == "refusal") return FinishReason::kRefusal;
  return FinishReason::kOther;
}

class AnthropicProtocol final : public LlmProtocol {
 public:
  [[nodiscard]] std::string provider() const override { return "anthropic"; }

  [[nodiscard]] HttpRequest buildRequest(const LlmRequest& request, const std::string& model,
                                         const std::string& apiKey) const override {
    json messages = json::array();
    for (const LlmMessage& message : request.messages) {
      messages.push_back({{"role", chatRoleName(message.role)}, {"content", message.content}});
    }
    json body = {{"model", model},
                 {"max_tokens", request.maxTokens},
                 {"temperature", request.temperature},
                 {"messages", messages}};
    if (!request.system.empty()) body["system"] = request.system;
    if (!request.schema.is_null()) {
      body["tools"] = json::array({{{"name", request.schemaName},
                                    {"description", "Submit the answer as structured data."},
                                    {"input_schema", request.schema}}});
      body["tool_choice"] = {{"type", "tool"}, {"name", request.schemaName}};
    }
    HttpRequest http{"/v1/messages", {{"anthropic-version", kAnthropicVersion}}, body.dump()};
    if (!apiKey.empty()) http.headers.emplace_back("x-api-key", apiKey);
    return http;
  }

  [[nodiscard]] LlmReply parseReply(const json& body, const LlmRequest& request,
                                    const std::string& who) const override {
    const json& content = requireMember(body, "content", "", who);
    if (!content.is_array()) {
      throw LlmError(LlmErrorKind::kBadResponse, who + ": answer field content is not an array");
    }
    LlmReply reply;
    reply.model = optionalString(body, "model");
    const json usage = body.value("usage", json());
    reply.usage.inputTokens = tokenCount(usage, "input_tokens");
    reply.usage.outputTokens = tokenCount(usage, "output_tokens");
    reply.finish = anthropicFinish(optionalString(body, "stop_reason"));
    std::string text;
    const json* toolInput = nullptr;
    for (const json& block : content) {
      const std::string type = optionalString(block, "type");
      if (type == "text") text += optionalString(block, "text");
      if (type == "tool_use" && optionalString(block, "name") == request.schemaName &&
          block.contains("input")) {
        toolInput = &block["input"];
      }
    }
    if (reply.finish == FinishReason::kRefusal) {
      reply.refusal = text.empty() ? "the model refused (stop_reason refusal)" : text;
      return reply;
    }
    if (request.schema.is_null()) {
      reply.content = text;
    } else if (toolInput != nullptr) {
      reply.content = toolInput->dump();
    } else if (reply.finish == FinishReason::kLength || !text.empty()) {
      // Text instead of the tool (a model or proxy ignoring tool_choice): the caller judges it
      // like any other answer, so a planner can ask again rather than give up.
      reply.content = text;
    } else {
      throw LlmError(LlmErrorKind::kBadResponse,
                     who + ": answer has no tool_use block named \"" + request.schemaName +
                         "\" and no text in content");
    }
    return reply;
  }
};

}  // namespace

std::unique_ptr<LlmProtocol> makeAnthropicProtocol() {
  return std::make_unique<AnthropicProtocol>();
}

}  // namespace lang2manip
