#include "lang2manip/symbolic/goal_statement.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "lang2manip/core/json_limits.hpp"
#include "lang2manip/symbolic/arrangement_check.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

constexpr GoalKind kGoalKinds[] = {GoalKind::kRelation, GoalKind::kHolding, GoalKind::kDisplaced,
                                   GoalKind::kAtConfiguration, GoalKind::kHandedOver, GoalKind::kAtPosition,
                                   GoalKind::kTurned, GoalKind::kFacing, GoalKind::kArranged};
const std::vector<std::string> kGoalFields{"kind",     "object", "relation", "target",  "distance", "displacement",  "configuration",
                                           "position", "angle",  "region",   "members", "shape",    "heading", "evenly_spaced"};

json nullableOf(const json& type, const std::string& description) {
  return {{"anyOf", {type, {{"type", "null"}}}}, {"description", description}};
}

std::string shown(const json& value) { return std::string(value.type_name()) + " " + boundedJsonDump(value, 40); }

/// Reads one goal object, reporting each problem under `path`.
class GoalReader {
 public:
  GoalReader(const std::vector<std::string>& objects, std::vector<std::string>& problems)
      : objects_(objects), problems_(problems) {}

  std::optional<Goal> read(const json& item, const std::string& path) {
    if (!item.is_object()) return fail(path, "expected a goal object, got " + shown(item));
    for (const auto& [name, value] : item.items()) {
      if (std::find(kGoalFields.begin(), kGoalFields.end(), name) == kGoalFields.end()) {
        report(path + "." + name, "unknown field (valid fields: kind, object, relation, target, distance, displacement, configuration, position, angle, region, members, shape, heading, evenly_spaced)");
      }
    }
    const std::optional<GoalKind> kind = readKind(item, path);
    if (!kind) return std::nullopt;
    Goal goal;
    goal.kind = *kind;
    const std::size_t before = problems_.size();
    checkGiven(item, path, requiredFields(*kind), optionalFields(*kind));
    goal.object = objectName(item, "object", path);
    goal.target = objectName(item, "target", path);
    goal.configuration = stringField(item, "configuration", path);
    if (const json* relation = given(item, "relation")) goal.relation = readRelation(*relation, path + ".relation");
    if (const json* distance = given(item, "distance")) goal.distance = readPositive(*distance, path + ".distance");
    if (const json* displacement = given(item, "displacement")) {
      goal.displacement = readVector(*displacement, path + ".displacement");
      if (goal.displacement.norm() == 0.0) report(path + ".displacement", "a displacement of zero moves nothing");
    }
    if (const json* position = given(item, "position")) goal.position = readVector(*position, path + ".position");
    if (const json* angle = given(item, "angle")) goal.angle = readAngle(*angle, path + ".angle", goal.kind == GoalKind::kFacing);
    if (const json* region = given(item, "region")) goal.region = readRegion(*region, path + ".region");
    if (goal.kind == GoalKind::kArranged) readArrangement(item, path, goal);
    if (goal.region && goal.relation && *goal.relation != SpatialRelation::kOn) {
      report(path + ".region", "only used with relation \"on\" (a region of the target's top face)");
    }
    if (goal.kind == GoalKind::kFacing && (given(item, "target") == nullptr) == (given(item, "angle") == nullptr)) {
      report(path, "a facing goal needs a target to point at or an angle (the heading of its long side), not both");
    }
    if (problems_.size() != before) return std::nullopt;
    return goal;
  }

 private:
  std::optional<Goal> fail(const std::string& path, const std::string& message) {
    report(path, message);
    return std::nullopt;
  }
  void report(const std::string& path, const std::string& message) { problems_.push_back(path + ": " + message); }

