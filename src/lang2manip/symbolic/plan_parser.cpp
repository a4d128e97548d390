#include "lang2manip/symbolic/plan_parser.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <set>

#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/symbolic/goal_statement.hpp"


namespace lang2manip {
namespace {

using nlohmann::json;

const std::vector<std::string> kPlanFields{"actions", "reasoning", "goals"};
const std::vector<std::string> kActionFields{"action", "object", "params", "refinements", "planner"};
const std::vector<std::string> kParamFields{"relation",    "target",        "distance",  "position",
                                            "orientation", "configuration", "direction", "region"};
const std::vector<std::string> kRefinementFields{"grasp", "approach"};
/// The largest coordinate of a position a plan may give, metres (said in the message below).
constexpr double kLargestCoordinate = 100.0;


/// A name from the document in quotes, cut after 60 bytes: an answer may hold names of megabytes.
std::string inQuotes(const std::string& text) {
  constexpr std::size_t kMaxShown = 60;
  if (text.size() <= kMaxShown) return "\"" + text + "\"";
  return "\"" + std::string(utf8Prefix(text, kMaxShown)) + "...\"";
}

/// A computed length for messages ("inf" when it overflowed).
std::string lengthText(double length) {
  return std::isfinite(length) ? json(length).dump() : std::string("inf");
}

/// A short rendering of a JSON value for messages; never serialises more than it shows.
std::string shown(const json& value) {
  return std::string(value.type_name()) + " " + boundedJsonDump(value, 40);
}

/// "Left of" -> "left_of".
std::string normalizedName(const std::string& name) {
  std::string result;
  for (char c : name) {
    const auto u = static_cast<unsigned char>(c);
    result += (c == ' ' || c == '-') ? '_' : static_cast<char>(std::tolower(u));
  }
  const auto first = result.find_first_not_of('_');
  const auto last = result.find_last_not_of('_');
  return first == std::string::npos ? std::string() : result.substr(first, last - first + 1);
}

std::optional<SpatialRelation> relationFromLooseName(const std::string& name) {
  const std::string n = normalizedName(name);
  if (n == "into" || n == "inside") return SpatialRelation::kIn;
  if (n == "onto" || n == "on_top_of") return SpatialRelation::kOn;
  if (n == "beside") return SpatialRelation::kNextTo;
  if (n == "in_front") return SpatialRelation::kInFrontOf;
  return spatialRelationFromName(n);
}

/// Collects problems while reading a plan document.
class PlanReader {
 public:
  explicit PlanReader(const PlanParseContext& context) : context_(context) {}

  Plan read(const json& document) {
    Plan plan;
    const json* actions = &document;
    if (document.is_object()) {
      checkFields(document, "", kPlanFields);
      if (auto reasoning = optionalString(document, "reasoning", "reasoning")) plan.reasoning = *reasoning;
      if (const json* goals = find(document, "goals")) plan.goals = readGoalStatement(*goals, "goals", context_.objects, problems_);
      actions = find(document, "actions");
      if (actions == nullptr) {
        report("actions", "missing; the plan needs an \"actions\" array");
        return plan;
      }
    } else if (!document.is_array()) {
      report("(document)", "expected a plan object {\"actions\": [...]}, got " + shown(document));
      return plan;
    }
    readActions(*actions, plan);
    return plan;
  }

  [[nodiscard]] const std::vector<std::string>& problems() const { return problems_; }

 private:
  void report(const std::string& path, const std::string& message) {
    problems_.push_back((path.empty() ? std::string("(document)") : path) + ": " + message);
  }

  static const json* find(const json& object, const std::string& name) {
    const auto it = object.find(name);
    return (it == object.end() || it->is_null()) ? nullptr : &*it;
  }

  static std::string join(const std::string& path, const std::string& field) {
    return path.empty() ? field : path + "." + field;
  }

  void checkFields(const json& object, const std::string& path, const std::vector<std::string>& valid) {
    for (const auto& [name, value] : object.items()) {
      if (std::find(valid.begin(), valid.end(), name) == valid.end()) {
        report(join(path, name), "unknown field (valid fields: " + joinedNames(valid) + ")");
      }
    }
  }

  std::optional<std::string> optionalString(const json& object, const std::string& field,
                                            const std::string& path) {
    const json* value = find(object, field);
    if (value == nullptr) return std::nullopt;
    if (!value->is_string()) {
      report(path, "expected a string, got " + shown(*value));
      return std::nullopt;
    }
    return value->get<std::string>();
  }

