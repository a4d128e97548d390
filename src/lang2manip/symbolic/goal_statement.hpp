#pragma once
/// @file A plan's goal statement: the final state a task planner says its plan reaches
/// ("goals": [{"kind": "relation", "object": "marker", "relation": "in", "target": "holder", ...}]).
/// When the instruction is beyond the offline parser, these are the goals checked against the
/// final world.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lang2manip/symbolic/action.hpp"

namespace lang2manip {

/// "relation", "holding", "displaced", "at_configuration", "handed_over", "at_position", "turned",
/// "facing".
std::string goalKindName(GoalKind kind);

/// The JSON Schema (strict mode: every field given, null where it does not apply) of the
/// "goals" array of a plan, null allowed.
nlohmann::json goalStatementSchema();

/// The goals as the plan document writes them (null when there are none).
nlohmann::json goalStatementJson(const std::vector<Goal>& goals);

/// Reads the "goals" array at `path`. Each problem is appended to `problems` as "path: what";
/// names are checked against `objects` when it is not empty. Fields may be absent instead of
/// null; the fields a kind needs must be given, the others must be null or absent.
std::vector<Goal> readGoalStatement(const nlohmann::json& goals, const std::string& path,
                                    const std::vector<std::string>& objects, std::vector<std::string>& problems);

}  // namespace lang2manip
