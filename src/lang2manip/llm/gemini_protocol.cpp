// Gemini generateContent with responseMimeType application/json and a converted responseSchema.
#include "lang2manip/llm/gemini_schema.hpp"
#include "lang2manip/llm/llm_protocol.hpp"
#include "lang2manip/llm/llm_support.hpp"

namespace lang2manip {

namespace {

using nlohmann::json;

FinishReason geminiFinish(const std::string& reason) {
  if (reason == "STOP") return FinishReason::kStop;
  if (reason == "MAX_TOKENS") return FinishReason::kLength;
  if (reason == "SAFETY" || reason == "RECITATION" || reason == "BLOCKLIST" ||
      reason == "PROHIBITED_CONTENT" || reason == "SPII" || reason == "IMAGE_SAFETY") {
    return FinishReason::kContentFilter;
  }
  return FinishReason::kOther;
}

/// Accepts "gemini-2.0-flash" and "models/gemini-2.0-flash".
std::string bareModelName(const std::string& model) {
  const std::string prefix = "models/";
  return model.rfind(prefix, 0) == 0 ? model.substr(prefix.size()) : model;
}

class GeminiProtocol final : public LlmProtocol {
 public:
  [[nodiscard]] std::string provider() const override { return "gemini"; }

  [[nodiscard]] HttpRequest buildRequest(const LlmRequest& request, const std::string& model,
                                         const std::string& apiKey) const override {
    json contents = json::array();
    for (const LlmMessage& message : request.messages) {
      const char* role = message.role == LlmMessage::Role::kAssistant ? "model" : "user";
      contents.push_back(
          {{"role", role}, {"parts", json::array({{{"text", message.content}}})}});
    }
    json config = {{"temperature", request.temperature},
                   {"maxOutputTokens", request.maxTokens}};
    if (request.seed) config["seed"] = *request.seed;
    if (!request.schema.is_null()) {
      config["responseMimeType"] = "application/json";
      config["responseSchema"] = toGeminiSchema(request.schema);
    }
    json body = {{"contents", contents}, {"generationConfig", config}};
    if (!request.system.empty()) {
      body["systemInstruction"] = {{"parts", json::array({{{"text", request.system}}})}};
    }
    HttpRequest http{"/v1beta/models/" + bareModelName(model) + ":generateContent", {},
                     body.dump()};
    if (!apiKey.empty()) http.headers.emplace_back("x-goog-api-key", apiKey);
    return http;
  }

  [[nodiscard]] LlmReply parseReply(const json& body, const LlmRequest& /*request*/,
                                    const std::string& who) const override {
    LlmReply reply;
    reply.model = optionalString(body, "modelVersion");
    const json usage = body.value("usageMetadata", json());
    reply.usage.inputTokens = tokenCount(usage, "promptTokenCount");
    // Thinking models add thoughtsTokenCount; others leave it out (zero thoughts).
    reply.usage.outputTokens =
        addTokenCounts(tokenCount(usage, "candidatesTokenCount"), tokenCountOrZero(usage, "thoughtsTokenCount"));
    const std::string blocked = optionalString(body.value("promptFeedback", json()), "blockReason");
    const auto candidates = body.find("candidates");
    if (!blocked.empty() && (candidates == body.end() || !candidates->is_array() || candidates->empty())) {
      reply.finish = FinishReason::kRefusal;
      reply.refusal = "the prompt was blocked (" + blocked + ")";
      return reply;
    }
    const json& candidate = requireFirstElement(body, "candidates", "", who);
    if (!candidate.is_object()) {
      throw LlmError(LlmErrorKind::kBadResponse, who + ": answer field candidates[0] is not an object");
    }
    const std::string reason = optionalString(candidate, "finishReason");
    reply.finish = geminiFinish(reason);
    if (reply.finish == FinishReason::kContentFilter) {
      reply.refusal = "the answer was blocked (finishReason " + reason + ")";
    }
    const auto content = candidate.find("content");
    const json parts = content != candidate.end() && content->is_object()
                           ? content->value("parts", json())
                           : json();
    bool hasText = false;
    for (const json& part : parts.is_array() ? parts : json::array()) {
      if (!part.is_object() || !part.contains("text") || part.value("thought", json()) == true) {
        continue;
      }
      if (!part["text"].is_string()) {
        throw LlmError(LlmErrorKind::kBadResponse,
                       who + ": answer field candidates[0].content.parts[].text is not a string");
      }
      reply.content += part["text"].get<std::string>();
      hasText = true;
    }
    if (!hasText && reply.finish == FinishReason::kStop) {
      throw LlmError(LlmErrorKind::kBadResponse,
                     who + ": answer has no text in candidates[0].content.parts");
    }
    return reply;
  }
};

}  // namespace

std::unique_ptr<LlmProtocol> makeGeminiProtocol() { return std::make_unique<GeminiProtocol>(); }

}  // namespace lang2manip