  void readActions(const json& actions, Plan& plan) {
    if (!actions.is_array()) {
      report("actions", "expected an array of actions, got " + shown(actions));
      return;
    }
    if (actions.empty()) report("actions", "empty; the plan needs at least one action");
    for (std::size_t i = 0; i < actions.size(); ++i) {
      const std::string path = "actions[" + std::to_string(i) + "]";
      if (auto action = readAction(actions[i], path)) plan.actions.push_back(*action);
    }
  }

  std::optional<SymbolicAction> readAction(const json& item, const std::string& path) {
    if (!item.is_object()) {
      report(path, "expected an action object, got " + shown(item));
      return std::nullopt;
    }
    const std::size_t before = problems_.size();
    checkFields(item, path, kActionFields);
    SymbolicAction action;
    const std::optional<ActionType> type = readActionType(item, path);
    if (auto object = optionalString(item, "object", path + ".object")) {
      action.object = checkObject(*object, path + ".object");
    }
    if (const json* params = find(item, "params")) readParams(*params, path + ".params", action.params);
    if (const json* refinements = find(item, "refinements")) {
      readRefinements(*refinements, path + ".refinements", action.refinements);
    }
    if (auto planner = optionalString(item, "planner", path + ".planner")) {
      action.planner = checkPlanner(*planner, path + ".planner");
    }
    if (!type) return std::nullopt;
    action.type = *type;
    checkActionShape(item, action, path);
    if (problems_.size() != before) return std::nullopt;
    return action;
  }

  std::optional<ActionType> readActionType(const json& item, const std::string& path) {
    const json* value = find(item, "action");
    if (value == nullptr) {
      report(path + ".action", "missing (one of: " + joinedNames(actionTypeNames()) + ")");
      return std::nullopt;
    }
    if (!value->is_string()) {
      report(path + ".action", "expected a string, got " + shown(*value));
      return std::nullopt;
    }
    const auto type = actionTypeFromName(normalizedName(value->get<std::string>()));
    if (!type) {
      report(path + ".action", "unknown action " + inQuotes(value->get<std::string>()) +
                                   " (valid actions: " + joinedNames(actionTypeNames()) + ")");
    }
    return type;
  }

  std::string checkObject(const std::string& name, const std::string& path) {
    if (name.empty() || context_.objects.empty()) return name;
    for (const std::string& object : context_.objects) {
      if (object == name) return object;
    }
    for (const std::string& object : context_.objects) {
      if (normalizedName(object) == normalizedName(name)) return object;
    }
    report(path, "unknown object " + inQuotes(name) + " (objects: " + joinedNames(context_.objects) + ")");
    return name;
  }

  std::string checkPlanner(const std::string& name, const std::string& path) {
    if (name.empty() || context_.planners.empty()) return name;
    if (std::find(context_.planners.begin(), context_.planners.end(), name) == context_.planners.end()) {
      report(path, "unknown planner " + inQuotes(name) + " (planners: " + joinedNames(context_.planners) +
                       "; or null for the default)");
    }
    return name;
  }

  void readParams(const json& params, const std::string& path, ActionParams& out) {
    if (!params.is_object()) {
      report(path, "expected an object or null, got " + shown(params));
      return;
    }
    checkFields(params, path, kParamFields);
    if (auto relation = optionalString(params, "relation", path + ".relation")) {
      out.relation = relationFromLooseName(*relation);
      if (!out.relation) {
        report(path + ".relation", "unknown relation " + inQuotes(*relation) +
                                       " (valid relations: " + joinedNames(spatialRelationNames()) + ")");
      }
    }
    if (auto target = optionalString(params, "target", path + ".target")) {
      out.target = checkObject(*target, path + ".target");
    }
    if (const json* distance = find(params, "distance")) {
      out.distance = readPositive(*distance, path + ".distance");
    }
    if (const json* position = find(params, "position")) {
      out.position = readVector(*position, path + ".position", false);
    }
    if (const json* orientation = find(params, "orientation")) {
      out.orientation = readQuaternion(*orientation, path + ".orientation");
    }
    if (auto configuration = optionalString(params, "configuration", path + ".configuration")) {
      out.configuration = *configuration;
    }
    if (const json* direction = find(params, "direction")) {
      out.direction = readVector(*direction, path + ".direction", true);
    }
    if (auto region = optionalString(params, "region", path + ".region")) {
      out.region = surfaceRegionFromName(normalizedName(*region));
      if (!out.region) {
        report(path + ".region", "unknown region " + inQuotes(*region) + " (valid regions: " +
                                     joinedNames(surfaceRegionNames()) + ")");
      }
    }
  }

