#pragma once
/// @file Parsing untrusted plan documents (LLM answers, files) into a Plan. Every problem is
/// reported with its JSON path, e.g. `actions[2].params.target: unknown object "cup" (objects:
/// marker, eraser, holder, desk)`, and all problems are collected before failing.

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/json_limits.hpp"
#include "lang2manip/symbolic/action.hpp"

namespace lang2manip {

/// What a plan may refer to.
struct PlanParseContext {
  /// Valid object names; object and target names are checked only when this is not empty.
  std::vector<std::string> objects;
  /// Valid motion planner names; `planner` is checked only when this is not empty.
  std::vector<std::string> planners;
  /// How far a direction's norm may be from 1 before it is rejected (it is then normalized).
  double unitTolerance = 0.02;
};

/// A plan document with problems. what() lists them one per line; problems() gives each as
/// "path: what is wrong".
class PlanParseError : public InputError {
 public:
  explicit PlanParseError(std::vector<std::string> problems);
  [[nodiscard]] const std::vector<std::string>& problems() const noexcept { return problems_; }

 private:
  std::vector<std::string> problems_;
};

/// The JSON document inside an answer: the whole text, a ```json fenced block, or the text from
/// the first '{' to its matching '}' after leading prose. Throws PlanParseError when there is
/// no JSON, it is malformed (with the position; any nlohmann failure, numbers out of range such
/// as 1e400 included), or the text exceeds `limits` (size, nesting depth: checked before
/// parsing, so no answer can exhaust the stack).
nlohmann::json extractJsonDocument(std::string_view text, const JsonLimits& limits = {});

/// Parses a plan document. Accepts the schema's form and common variants: fields absent
/// instead of null, a bare array of actions, names in other case or with spaces ("Left of"),
/// vectors as [x, y, z] arrays, quaternions as [w, x, y, z]. Throws PlanParseError listing
/// every problem (unknown fields, wrong types, unknown actions/relations/grasps/objects/
/// planners, missing or contradictory parameters, zero or non-unit vectors, non-positive
/// distances, an empty plan).
Plan parsePlan(const nlohmann::json& document, const PlanParseContext& context);

/// extractJsonDocument() then parsePlan(): for answer text and plan files. Throws
/// PlanParseError for every problem of the text.
Plan parsePlanText(std::string_view text, const PlanParseContext& context, const JsonLimits& limits = {});

}  // namespace lang2manip
