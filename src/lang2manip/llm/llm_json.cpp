#include "lang2manip/llm/llm_json.hpp"

#include <cstdint>
#include <limits>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/json_limits.hpp"

namespace lang2manip {

namespace {

using nlohmann::json;

constexpr long kMaxInt = std::numeric_limits<int>::max();

const json& field(const json& object, const std::string& key, const std::string& where) {
  if (!object.is_object() || !object.contains(key)) {
    throw InputError(where + key + ": missing");
  }
  return object[key];
}

std::string stringField(const json& object, const std::string& key, const std::string& where) {
  const json& value = field(object, key, where);
  if (!value.is_string()) throw InputError(where + key + ": expected a string");
  return value.get<std::string>();
}

double numberField(const json& object, const std::string& key, const std::string& where) {
  const json& value = field(object, key, where);
  if (!value.is_number()) throw InputError(where + key + ": expected a number");
  return value.get<double>();
}

long integerField(const json& object, const std::string& key, const std::string& where, long minimum,
                  long maximum) {
  const json& value = field(object, key, where);
  const auto fail = [&] {
    return InputError(where + key + ": expected an integer in [" + std::to_string(minimum) + ", " +
                      std::to_string(maximum) + "], got " + boundedJsonDump(value));
  };
  if (value.is_number_unsigned()) {
    const auto number = value.get<std::uint64_t>();
    if (maximum < 0 || number > static_cast<std::uint64_t>(maximum)) throw fail();
    if (minimum > 0 && number < static_cast<std::uint64_t>(minimum)) throw fail();
    return static_cast<long>(number);
  }
  if (!value.is_number_integer()) throw fail();
  const auto number = value.get<std::int64_t>();
  if (number < minimum || number > maximum) throw fail();
  return static_cast<long>(number);
}

/// A token count as written by llmReplyToJson: null (unknown) or a count by LlmUsage's rule.
std::optional<long> tokenCountField(const json& object, const std::string& key, const std::string& where) {
  const json& value = field(object, key, where);
  if (value.is_null()) return std::nullopt;
  return integerField(object, key, where, 0, kMaxTokenCount);
}

LlmMessage::Role roleFromName(const std::string& name, const std::string& where) {
  if (name == "user") return LlmMessage::Role::kUser;
  if (name == "assistant") return LlmMessage::Role::kAssistant;
  throw InputError(where + "role: \"" + name + "\" is not user or assistant");
}

}  // namespace

nlohmann::json tokenCountJson(const std::optional<long>& count) {
  return count ? json(*count) : json(nullptr);
}

std::optional<FinishReason> finishReasonFromName(const std::string& name) {
  for (const FinishReason reason : {FinishReason::kStop, FinishReason::kLength,
                                    FinishReason::kRefusal, FinishReason::kContentFilter,
                                    FinishReason::kOther}) {
    if (finishReasonName(reason) == name) return reason;
  }
  return std::nullopt;
}

json llmRequestToJson(const LlmRequest& request) {
  json messages = json::array();
  for (const LlmMessage& message : request.messages) {
    messages.push_back({{"role", message.role == LlmMessage::Role::kAssistant ? "assistant" : "user"},
                        {"content", message.content}});
  }
  return {{"system", request.system},
          {"messages", messages},
          {"schema", request.schema},
          {"schemaName", request.schemaName},
          {"maxTokens", request.maxTokens},
          {"temperature", request.temperature},
          {"seed", request.seed ? json(*request.seed) : json()}};
}

LlmRequest llmRequestFromJson(const json& object) {
  const std::string where = "request.";
  LlmRequest request;
  request.system = stringField(object, "system", where);
  const json& messages = field(object, "messages", where);
  if (!messages.is_array()) throw InputError(where + "messages: expected an array");
  for (std::size_t i = 0; i < messages.size(); ++i) {
    const std::string at = where + "messages[" + std::to_string(i) + "].";
    request.messages.push_back({roleFromName(stringField(messages[i], "role", at), at),
                                stringField(messages[i], "content", at)});
  }
  request.schema = field(object, "schema", where);
  request.schemaName = stringField(object, "schemaName", where);
  request.maxTokens = static_cast<int>(integerField(object, "maxTokens", where, 1, kMaxInt));
  request.temperature = numberField(object, "temperature", where);
  if (!field(object, "seed", where).is_null()) {
    request.seed = integerField(object, "seed", where, std::numeric_limits<long>::min(),
                                std::numeric_limits<long>::max());
  }
  return request;
}

json llmReplyToJson(const LlmReply& reply) {
  return {{"content", reply.content},
          {"finish", finishReasonName(reply.finish)},
          {"refusal", reply.refusal},
          {"usage", {{"inputTokens", tokenCountJson(reply.usage.inputTokens)},
                     {"outputTokens", tokenCountJson(reply.usage.outputTokens)}}},
          {"latencySeconds", reply.latencySeconds},
          {"attempts", reply.attempts},
          {"model", reply.model}};
}

LlmReply llmReplyFromJson(const json& object) {
  const std::string where = "reply.";
  LlmReply reply;
  reply.content = stringField(object, "content", where);
  const std::string finish = stringField(object, "finish", where);
  const auto reason = finishReasonFromName(finish);
  if (!reason) throw InputError(where + "finish: \"" + finish + "\" is not a finish reason");
  reply.finish = *reason;
  reply.refusal = stringField(object, "refusal", where);
  const json& usage = field(object, "usage", where);
  reply.usage.inputTokens = tokenCountField(usage, "inputTokens", where + "usage.");
  reply.usage.outputTokens = tokenCountField(usage, "outputTokens", where + "usage.");
  reply.latencySeconds = numberField(object, "latencySeconds", where);
  reply.attempts = static_cast<int>(integerField(object, "attempts", where, 1, kMaxInt));
  reply.model = stringField(object, "model", where);
  return reply;
}

}  // namespace lang2manip