  void readRefinements(const json& refinements, const std::string& path, ActionRefinements& out) {
    if (!refinements.is_object()) {
      report(path, "expected an object or null, got " + shown(refinements));
      return;
    }
    checkFields(refinements, path, kRefinementFields);
    if (auto grasp = optionalString(refinements, "grasp", path + ".grasp")) {
      if (auto direction = graspDirectionFromName(normalizedName(*grasp))) {
        out.grasp = *direction;
      } else {
        report(path + ".grasp", "unknown grasp " + inQuotes(*grasp) + " (valid grasps: " +
                                    joinedNames(graspDirectionNames()) + ")");
      }
    }
    if (const json* approach = find(refinements, "approach")) {
      out.approach = readVector(*approach, path + ".approach", true);
    }
  }

  std::optional<double> readNumber(const json& value, const std::string& path) {
    if (!value.is_number()) {
      report(path, "expected a number, got " + shown(value));
      return std::nullopt;
    }
    const double number = value.get<double>();
    if (!std::isfinite(number)) {
      report(path, "not a finite number");
      return std::nullopt;
    }
    return number;
  }

  std::optional<double> readPositive(const json& value, const std::string& path) {
    const auto number = readNumber(value, path);
    if (number && *number <= 0.0) {
      report(path, (*number < 0.0 ? "negative distance " : "zero distance ") + value.dump() +
                       "; distances are positive, in metres");
      return std::nullopt;
    }
    return number;
  }

  /// Components named `names` from an object {name: number} or an array in that order.
  std::optional<std::vector<double>> readComponents(const json& value, const std::string& path,
                                                    const std::vector<std::string>& names) {
    std::vector<double> components;
    if (value.is_array() && value.size() == names.size()) {
      for (std::size_t i = 0; i < names.size(); ++i) {
        const auto number = readNumber(value[i], path + "[" + std::to_string(i) + "]");
        if (!number) return std::nullopt;
        components.push_back(*number);
      }
      return components;
    }
    if (!value.is_object()) {
      report(path, "expected an object {" + joinedNames(names) + "}, got " + shown(value));
      return std::nullopt;
    }
    checkFields(value, path, names);
    bool complete = true;
    for (const std::string& name : names) {
      const json* component = find(value, name);
      std::optional<double> number;
      if (component == nullptr) {
        report(path + "." + name, "missing");
      } else {
        number = readNumber(*component, path + "." + name);
      }
      complete = complete && number.has_value();
      components.push_back(number.value_or(0.0));
    }
    if (!complete) return std::nullopt;
    return components;
  }

  std::optional<Vector3> readVector(const json& value, const std::string& path, bool unit) {
    const auto c = readComponents(value, path, {"x", "y", "z"});
    if (!c) return std::nullopt;
    Vector3 v((*c)[0], (*c)[1], (*c)[2]);
    if (!unit) {
      // Positions are in metres from the robot's base: anything beyond this is no place in a scene.
      if (v.cwiseAbs().maxCoeff() > kLargestCoordinate) {
        report(path, "a coordinate beyond 100 m from the robot; positions are in metres");
        return std::nullopt;
      }
      return v;
    }
    if (v.norm() < 1e-9) {
      report(path, "zero vector; give a unit direction");
      return std::nullopt;
    }
    if (std::abs(v.norm() - 1.0) > context_.unitTolerance) {
      report(path, "not a unit vector (length " + lengthText(v.norm()) + ")");
      return std::nullopt;
    }
    return v.normalized();
  }

  std::optional<Quaternion> readQuaternion(const json& value, const std::string& path) {
    const auto c = readComponents(value, path, {"w", "x", "y", "z"});
    if (!c) return std::nullopt;
    Quaternion q((*c)[0], (*c)[1], (*c)[2], (*c)[3]);
    if (q.norm() < 1e-9) {
      report(path, "zero quaternion; give a unit quaternion");
      return std::nullopt;
    }
    if (std::abs(q.norm() - 1.0) > context_.unitTolerance) {
      report(path, "not a unit quaternion (norm " + lengthText(q.norm()) + ")");
      return std::nullopt;
    }
    return q.normalized();
  }

