// The target table and the text parsers: plan answers, LLM response bodies, replay files.
// The model file readers are in fuzz_model_inputs.cpp.

#include "fuzz_inputs.hpp"

#include <array>
#include <memory>
#include <stdexcept>

#include "lang2manip/core/error.hpp"
#include "lang2manip/llm/http_proxy.hpp"
#include "lang2manip/llm/llm_json.hpp"
#include "lang2manip/llm/llm_protocol.hpp"
#include "lang2manip/llm/llm_recording.hpp"
#include "lang2manip/llm/llm_support.hpp"
#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/plan_parser.hpp"
#include "scratch_file.hpp"

namespace lang2manip::fuzz {
namespace {

/// An LlmError of another kind than the parser documents is a finding.
void requireKind(const LlmError& error, LlmErrorKind documented) {
  if (error.kind() != documented) {
    throw std::logic_error("LlmError of kind " + llmErrorKindName(error.kind()) + " instead of " +
                           llmErrorKindName(documented) + ": " + error.what());
  }
}

PlanParseContext namedContext() {
  PlanParseContext context;
  context.objects = {"marker", "eraser", "holder", "desk"};
  context.planners = {"RRTConnect", "RRTstar", "PRM", "KPIECE1"};
  return context;
}

void requirePlanRoundTrip(const Plan& plan, const PlanParseContext& context) {
  try {
    const Plan again = parsePlan(toJson(plan), context);
    if (again.actions.size() != plan.actions.size()) {
      throw std::logic_error("a parsed plan reads back with another number of actions");
    }
  } catch (const InputError& error) {
    throw std::logic_error(std::string("a parsed plan does not read back from its JSON: ") +
                           error.what());
  }
}

/// The requests a reply is parsed for: the planner's (with the plan schema) and free text.
const std::array<LlmRequest, 2>& replyRequests() {
  static const std::array<LlmRequest, 2> requests = [] {
    LlmRequest structured;
    structured.system = "You plan manipulation tasks.";
    structured.messages = {LlmMessage{LlmMessage::Role::kUser, "put the marker in the holder"}};
    structured.schema = planJsonSchema();
    LlmRequest freeText = structured;
    freeText.schema = nullptr;
    return std::array<LlmRequest, 2>{structured, freeText};
  }();
  return requests;
}

void requireReplyRoundTrip(const LlmReply& reply) {
  try {
    const LlmReply again = llmReplyFromJson(llmReplyToJson(reply));
    if (again.content != reply.content) throw std::logic_error("reply content changed in JSON");
  } catch (const InputError& error) {
    throw std::logic_error(std::string("a parsed reply does not read back from its JSON: ") +
                           error.what());
  }
}

/// As HttpLlmClient::parseReply: the body as JSON, then the protocol's reading of it; the
/// client turns nlohmann's exceptions into LlmError(kBadResponse), so they are rejections too.
InputOutcome feedReply(const LlmProtocol& protocol, std::string_view input) {
  const std::string body(input);
  const std::string who = "HTTP 200";
  InputOutcome outcome = InputOutcome::kRejected;
  for (const LlmRequest& request : replyRequests()) {
    try {
      requireReplyRoundTrip(protocol.parseReply(parseResponseJson(body, who), request, who));
      outcome = InputOutcome::kAccepted;
    } catch (const nlohmann::json::exception&) {
    } catch (const LlmError& error) {
      requireKind(error, LlmErrorKind::kBadResponse);
    }
  }
  return outcome;
}

}  // namespace

InputOutcome feedPlanText(std::string_view input) {
  InputOutcome outcome = InputOutcome::kRejected;
  for (const PlanParseContext& context : {PlanParseContext{}, namedContext()}) {
    try {
      requirePlanRoundTrip(parsePlanText(input, context), context);
      outcome = InputOutcome::kAccepted;
    } catch (const InputError&) {
    }
  }
  return outcome;
}

InputOutcome feedOpenAiReply(std::string_view input) {
  static const std::unique_ptr<LlmProtocol> protocol = makeOpenAiProtocol();
  return feedReply(*protocol, input);
}

InputOutcome feedAnthropicReply(std::string_view input) {
  static const std::unique_ptr<LlmProtocol> protocol = makeAnthropicProtocol();
  return feedReply(*protocol, input);
}

InputOutcome feedGeminiReply(std::string_view input) {
  static const std::unique_ptr<LlmProtocol> protocol = makeGeminiProtocol();
  return feedReply(*protocol, input);
}

InputOutcome feedOllamaReply(std::string_view input) {
  static const std::unique_ptr<LlmProtocol> protocol = makeOllamaProtocol();
  return feedReply(*protocol, input);
}

InputOutcome feedLlmReplay(std::string_view input) {
  const std::string file = writeScratchFile("replay.jsonl", input).string();
  try {
    (void)makeReplayLlmClient(file);
    return InputOutcome::kAccepted;
  } catch (const LlmError& error) {
    requireKind(error, LlmErrorKind::kConfiguration);
    return InputOutcome::kRejected;
  }
}

InputOutcome feedProxyUrl(std::string_view input) {
  const std::string text(input);
  for (const char* host : {"api.example.com", "127.0.0.1", "[::1]", ""}) (void)noProxyMatches(text, host, 443);
  try {
    const HttpProxy proxy = parseProxyUrl(text, "HTTPS_PROXY");
    const HttpProxy again = parseProxyUrl(proxy.origin(), "HTTPS_PROXY");
    if (again.host != proxy.host || again.port != proxy.port) throw std::logic_error("proxy origin does not read back: " + proxy.origin());
    return InputOutcome::kAccepted;
  } catch (const LlmError& error) {
    requireKind(error, LlmErrorKind::kConfiguration);
    return InputOutcome::kRejected;
  }
}

const std::vector<FuzzTarget>& fuzzTargets() {
  static const std::vector<FuzzTarget> targets = {
      {"plan_text", feedPlanText},
      {"instruction", feedInstruction},
      {"instruction_corpus", feedInstructionCorpus},
      {"llm_openai", feedOpenAiReply},
      {"llm_anthropic", feedAnthropicReply},
      {"llm_gemini", feedGeminiReply},
      {"llm_ollama", feedOllamaReply},
      {"llm_replay", feedLlmReplay},
      {"proxy_url", feedProxyUrl},
      {"urdf", feedUrdf},
      {"srdf", feedSrdf},
      {"xacro", feedXacro},
      {"joint_limits", feedJointLimits},
      {"kautham_problem", feedKauthamProblem},
      {"kautham_controls", feedKauthamControls},
      {"kautham_benchmark", feedKauthamBenchmark},
      {"moveit_problem", feedMoveItProblem},
      {"api_request", feedApiRequest},
      {"viewer_document", feedViewerDocument},
      {"mesh_stl", feedStlMesh},
      {"mesh_obj", feedObjMesh},
      {"mesh_dae", feedDaeMesh},
      {"mesh_ply", feedPlyMesh},
      {"mesh_iv", feedInventorMesh},
      {"mesh_wrl", feedVrmlMesh},
  };
  return targets;
}

const FuzzTarget& fuzzTarget(std::string_view name) {
  for (const FuzzTarget& target : fuzzTargets()) {
    if (target.name == name) return target;
  }
  throw std::invalid_argument("no fuzz target named " + std::string(name));
}

}  // namespace lang2manip::fuzz