  /// The members, shape, heading and spacing of an arranged goal.
  void readArrangement(const json& item, const std::string& path, Goal& goal) {
    if (const json* members = given(item, "members")) {
      if (!members->is_array()) report(path + ".members", "expected an array of object names, got " + shown(*members));
      for (std::size_t i = 0; members->is_array() && i < members->size(); ++i) {
        const std::string where = path + ".members[" + std::to_string(i) + "]";
        const json& member = (*members)[i];
        if (!member.is_string()) {
          report(where, "expected an object name, got " + shown(member));
          continue;
        }
        const std::string name = member.get<std::string>();
        checkKnown(name, where);
        if (std::find(goal.members.begin(), goal.members.end(), name) != goal.members.end()) report(where, "\"" + name + "\" is named twice");
        goal.members.push_back(name);
      }
    }
    if (const json* shape = given(item, "shape")) {
      if (shape->is_string()) goal.shape = arrangementShapeFromName(shape->get<std::string>());
      std::string names;
      for (const std::string& name : arrangementShapeNames()) names += (names.empty() ? "" : ", ") + name;
      if (!goal.shape) report(path + ".shape", "unknown shape " + shown(*shape) + " (shapes: " + names + ")");
    }
    if (const json* heading = given(item, "heading")) goal.heading = readAngle(*heading, path + ".heading", true);
    if (const json* evenly = given(item, "evenly_spaced")) {
      if (!evenly->is_boolean()) report(path + ".evenly_spaced", "expected true or false, got " + shown(*evenly));
      goal.evenlySpaced = evenly->is_boolean() && evenly->get<bool>();
    }
    if (!goal.shape) return;
    if (const std::string problem = memberCountProblem(*goal.shape, goal.members.size()); !problem.empty()) report(path + ".members", problem);
    const bool line = *goal.shape == ArrangementShape::kLine;
    if (!line && (goal.heading || goal.evenlySpaced || goal.distance)) report(path, "heading, evenly_spaced and distance are of a line only");
  }

  static const json* given(const json& item, const std::string& field) {
    const auto it = item.find(field);
    return (it == item.end() || it->is_null()) ? nullptr : &*it;
  }

  static std::vector<std::string> requiredFields(GoalKind kind) {
    switch (kind) {
      case GoalKind::kRelation: return {"object", "relation", "target"};
      case GoalKind::kHolding: return {"object"};
      case GoalKind::kHandedOver: return {"object"};
      case GoalKind::kDisplaced: return {"object", "displacement"};
      case GoalKind::kAtConfiguration: return {"configuration"};
      case GoalKind::kAtPosition: return {"object", "position"};
      case GoalKind::kTurned: return {"object", "angle"};
      case GoalKind::kFacing: return {"object"};
      case GoalKind::kArranged: return {"members", "shape"};
    }
    return {};
  }
  static std::vector<std::string> optionalFields(GoalKind kind) {
    if (kind == GoalKind::kRelation) return {"distance", "region"};
    if (kind == GoalKind::kAtPosition) return {"target"};
    if (kind == GoalKind::kFacing) return {"target", "angle"};
    if (kind == GoalKind::kTurned) return {"position"};
    if (kind == GoalKind::kArranged) return {"target", "region", "heading", "evenly_spaced", "distance"};
    return {};
  }

  void checkGiven(const json& item, const std::string& path, const std::vector<std::string>& required,
                  const std::vector<std::string>& optional) {
    const std::string kind = item.at("kind").get<std::string>();
    const std::string article = std::string("aeiou").find(kind.front()) == std::string::npos ? "a " : "an ";
    for (const std::string& field : required) {
      if (given(item, field) == nullptr) report(path + "." + field, "missing; " + article + kind + " goal needs it");
    }
    for (const std::string& field : kGoalFields) {
      const bool allowed = field == "kind" || std::count(required.begin(), required.end(), field) != 0 ||
                           std::count(optional.begin(), optional.end(), field) != 0;
      if (!allowed && given(item, field) != nullptr) report(path + "." + field, "must be null for " + article + kind + " goal");
    }
  }

  std::optional<GoalKind> readKind(const json& item, const std::string& path) {
    const json* kind = given(item, "kind");
    std::string names;
    for (const GoalKind k : kGoalKinds) {
      if (kind != nullptr && kind->is_string() && kind->get<std::string>() == goalKindName(k)) return k;
      names += (names.empty() ? "" : ", ") + goalKindName(k);
    }
    report(path + ".kind", (kind == nullptr ? std::string("missing") : "unknown kind " + shown(*kind)) + " (kinds: " + names + ")");
    return std::nullopt;
  }

  std::string stringField(const json& item, const std::string& field, const std::string& path) {
    const json* value = given(item, field);
    if (value == nullptr) return {};
    if (!value->is_string()) {
      report(path + "." + field, "expected a string, got " + shown(*value));
      return {};
    }
    return value->get<std::string>();
  }

  std::string objectName(const json& item, const std::string& field, const std::string& path) {
    const std::string name = stringField(item, field, path);
    checkKnown(name, path + "." + field);
    return name;
  }

  void checkKnown(const std::string& name, const std::string& where) {
    if (!name.empty() && !objects_.empty() && std::find(objects_.begin(), objects_.end(), name) == objects_.end()) {
      std::string names;
      for (const std::string& object : objects_) names += (names.empty() ? "" : ", ") + object;
      report(where, "unknown object " + boundedJsonDump(json(name), 60) + " (objects: " + names + ")");
    }
  }

