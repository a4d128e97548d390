// Ollama's native /api/chat with format = the JSON Schema and stream false.
#include "lang2manip/llm/llm_protocol.hpp"
#include "lang2manip/llm/llm_support.hpp"

namespace lang2manip {

namespace {

using nlohmann::json;

FinishReason ollamaFinish(const std::string& reason) {
  if (reason == "stop" || reason.empty()) return FinishReason::kStop;
  if (reason == "length") return FinishReason::kLength;
  return FinishReason::kOther;
}

class OllamaProtocol final : public LlmProtocol {
 public:
  [[nodiscard]] std::string provider() const override { return "ollama"; }

  [[nodiscard]] HttpRequest buildRequest(const LlmRequest& request, const std::string& model,
                                         const std::string& apiKey) const override {
    json messages = json::array();
    if (!request.system.empty()) {
      messages.push_back({{"role", "system"}, {"content", request.system}});
    }
    for (const LlmMessage& message : request.messages) {
      messages.push_back({{"role", chatRoleName(message.role)}, {"content", message.content}});
    }
    json options = {{"temperature", request.temperature}, {"num_predict", request.maxTokens}};
    if (request.seed) options["seed"] = *request.seed;
    json body = {{"model", model}, {"stream", false}, {"messages", messages}, {"options", options}};
    if (!request.schema.is_null()) body["format"] = request.schema;
    HttpRequest http{"/api/chat", {}, body.dump()};
    if (!apiKey.empty()) http.headers.emplace_back("Authorization", "Bearer " + apiKey);
    return http;
  }

  [[nodiscard]] LlmReply parseReply(const json& body, const LlmRequest& /*request*/,
                                    const std::string& who) const override {
    const json& message = requireMember(body, "message", "", who);
    LlmReply reply;
    reply.content = requireString(message, "content", "message", who);
    if (body.contains("done") && body["done"] == false) {
      throw LlmError(LlmErrorKind::kBadResponse,
                     who + ": answer is a partial stream chunk (done false) although stream was false");
    }
    reply.finish = ollamaFinish(optionalString(body, "done_reason"));
    reply.model = optionalString(body, "model");
    reply.usage.inputTokens = tokenCount(body, "prompt_eval_count");
    reply.usage.outputTokens = tokenCount(body, "eval_count");
    return reply;
  }
};

}  // namespace

std::unique_ptr<LlmProtocol> makeOllamaProtocol() { return std::make_unique<OllamaProtocol>(); }

}  // namespace lang2manip
