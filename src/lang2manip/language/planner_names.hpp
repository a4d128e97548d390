#pragma once
/// @file Motion planner names an instruction may use ("using RRT*", "with rrt connect",
/// "omplRRTConnect"), mapped to the names the planner registry knows: OMPL's class names
/// (RRTConnect, RRTstar, PRM, ...) and Kautham names that have no OMPL equivalent. Whether a
/// planner is really available is checked later by the motion layer.

#include <optional>
#include <string>
#include <vector>

#include "lang2manip/language/words.hpp"

namespace lang2manip {

/// The registry name for a planner name, alias or spoken form, matched case-insensitively: an OMPL name
/// ("RRTConnect"), a Kautham name ("omplRRTConnect", "omplRRTStar"), or a spoken form ("RRT*",
/// "rrt connect", "PRM star"); nullopt when unknown.
std::optional<std::string> plannerNameFromWords(const std::string& name);

/// A planner name found in a word sequence.
struct PlannerMatch {
  std::string name;
  std::size_t length = 0;
};

/// The longest planner name or alias starting at `words[at]`; nullopt when none.
std::optional<PlannerMatch> matchPlannerName(const Words& words, std::size_t at);

}  // namespace lang2manip