  std::optional<SpatialRelation> readRelation(const json& value, const std::string& path) {
    if (value.is_string()) {
      if (auto relation = spatialRelationFromName(value.get<std::string>())) return relation;
    }
    std::string names;
    for (const std::string& name : spatialRelationNames()) names += (names.empty() ? "" : ", ") + name;
    report(path, "unknown relation " + shown(value) + " (relations: " + names + ")");
    return std::nullopt;
  }

  std::optional<SurfaceRegion> readRegion(const json& value, const std::string& path) {
    if (value.is_string()) {
      if (auto region = surfaceRegionFromName(value.get<std::string>())) return region;
    }
    std::string names;
    for (const std::string& name : surfaceRegionNames()) names += (names.empty() ? "" : ", ") + name;
    report(path, "unknown region " + shown(value) + " (regions: " + names + ")");
    return std::nullopt;
  }

  std::optional<double> readPositive(const json& value, const std::string& path) {
    if (value.is_number() && std::isfinite(value.get<double>()) && value.get<double>() > 0.0) return value.get<double>();
    report(path, "expected a positive number of metres, got " + shown(value));
    return std::nullopt;
  }

  double readAngle(const json& value, const std::string& path, bool heading) {
    constexpr double kTwoPi = 6.283185307179586;
    if (value.is_number() && std::isfinite(value.get<double>()) && std::abs(value.get<double>()) <= kTwoPi &&
        (heading || value.get<double>() != 0.0)) {
      return value.get<double>();
    }
    if (heading) {
      report(path, "expected a heading in radians within [-2 pi, 2 pi] (base frame, 0 = front), got " + shown(value));
      return 0.0;
    }
    report(path, "expected a non-zero turn in radians within [-2 pi, 2 pi] (counter-clockwise seen from above), got " + shown(value));
    return 0.0;
  }

  Vector3 readVector(const json& value, const std::string& path) {
    Vector3 v = Vector3::Zero();
    const bool asObject = value.is_object() && value.size() == 3 && value.contains("x") && value.contains("y") && value.contains("z");
    const bool asArray = value.is_array() && value.size() == 3;
    for (int i = 0; (asObject || asArray) && i < 3; ++i) {
      const json& component = asObject ? value.at(std::string(1, static_cast<char>('x' + i))) : value.at(static_cast<std::size_t>(i));
      if (!component.is_number() || !std::isfinite(component.get<double>())) {
        report(path, "expected {x, y, z} in metres, got " + shown(value));
        return v;
      }
      v[i] = component.get<double>();
    }
    if (!asObject && !asArray) report(path, "expected {x, y, z} in metres, got " + shown(value));
    return v;
  }

  const std::vector<std::string>& objects_;
  std::vector<std::string>& problems_;
};

}  // namespace

std::string goalKindName(GoalKind kind) {
  switch (kind) {
    case GoalKind::kRelation: return "relation";
    case GoalKind::kHolding: return "holding";
    case GoalKind::kDisplaced: return "displaced";
    case GoalKind::kAtConfiguration: return "at_configuration";
    case GoalKind::kHandedOver: return "handed_over";
    case GoalKind::kAtPosition: return "at_position";
    case GoalKind::kTurned: return "turned";
    case GoalKind::kFacing: return "facing";
    case GoalKind::kArranged: return "arranged";
  }
  return "unknown";
}

