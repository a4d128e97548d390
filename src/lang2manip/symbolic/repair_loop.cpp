#include "lang2manip/symbolic/repair_loop.hpp"

#include <chrono>

#include "lang2manip/core/error.hpp"
#include "lang2manip/llm/llm_client.hpp"
#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/plan_validation.hpp"

namespace lang2manip {
namespace {

using Clock = std::chrono::steady_clock;

void accumulate(PlanningStatistics& total, const PlanningStatistics& round) {
  total.llmCalls += round.llmCalls;
  total.inputTokens = addTokenCounts(total.inputTokens, round.inputTokens);
  total.outputTokens = addTokenCounts(total.outputTokens, round.outputTokens);
  total.llmSeconds += round.llmSeconds;
  total.planningSeconds += round.planningSeconds;
}

/// Asks the planner once; fills round.attempt.plan or round.outcome/attempt for answers that failed.
void askPlanner(TaskPlanner& planner, const PlanningRequest& request, const StopCondition& stop, RepairRound& round) {
  const auto start = Clock::now();
  try {
    round.attempt.plan = planner.plan(request, stop, round.statistics);
  } catch (const UnusableAnswerError& error) {
    round.outcome = RoundOutcome::kUnusableAnswer;
    round.attempt.answer = error.answer();
    round.attempt.failure = error.what();
  } catch (const PlanningError& error) {
    round.outcome = RoundOutcome::kPlannerError;
    round.attempt.failure = planner.name() + " could not plan: " + error.what();
  } catch (const LlmError& error) {
    round.outcome = RoundOutcome::kPlannerError;
    round.attempt.failure = "the LLM call of " + planner.name() + " failed: " + error.what();
  }
  if (round.statistics.planningSeconds == 0.0) {
    round.statistics.planningSeconds = std::chrono::duration<double>(Clock::now() - start).count();
  }
}

/// Checks a plan the planner returned: validation, then grounding.
void checkPlan(const PlanningRequest& request, PlanExecutor* executor, const RepairOptions& options,
               const StopCondition& stop, RepairRound& round) {
  const Plan& plan = *round.attempt.plan;
  round.attempt.answer = toJson(plan).dump();
  if (options.validate) {
    const PlanValidation validation =
        validatePlan(plan, observeSymbolicState(*request.scene, options.tolerances, request.robot, request.arm));
    if (!validation.valid()) {
      round.outcome = RoundOutcome::kInvalidPlan;
      round.attempt.failure = "the plan is not valid in the current state: " + validation.summary();
      return;
    }
  }
  if (executor != nullptr) {
    if (auto failure = executor->execute(plan, stop)) {
      round.outcome = RoundOutcome::kGroundingFailed;
      round.attempt.grounding = failure;
      round.attempt.failure = describeGroundingFailure(*failure, plan);
      return;
    }
  }
  round.outcome = RoundOutcome::kAccepted;
}

std::string firstLines(const std::string& text, std::size_t maxLength) {
  std::string result;
  for (char c : text) result += c == '\n' ? ' ' : c;
  if (result.size() > maxLength) result = result.substr(0, maxLength - 3) + "...";
  return result;
}

std::string roundsText(const std::vector<RepairRound>& rounds) {
  std::string text;
  for (const RepairRound& round : rounds) {
    text += "\n  round " + std::to_string(round.round) + " (" + roundOutcomeName(round.outcome) + "): " +
            firstLines(round.attempt.failure, 400);
  }
  return text;
}

}  // namespace

std::string roundOutcomeName(RoundOutcome outcome) {
  switch (outcome) {
    case RoundOutcome::kAccepted: return "accepted";
    case RoundOutcome::kUnusableAnswer: return "unusable answer";
    case RoundOutcome::kInvalidPlan: return "invalid plan";
    case RoundOutcome::kGroundingFailed: return "grounding failed";
    case RoundOutcome::kPlannerError: return "planner error";
  }
  return "unknown";
}

std::string describeGroundingFailure(const GroundingFailure& failure, const Plan& plan) {
  std::string step = "step " + std::to_string(failure.actionIndex + 1);
  if (failure.actionIndex < plan.actions.size()) step += " (" + describeAction(plan.actions[failure.actionIndex]) + ")";
  std::string text = step + " could not be executed";
  if (!failure.stage.empty()) text += " at the " + failure.stage + " stage";
  if (!failure.object.empty()) text += " for " + failure.object;
  return text + ": " + failure.reason;
}

RepairResult planWithRepair(TaskPlanner& planner, const PlanningRequest& request, PlanExecutor* executor,
                            const RepairOptions& options, const StopCondition& stop) {
  if (request.scene == nullptr) throw InputError("planning request: no scene given");
  if (options.maxRounds < 1) {
    throw InputError("repair options: maxRounds must be at least 1 (got " + std::to_string(options.maxRounds) + ")");
  }
  RepairResult result;
  PlanningRequest current = request;
  std::string ending;
  for (int number = 1; number <= options.maxRounds; ++number) {
    if (stop.shouldStop()) {
      ending = "stopped (deadline or cancellation) before round " + std::to_string(number);
      break;
    }
    RepairRound& round = result.rounds.emplace_back();
    round.round = number;
    report(options.progress, {ProgressStage::kPlannerCall, number, -1, "", planner.name()});
    askPlanner(planner, current, stop, round);
    if (round.attempt.plan) checkPlan(current, executor, options, stop, round);
    report(options.progress, {ProgressStage::kPlannerAnswer, number, -1, roundOutcomeName(round.outcome), round.attempt.failure});
    accumulate(result.statistics, round.statistics);
    if (round.outcome == RoundOutcome::kAccepted) {
      result.plan = round.attempt.plan;
      return result;
    }
    if (round.outcome == RoundOutcome::kPlannerError) {
      ending = round.attempt.failure;
      break;
    }
    current.earlierAttempts.push_back(round.attempt);
  }
  if (ending.empty()) {
    ending = "no acceptable plan from " + planner.name() + " after " + std::to_string(result.rounds.size()) +
             (result.rounds.size() == 1 ? " round" : " rounds");
  }
  // A planner error is the ending itself; only the rounds before it are listed then.
  const bool endedByPlannerError =
      !result.rounds.empty() && result.rounds.back().outcome == RoundOutcome::kPlannerError;
  const std::vector<RepairRound> listed(result.rounds.begin(), result.rounds.end() - (endedByPlannerError ? 1 : 0));
  if (!listed.empty()) ending += (endedByPlannerError ? "; earlier attempts:" : "; attempts:") + roundsText(listed);
  result.failure = ending;
  return result;
}

}  // namespace lang2manip
