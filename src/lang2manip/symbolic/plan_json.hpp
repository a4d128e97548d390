#pragma once
/// @file The plan as JSON: the JSON Schema planners answer with (valid for OpenAI's strict
/// structured-output mode) and the conversion of a Plan to that JSON. Parsing is in
/// plan_parser.hpp.
///
/// The plan document:
/// @code
/// {"reasoning": "..." | null,
///  "actions": [{"action": "pick" | "place" | "move" | "push",
///               "object": "marker" | null,
///               "params": {"relation", "target", "distance", "position", "orientation",
///                          "configuration", "direction"} | null,
///               "refinements": {"grasp", "approach"} | null,
///               "planner": "RRTConnect" | null}, ...],
///  "goals": [{"kind": "relation" | "holding" | "displaced" | "at_configuration",
///             "object", "relation", "target", "distance", "displacement",
///             "configuration"}, ...] | null}
/// @endcode
/// "goals" is the planner's goal statement (goal_statement.hpp).
/// Vectors are objects {"x","y","z"} (metres or unit vectors, robot base frame); orientations
/// are quaternions {"w","x","y","z"}.

#include <nlohmann/json.hpp>
#include <string>

#include "lang2manip/symbolic/action.hpp"

namespace lang2manip {

/// The JSON Schema of a plan document. Strict-mode compatible: every object lists all its
/// properties in `required` and has `"additionalProperties": false`; optional values are
/// unions with "null"; no keywords strict mode rejects (minLength, pattern, minItems, ...).
nlohmann::json planJsonSchema();

/// The plan document for `plan` (every field present, null where unset).
nlohmann::json toJson(const Plan& plan);
/// One action of the plan document.
nlohmann::json toJson(const SymbolicAction& action);

/// A short description of an action for messages: "pick marker", "place eraser in holder",
/// "move to home", "push eraser 0.05 m along (0, 1, 0)".
std::string describeAction(const SymbolicAction& action);

}  // namespace lang2manip