nlohmann::json goalStatementSchema() {
  json kinds = json::array();
  for (const GoalKind kind : kGoalKinds) kinds.push_back(goalKindName(kind));
  json relations = spatialRelationNames();
  const json number = {{"type", "number"}};
  const json vector = {{"type", "object"},
                       {"properties", {{"x", number}, {"y", number}, {"z", number}}},
                       {"required", {"x", "y", "z"}},
                       {"additionalProperties", false}};
  const json goal = {
      {"type", "object"},
      {"description", "One condition of the final state"},
      {"properties",
       {{"kind", {{"type", "string"}, {"enum", kinds}, {"description", "relation, holding, displaced, at_configuration, handed_over, at_position, turned, facing or arranged"}}},
        {"object", nullableOf({{"type", "string"}}, "The object the goal is about (null for at_configuration)")},
        {"relation", nullableOf({{"type", "string"}, {"enum", relations}}, "relation: where the object ends up relative to target")},
        {"target", nullableOf({{"type", "string"}}, "relation: the reference object; facing: what the object's long side points at; at_position: whose place it was (optional); arranged: the support they all stand on (optional)")},
        {"distance", nullableOf(number, "relation: offset from target in metres, when the task gives one; arranged line: the spacing of neighbouring centres")},
        {"displacement", nullableOf(vector, "displaced: how far the object moves, metres, robot base frame")},
        {"configuration", nullableOf({{"type", "string"}}, "at_configuration: the named configuration, e.g. home")},
        {"position", nullableOf(vector, "at_position: where the object frame's origin ends up, metres, robot base frame (x and y are checked); turned: where it stands turned when the plan moved it first (null: where it stood)")},
        {"region", nullableOf({{"type", "string"}, {"enum", surfaceRegionNames()}}, "relation on a support, or arranged on a target: the region of its top face the object's centre ends up in (corners, edges, centre, halves, quadrants of the reachable part)")},
        {"members", nullableOf({{"type", "array"}, {"items", {{"type", "string"}}}}, "arranged: the objects arranged together")},
        {"shape", nullableOf({{"type", "string"}, {"enum", arrangementShapeNames()}}, "arranged: line, circle, triangle (3 members at its corners, or 6, 9, ...: as many more evenly along each side), square (4, or 8, 12, ... likewise), spread_out (no two next_to), together (next to each other: one group of members next_to one another) or pyramid (3, 6 or 10 members: rows resting on two below)")},
        {"heading", nullableOf(number, "arranged line: its direction, radians, base frame (0 = front, pi/2 = left), when the task names one")},
        {"evenly_spaced", nullableOf({{"type", "boolean"}}, "arranged line: neighbours equally far apart")},
        {"angle", nullableOf(number, "turned: the turn about the vertical from where it started, radians, counter-clockwise seen from above; facing without a target: the heading of the long side, radians, base frame (0 = front)")}}},
      {"required", kGoalFields},
      {"additionalProperties", false}};
  return nullableOf({{"type", "array"}, {"items", goal}}, "The final state the plan reaches (what the task asks for)");
}

nlohmann::json goalStatementJson(const std::vector<Goal>& goals) {
  if (goals.empty()) return nullptr;
  json list = json::array();
  for (const Goal& goal : goals) {
    const bool relation = goal.kind == GoalKind::kRelation;
    const bool displaced = goal.kind == GoalKind::kDisplaced;
    const bool arranged = goal.kind == GoalKind::kArranged;
    const auto vectorJson = [](const Vector3& v) { return json{{"x", v.x()}, {"y", v.y()}, {"z", v.z()}}; };
    list.push_back({{"kind", goalKindName(goal.kind)},
                    {"object", goal.object.empty() ? json(nullptr) : json(goal.object)},
                    {"relation", relation && goal.relation ? json(spatialRelationName(*goal.relation)) : json(nullptr)},
                    {"target", goal.target.empty() ? json(nullptr) : json(goal.target)},
                    {"distance", (relation || arranged) && goal.distance ? json(*goal.distance) : json(nullptr)},
                    {"displacement", displaced ? vectorJson(goal.displacement) : json(nullptr)},
                    {"configuration", goal.configuration.empty() ? json(nullptr) : json(goal.configuration)},
                    {"position", (goal.kind == GoalKind::kAtPosition || goal.kind == GoalKind::kTurned) && goal.position ? vectorJson(*goal.position) : json(nullptr)},
                    {"angle", goal.kind == GoalKind::kTurned || (goal.kind == GoalKind::kFacing && goal.target.empty()) ? json(goal.angle) : json(nullptr)},
                    {"region", (relation || arranged) && goal.region ? json(surfaceRegionName(*goal.region)) : json(nullptr)},
                    {"members", arranged ? json(goal.members) : json(nullptr)},
                    {"shape", arranged && goal.shape ? json(arrangementShapeName(*goal.shape)) : json(nullptr)},
                    {"heading", arranged && goal.heading ? json(*goal.heading) : json(nullptr)},
                    {"evenly_spaced", arranged && goal.evenlySpaced ? json(true) : json(nullptr)}});
  }
  return list;
}

std::vector<Goal> readGoalStatement(const nlohmann::json& goals, const std::string& path,
                                    const std::vector<std::string>& objects, std::vector<std::string>& problems) {
  std::vector<Goal> result;
  if (goals.is_null()) return result;
  if (!goals.is_array()) {
    problems.push_back(path + ": expected an array of goals, got " + shown(goals));
    return result;
  }
  GoalReader reader(objects, problems);
  for (std::size_t i = 0; i < goals.size(); ++i) {
    if (auto goal = reader.read(goals[i], path + "[" + std::to_string(i) + "]")) result.push_back(*goal);
  }
  return result;
}

}  // namespace lang2manip
