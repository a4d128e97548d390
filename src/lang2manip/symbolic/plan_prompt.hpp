#pragma once
/// @file Prompt assembly for task planners: a fixed, versioned system prompt (the action
/// grammar, the plan schema, rules, one short example), the user message with the task and the
/// observation, and repair messages that describe earlier attempts and their failures.

#include <string>
#include <vector>

#include "lang2manip/llm/llm_client.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip {

/// Version of the system prompt; changes whenever its text changes (recorded with each plan).
inline constexpr const char* kPlanPromptVersion = "lang2manip-plan-prompt-4";

/// The fixed system prompt. `planners` (may be empty) lists the motion planners an action may
/// name; they are appended as one line so the prompt's fixed part never changes.
std::string planSystemPrompt(const std::vector<std::string>& planners = {});

/// The first user message: the task and the observation text (observationText()).
std::string planTaskMessage(const std::string& task, const std::string& observation);

/// The user message after a rejected answer: what was wrong, in words, and what to do.
std::string planRepairMessage(const PlanAttempt& attempt, int attemptNumber);

/// The whole conversation for one round: the task message, then for each earlier attempt (the
/// last `maxAttempts` of them) the answer as an assistant turn and its repair message.
std::vector<LlmMessage> planMessages(const std::string& task, const std::string& observation,
                                     const std::vector<PlanAttempt>& earlierAttempts,
                                     std::size_t maxAttempts = 3);

/// A readable rendering of a system prompt and messages ("--print-prompt").
std::string renderPrompt(const std::string& system, const std::vector<LlmMessage>& messages);

}  // namespace lang2manip
