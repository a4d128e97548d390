#include "lang2manip/symbolic/plan_json.hpp"

#include <cmath>
#include <sstream>

#include "lang2manip/symbolic/goal_statement.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

json nullableString(const std::string& description) {
  return {{"type", {"string", "null"}}, {"description", description}};
}

json nullableNumber(const std::string& description) {
  return {{"type", {"number", "null"}}, {"description", description}};
}

json nullableEnum(const std::vector<std::string>& names, const std::string& description) {
  json values = json::array();
  for (const std::string& name : names) values.push_back(name);
  values.push_back(nullptr);
  return {{"type", {"string", "null"}}, {"enum", values}, {"description", description}};
}

/// A strict-mode object: every property required, no others.
json strictObject(const json& properties, const std::string& description) {
  json required = json::array();
  for (const auto& [name, schema] : properties.items()) required.push_back(name);
  return {{"type", "object"},
          {"description", description},
          {"properties", properties},
          {"required", required},
          {"additionalProperties", false}};
}

json nullable(const json& schema) { return {{"anyOf", {schema, {{"type", "null"}}}}}; }

json vectorSchema(const std::string& description) {
  const json number = {{"type", "number"}};
  return nullable(strictObject({{"x", number}, {"y", number}, {"z", number}}, description));
}

json quaternionSchema() {
  const json number = {{"type", "number"}};
  return nullable(strictObject({{"w", number}, {"x", number}, {"y", number}, {"z", number}},
                               "Orientation as a unit quaternion, robot base frame"));
}

json paramsSchema() {
  return nullable(strictObject(
      {{"relation", nullableEnum(spatialRelationNames(),
                                 "place: where the object goes relative to target")},
       {"target", nullableString("place: the reference object of the relation")},
       {"distance", nullableNumber("place: offset from target in metres (left_of, right_of, "
                                   "in_front_of, behind, next_to); push: distance in metres")},
       {"position", vectorSchema("place/move: explicit position in metres, robot base frame")},
       {"orientation", quaternionSchema()},
       {"configuration", nullableString("move: a named robot configuration such as home")},
       {"direction", vectorSchema("push: unit direction, robot base frame (x front, y left)")},
       {"region", nullableEnum(surfaceRegionNames(),
                               "place on a support: the region of its top face the object goes to "
                               "(corners, edges, centre, halves, quadrants of the reachable part)")}},
      "Action parameters; null for pick"));
}

json refinementsSchema() {
  return nullable(strictObject(
      {{"grasp", nullableEnum(graspDirectionNames(), "How to grasp the object")},
       {"approach", vectorSchema("Unit approach direction of the gripper, robot base frame")}},
      "How to grasp and approach; null for the defaults"));
}

json actionSchema() {
  return strictObject(
      {{"action", {{"type", "string"}, {"enum", actionTypeNames()}, {"description", "Action type"}}},
       {"object", nullableString("The object acted on (null for move to a configuration)")},
       {"params", paramsSchema()},
       {"refinements", refinementsSchema()},
       {"planner", nullableString("Motion planner name, null for the default")}},
      "One symbolic action a(o, p, r, kappa)");
}

json vectorJson(const std::optional<Vector3>& v) {
  if (!v) return nullptr;
  return {{"x", v->x()}, {"y", v->y()}, {"z", v->z()}};
}

json quaternionJson(const std::optional<Quaternion>& q) {
  if (!q) return nullptr;
  return {{"w", q->w()}, {"x", q->x()}, {"y", q->y()}, {"z", q->z()}};
}

json stringOrNull(const std::string& text) { return text.empty() ? json(nullptr) : json(text); }

bool hasParams(const ActionParams& p) {
  return p.relation || !p.target.empty() || p.distance || p.position || p.orientation ||
         !p.configuration.empty() || p.direction || p.region;
}

json paramsJson(const ActionParams& p) {
  if (!hasParams(p)) return nullptr;
  return {{"relation", p.relation ? json(spatialRelationName(*p.relation)) : json(nullptr)},
          {"target", stringOrNull(p.target)},
          {"distance", p.distance ? json(*p.distance) : json(nullptr)},
          {"position", vectorJson(p.position)},
          {"orientation", quaternionJson(p.orientation)},
          {"configuration", stringOrNull(p.configuration)},
          {"direction", vectorJson(p.direction)},
          {"region", p.region ? json(surfaceRegionName(*p.region)) : json(nullptr)}};
}

json refinementsJson(const ActionRefinements& r) {
  if (r.grasp == GraspDirection::kAuto && !r.approach) return nullptr;
  return {{"grasp", graspDirectionName(r.grasp)}, {"approach", vectorJson(r.approach)}};
}

std::string vectorText(const Vector3& v) {
  std::ostringstream text;
  text << '(' << v.x() << ", " << v.y() << ", " << v.z() << ')';
  return text.str();
}

}  // namespace

nlohmann::json planJsonSchema() {
  return strictObject(
      {{"reasoning", nullableString("Optional short reasoning behind the plan")},
       {"actions", {{"type", "array"},
                    {"description", "The actions in execution order"},
                    {"items", actionSchema()}}},
       {"goals", goalStatementSchema()}},
      "A symbolic manipulation plan");
}

nlohmann::json toJson(const SymbolicAction& action) {
  return {{"action", actionTypeName(action.type)},
          {"object", stringOrNull(action.object)},
          {"params", paramsJson(action.params)},
          {"refinements", refinementsJson(action.refinements)},
          {"planner", stringOrNull(action.planner)}};
}

nlohmann::json toJson(const Plan& plan) {
  json actions = json::array();
  for (const SymbolicAction& action : plan.actions) actions.push_back(toJson(action));
  return {{"reasoning", stringOrNull(plan.reasoning)}, {"actions", actions}, {"goals", goalStatementJson(plan.goals)}};
}

std::string describeAction(const SymbolicAction& action) {
  std::ostringstream text;
  text << actionTypeName(action.type);
  if (!action.object.empty()) text << ' ' << action.object;
  const ActionParams& p = action.params;
  if (p.relation) {
    if (p.distance) text << ' ' << *p.distance << " m";
    text << ' ' << spatialRelationWords(*p.relation) << ' ' << p.target;
    if (p.region) text << " (" << surfaceRegionWords(*p.region) << ')';
  }
  if (!p.configuration.empty()) text << " to " << p.configuration;
  if (p.position) text << (action.type == ActionType::kPlace ? " at " : " to ") << vectorText(*p.position);
  if (p.orientation) {
    const Matrix3 rotation = p.orientation->normalized().toRotationMatrix();
    if (rotation(2, 2) > 0.9998) {
      text << " with yaw " << std::round(std::atan2(rotation(1, 0), rotation(0, 0)) * 180.0 / 3.14159265358979323846) << " deg";
    } else {
      text << " with orientation (w, x, y, z) = (" << p.orientation->w() << ", " << p.orientation->x() << ", " << p.orientation->y()
           << ", " << p.orientation->z() << ")";
    }
  }
  if (action.type == ActionType::kPush && p.direction) {
    if (p.distance) text << ' ' << *p.distance << " m";
    text << " along " << vectorText(*p.direction);
  }
  return text.str();
}

}  // namespace lang2manip
