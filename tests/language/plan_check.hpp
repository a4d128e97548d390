#pragma once
/// @file An independent check of plans for the language tests: replays the actions on a
/// symbolic state, checking each precondition, then checks the goals that must hold at the end.

#include <span>
#include <string>
#include <utility>

#include "lang2manip/language/instruction.hpp"
#include "lang2manip/symbolic/action.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"

namespace lang2manip::test {

/// "" when `plan` is valid from `state` and reaches every final in/on/holding goal of
/// `specification`; otherwise the first problem, e.g. "action 3 (pick eraser): gripper holds
/// marker".
std::string checkPlan(const Plan& plan, SymbolicState state,
                      const TaskSpecification& specification);

/// Expects every instruction of `cases` to mean its goals (as summarize() writes them) on `scene`
/// and to get a plan checkPlan() accepts; a refusal is a test failure naming why.
void expectUnderstoodAndPlanned(const Scene& scene, std::span<const std::pair<const char*, const char*>> cases);

}  // namespace lang2manip::test
