#include "lang2manip/symbolic/llm_task_planner.hpp"

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/json_limits.hpp"
#include "lang2manip/model/scene.hpp"
#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/plan_parser.hpp"
#include "lang2manip/symbolic/plan_prompt.hpp"

namespace lang2manip {
namespace {

void checkUsable(const LlmReply& reply) {
  switch (reply.finish) {
    case FinishReason::kLength:
      throw UnusableAnswerError(reply.content,
                                "the answer was cut off at the output token limit" +
                                    (reply.usage.outputTokens
                                         ? " (" + std::to_string(*reply.usage.outputTokens) + " tokens)"
                                         : std::string()) +
                                    ", so its JSON is incomplete; answer with a shorter plan "
                                    "and keep the reasoning brief");
    case FinishReason::kRefusal:
      throw UnusableAnswerError(reply.content, "the model refused to answer" +
                                                   (reply.refusal.empty() ? std::string() : ": " + reply.refusal) +
                                                   "; the task only asks to move objects on a desk with a robot arm");
    case FinishReason::kContentFilter:
      throw UnusableAnswerError(reply.content, "the answer was blocked by the provider's content filter");
    case FinishReason::kStop:
    case FinishReason::kOther:
      break;
  }
}

}  // namespace

LlmTaskPlanner::LlmTaskPlanner(LlmClient& client, LlmTaskPlannerOptions options)
    : client_(client), options_(std::move(options)) {}

std::string LlmTaskPlanner::name() const { return client_.name(); }

LlmRequest LlmTaskPlanner::buildRequest(const PlanningRequest& request) const {
  return buildPlanRequest(request, options_);
}

LlmRequest buildPlanRequest(const PlanningRequest& request, const LlmTaskPlannerOptions& options) {
  if (request.scene == nullptr) throw InputError("planning request: no scene given");
  ObservationOptions observation = options.observation;
  if (!request.robot.empty()) observation.robot = request.robot;
  observation.arm = request.arm;
  LlmRequest llm;
  llm.system = planSystemPrompt(options.plannerNames);
  llm.messages = planMessages(request.task, observationText(observeEnvironment(*request.scene, observation)),
                              request.earlierAttempts, options.maxAttemptsInContext);
  llm.schema = planJsonSchema();
  llm.schemaName = "plan";
  llm.maxTokens = options.maxTokens;
  llm.temperature = options.temperature;
  llm.seed = options.seed;
  return llm;
}

Plan LlmTaskPlanner::plan(const PlanningRequest& request, const StopCondition& stop,
                          PlanningStatistics& statistics) {
  const LlmRequest llm = buildRequest(request);
  const LlmReply reply = client_.complete(llm, stop);
  statistics.llmCalls += 1;
  statistics.inputTokens = addTokenCounts(statistics.inputTokens, reply.usage.inputTokens);
  statistics.outputTokens = addTokenCounts(statistics.outputTokens, reply.usage.outputTokens);
  statistics.llmSeconds += reply.latencySeconds;
  checkUsable(reply);
  PlanParseContext context;
  for (const SceneObject& object : request.scene->objects()) context.objects.push_back(object.name);
  context.planners = options_.plannerNames;
  // Every way an answer can be malformed is a failure the repair loop feeds back, never an
  // exception that ends the command.
  try {
    return parsePlanText(reply.content, context);
  } catch (const InputError& error) {  // PlanParseError and any other bad-input report
    throw UnusableAnswerError(reply.content, error.what());
  } catch (const nlohmann::json::exception& error) {
    throw UnusableAnswerError(reply.content, "the answer could not be read as a plan: " + jsonErrorText(error));
  }
}

}  // namespace lang2manip