  /// Which parameters each action takes, from the fields present in the document (so a field
  /// already reported as malformed is not reported missing too).
  void checkActionShape(const json& item, const SymbolicAction& action, const std::string& path) {
    const std::string verb = actionTypeName(action.type);
    std::set<std::string> given;
    if (const json* params = find(item, "params"); params != nullptr && params->is_object()) {
      for (const auto& [name, value] : params->items()) {
        if (!value.is_null()) given.insert(name);
      }
    }
    const bool hasObject = find(item, "object") != nullptr;
    if (!hasObject && action.type != ActionType::kMove) {
      report(path + ".object", "missing; " + verb + " needs an object");
    }
    const std::vector<std::string> allowed = allowedParams(action.type);
    for (const std::string& name : given) {
      const bool known = std::find(kParamFields.begin(), kParamFields.end(), name) != kParamFields.end();
      if (known && std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
        report(path + ".params." + name, "not used by " + verb + (allowed.empty() ? " (it takes no parameters)" : " (it takes: " + joinedNames(allowed) + ")"));
      }
    }
    const std::string params = path + ".params";
    switch (action.type) {
      case ActionType::kPick:
        break;
      case ActionType::kPlace:
        checkPlaceShape(given, action, params);
        break;
      case ActionType::kMove:
        if (given.count("configuration") == given.count("position")) {
          report(params, "move needs either a configuration (such as \"home\") or a position");
        }
        break;
      case ActionType::kPush:
        if (!given.count("direction")) report(params + ".direction", "missing; push needs a unit direction");
        if (!given.count("distance")) report(params + ".distance", "missing; push needs a distance in metres");
        break;
    }
  }

  void checkPlaceShape(const std::set<std::string>& given, const SymbolicAction& action,
                       const std::string& params) {
    const bool relation = given.count("relation") > 0;
    const bool target = given.count("target") > 0;
    const bool position = given.count("position") > 0;
    if (!relation && !target && !position) {
      report(params, "place needs a relation and a target object, or a position");
      return;
    }
    if (position && (relation || target)) {
      report(params + ".position", "give either a relation with a target or a position, not both");
    }
    if (relation && !target) report(params + ".target", "missing; place needs a target object for its relation");
    if (target && !relation && !position) {
      report(params + ".relation", "missing (one of: " + joinedNames(spatialRelationNames()) + ")");
    }
    if (!action.object.empty() && action.object == action.params.target) {
      report(params + ".target", "the object cannot be placed relative to itself");
    }
    const bool distanceRelation = action.params.relation && *action.params.relation != SpatialRelation::kIn &&
                                  *action.params.relation != SpatialRelation::kOn;
    if (given.count("distance") && relation && action.params.relation && !distanceRelation) {
      report(params + ".distance", "not used with relation \"" + spatialRelationName(*action.params.relation) + "\"");
    }
    if (given.count("distance") && !relation) report(params + ".distance", "only used with a relation");
    if (given.count("region") && action.params.relation && *action.params.relation != SpatialRelation::kOn) {
      report(params + ".region", "only used with relation \"on\" (a region of the target's top face)");
    }
    if (given.count("region") && !relation) report(params + ".region", "only used with relation \"on\"");
  }

  static std::vector<std::string> allowedParams(ActionType type) {
    switch (type) {
      case ActionType::kPick: return {};
      case ActionType::kPlace: return {"relation", "target", "distance", "position", "orientation", "region"};
      case ActionType::kMove: return {"position", "orientation", "configuration"};
      case ActionType::kPush: return {"direction", "distance"};
    }
    return {};
  }

  const PlanParseContext& context_;
  std::vector<std::string> problems_;
};

std::string problemsText(const std::vector<std::string>& problems) {
  std::string text = "the plan has " + std::to_string(problems.size()) +
                     (problems.size() == 1 ? " problem:" : " problems:");
  for (const std::string& problem : problems) text += "\n  " + problem;
  return text;
}

}  // namespace

PlanParseError::PlanParseError(std::vector<std::string> problems)
    : InputError(problemsText(problems)), problems_(std::move(problems)) {}

Plan parsePlan(const nlohmann::json& document, const PlanParseContext& context) {
  PlanReader reader(context);
  Plan plan = reader.read(document);
  if (!reader.problems().empty()) throw PlanParseError(reader.problems());
  return plan;
}

Plan parsePlanText(std::string_view text, const PlanParseContext& context, const JsonLimits& limits) {
  return parsePlan(extractJsonDocument(text, limits), context);
}

}  // namespace lang2manip
