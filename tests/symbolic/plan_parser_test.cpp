#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <set>

#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/plan_parser.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;
using ::testing::Contains;
using ::testing::HasSubstr;

PlanParseContext parserDeskContext() {
  PlanParseContext context;
  context.objects = {"desk", "marker", "eraser", "holder"};
  context.planners = {"RRTConnect", "RRTstar", "PRM"};
  return context;
}

json nullParams() {
  return {{"relation", nullptr}, {"target", nullptr},        {"distance", nullptr}, {"position", nullptr},
          {"orientation", nullptr}, {"configuration", nullptr}, {"direction", nullptr}};
}

json placeIn(const std::string& object, const std::string& target) {
  json params = nullParams();
  params["relation"] = "in";
  params["target"] = target;
  return {{"action", "place"}, {"object", object}, {"params", params}, {"refinements", nullptr}, {"planner", nullptr}};
}

json pickEntry(const std::string& object) {
  return {{"action", "pick"}, {"object", object}, {"params", nullptr}, {"refinements", nullptr}, {"planner", nullptr}};
}

json paperPlan() {
  return {{"reasoning", "one object at a time"},
          {"actions", {pickEntry("marker"), placeIn("marker", "holder"), pickEntry("eraser"), placeIn("eraser", "holder")}}};
}

/// The problems parsePlan reports for `document` (fails the test when it parses).
std::vector<std::string> problemsOf(const json& document, const PlanParseContext& context = parserDeskContext()) {
  try {
    parsePlan(document, context);
  } catch (const PlanParseError& error) {
    return error.problems();
  }
  ADD_FAILURE() << "parsed without problems: " << document.dump();
  return {};
}

std::vector<std::string> problemsOfText(const std::string& text) {
  try {
    parsePlanText(text, parserDeskContext());
  } catch (const PlanParseError& error) {
    return error.problems();
  }
  ADD_FAILURE() << "parsed without problems: " << text;
  return {};
}

TEST(PlanParserTest, ParsesThePaperPlan) {
  const Plan plan = parsePlan(paperPlan(), parserDeskContext());
  ASSERT_EQ(plan.actions.size(), 4U);
  EXPECT_EQ(plan.actions[0].type, ActionType::kPick);
  EXPECT_EQ(plan.actions[1].type, ActionType::kPlace);
  EXPECT_EQ(plan.actions[1].params.relation, SpatialRelation::kIn);
  EXPECT_EQ(plan.actions[3].params.target, "holder");
  EXPECT_EQ(plan.reasoning, "one object at a time");
}

TEST(PlanParserTest, PositionsFarOutsideAnySceneAndHugeQuaternionsAreRefused) {
  const json far = json::parse(R"({"actions": [{"action": "move", "params": {"position": [1e308, 0, 0.5]}}]})");
  EXPECT_THAT(problemsOf(far), ::testing::Contains(::testing::HasSubstr("actions[0].params.position: a coordinate beyond 100 m")));
  const json turned = json::parse(R"({"actions": [{"action": "move", "params": {"position": [0.4, 0, 0.5],
      "orientation": {"w": 1e300, "x": 0, "y": 0, "z": 0}}}]})");
  EXPECT_THAT(problemsOf(turned), ::testing::Contains(::testing::HasSubstr("not a unit quaternion")));
  EXPECT_THAT(problemsOfText(R"({"actions": [], "actions": [{"action": "pick", "object": "marker"}]})"),
              ::testing::Contains(::testing::HasSubstr("\"actions\" appears twice")));
}

TEST(PlanParserTest, UnknownTargetObjectIsReportedWithPathAndTheValidObjects) {
  json document = paperPlan();
  document["actions"][2] = placeIn("eraser", "cup");
  EXPECT_THAT(problemsOf(document),
              Contains(R"(actions[2].params.target: unknown object "cup" (objects: desk, marker, eraser, holder))"));
}

TEST(PlanParserTest, UnknownActionListsTheValidActions) {
  json document = paperPlan();
  document["actions"][1]["action"] = "grab";
  EXPECT_THAT(problemsOf(document),
              Contains(R"(actions[1].action: unknown action "grab" (valid actions: pick, place, move, push))"));
}

TEST(PlanParserTest, EveryProblemIsReportedNotOnlyTheFirst) {
  json document = paperPlan();
  document["actions"][0]["object"] = "cup";
  document["actions"][1]["action"] = 5;
  document["actions"][3]["planner"] = "FancyPlanner";
  const auto problems = problemsOf(document);
  EXPECT_EQ(problems.size(), 3U) << ::testing::PrintToString(problems);
  EXPECT_THAT(problems, Contains(HasSubstr("actions[0].object: unknown object \"cup\"")));
  EXPECT_THAT(problems, Contains("actions[1].action: expected a string, got number 5"));
  EXPECT_THAT(problems, Contains(R"(actions[3].planner: unknown planner "FancyPlanner" (planners: RRTConnect, RRTstar, PRM; or null for the default))"));
}

TEST(PlanParserTest, GoalStatementRoundTripsThroughTheDocument) {
  json document = paperPlan();
  document["goals"] = {{{"kind", "relation"}, {"object", "marker"}, {"relation", "in"}, {"target", "holder"}},
                       {{"kind", "relation"}, {"object", "eraser"}, {"relation", "left_of"}, {"target", "holder"}, {"distance", 0.05}},
                       {{"kind", "holding"}, {"object", "eraser"}, {"relation", nullptr}},
                       {{"kind", "displaced"}, {"object", "eraser"}, {"displacement", {{"x", 0.0}, {"y", 0.05}, {"z", 0.0}}}},
                       {{"kind", "at_configuration"}, {"configuration", "home"}}};
  const Plan plan = parsePlan(document, parserDeskContext());
  ASSERT_EQ(plan.goals.size(), 5U);
  EXPECT_EQ(describeGoal(plan.goals[0]), "marker in holder");
  EXPECT_EQ(describeGoal(plan.goals[1]), "eraser left of holder at 0.05 m");
  EXPECT_EQ(plan.goals[2].kind, GoalKind::kHolding);
  EXPECT_TRUE(plan.goals[3].displacement.isApprox(Vector3(0.0, 0.05, 0.0)));
  EXPECT_EQ(plan.goals[4].configuration, "home");
  const Plan again = parsePlan(toJson(plan), parserDeskContext());
  ASSERT_EQ(again.goals.size(), 5U);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(describeGoal(again.goals[i]), describeGoal(plan.goals[i]));
  EXPECT_TRUE(parsePlan(paperPlan(), parserDeskContext()).goals.empty());  // a plan without goals is still a plan
}

TEST(PlanParserTest, AHandoverGoalNamesItsObject) {
  json document = paperPlan();
  document["goals"] = {{{"kind", "handed_over"}, {"object", "marker"}}};
  const Plan plan = parsePlan(document, parserDeskContext());
  ASSERT_EQ(plan.goals.size(), 1U);
  EXPECT_EQ(describeGoal(plan.goals[0]), "marker handed over");
  EXPECT_EQ(toJson(plan)["goals"][0]["kind"], "handed_over");
  document["goals"] = {{{"kind", "handed_over"}}};
  EXPECT_THAT(problemsOf(document), Contains(HasSubstr("goals[0].object: missing; a handed_over goal needs it")));
}

TEST(PlanParserTest, PlaceTurnAndPointingGoalsRoundTrip) {
  json document = paperPlan();
  document["goals"] = {{{"kind", "at_position"}, {"object", "marker"}, {"position", {{"x", 0.4}, {"y", 0.1}, {"z", 0.0}}}, {"target", "eraser"}},
                       {{"kind", "turned"}, {"object", "eraser"}, {"angle", -1.5707963}},
                       {{"kind", "facing"}, {"object", "marker"}, {"target", "holder"}}};
  const Plan plan = parsePlan(document, parserDeskContext());
  ASSERT_EQ(plan.goals.size(), 3U);
  EXPECT_EQ(describeGoal(plan.goals[0]), "marker at (0.4, 0.1) where eraser stood");
  EXPECT_EQ(describeGoal(plan.goals[1]), "eraser turned by -90 deg");
  EXPECT_EQ(describeGoal(plan.goals[2]), "marker pointing at holder");
  const Plan again = parsePlan(toJson(plan), parserDeskContext());
  ASSERT_EQ(again.goals.size(), 3U);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(describeGoal(again.goals[i]), describeGoal(plan.goals[i]));
  document["goals"] = {{{"kind", "at_position"}, {"object", "marker"}},
                       {{"kind", "turned"}, {"object", "eraser"}, {"angle", 7.0}},
                       {{"kind", "turned"}, {"object", "eraser"}, {"angle", 0}},
                       {{"kind", "facing"}, {"object", "marker"}},
                       {{"kind", "facing"}, {"object", "marker"}, {"target", "holder"}, {"angle", 1.0}}};
  const auto problems = problemsOf(document);
  EXPECT_THAT(problems, Contains(HasSubstr("goals[0].position: missing; an at_position goal needs it")));
  EXPECT_THAT(problems, Contains(HasSubstr("goals[1].angle: expected a non-zero turn in radians within [-2 pi, 2 pi]")));
  EXPECT_THAT(problems, Contains(HasSubstr("goals[2].angle: expected a non-zero turn")));
  EXPECT_THAT(problems, Contains(HasSubstr("goals[3]: a facing goal needs a target to point at or an angle")));
  EXPECT_THAT(problems, Contains(HasSubstr("goals[4]: a facing goal needs a target to point at or an angle (the heading of its long side), not both")));
  document["goals"] = {{{"kind", "facing"}, {"object", "marker"}, {"angle", 0.0}}};
  const Plan heading = parsePlan(document, parserDeskContext());
  ASSERT_EQ(heading.goals.size(), 1U);
  EXPECT_EQ(describeGoal(heading.goals[0]), "marker pointing along yaw 0 deg");
  EXPECT_EQ(toJson(heading)["goals"][0]["angle"], 0.0);
}

TEST(PlanParserTest, PlannerNamesAreCheckedOnlyWhenTheContextListsThem) {
  json document = paperPlan();
  document["actions"][0]["planner"] = "AnyPlanner";
  PlanParseContext context = parserDeskContext();
  context.planners.clear();
  EXPECT_EQ(parsePlan(document, context).actions[0].planner, "AnyPlanner");
  EXPECT_FALSE(problemsOf(document).empty());
}

struct BadCase {
  std::string name;
  std::function<void(json&)> change;
  std::string expected;
};

class PlanParserBadInputTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(PlanParserBadInputTest, ReportsTheProblemWithItsPath) {
  json document = paperPlan();
  GetParam().change(document);
  EXPECT_THAT(problemsOf(document), Contains(HasSubstr(GetParam().expected)))
      << ::testing::PrintToString(problemsOf(document));
}

json pushAction(const json& direction, const json& distance) {
  json params = nullParams();
  params["direction"] = direction;
  params["distance"] = distance;
  return {{"action", "push"}, {"object", "eraser"}, {"params", params}, {"refinements", nullptr}, {"planner", nullptr}};
}

INSTANTIATE_TEST_SUITE_P(
    Cases, PlanParserBadInputTest,
    ::testing::Values(
        BadCase{"MissingActions", [](json& d) { d.erase("actions"); }, "actions: missing"},
        BadCase{"ActionsNotArray", [](json& d) { d["actions"] = "pick marker"; }, "actions: expected an array of actions, got string"},
        BadCase{"EmptyActions", [](json& d) { d["actions"] = json::array(); }, "actions: empty; the plan needs at least one action"},
        BadCase{"ActionNotObject", [](json& d) { d["actions"][1] = 3; }, "actions[1]: expected an action object, got number 3"},
        BadCase{"MissingActionName", [](json& d) { d["actions"][0].erase("action"); }, "actions[0].action: missing (one of: pick, place, move, push)"},
        BadCase{"UnknownActionField", [](json& d) { d["actions"][0]["speed"] = 2; }, "actions[0].speed: unknown field (valid fields: action, object, params, refinements, planner)"},
        BadCase{"UnknownTopField", [](json& d) { d["notes"] = "x"; }, "notes: unknown field (valid fields: actions, reasoning, goals)"},
        BadCase{"GoalsNotArray", [](json& d) { d["goals"] = "marker in holder"; }, "goals: expected an array of goals, got string"},
        BadCase{"GoalNotObject", [](json& d) { d["goals"] = {1}; }, "goals[0]: expected a goal object, got number 1"},
        BadCase{"GoalUnknownKind", [](json& d) { d["goals"] = {{{"kind", "tidy"}}}; }, "goals[0].kind: unknown kind string \"tidy\" (kinds: relation, holding, displaced, at_configuration, handed_over, at_position, turned, facing, arranged)"},
        BadCase{"GoalMissingKind", [](json& d) { d["goals"] = {{{"object", "marker"}}}; }, "goals[0].kind: missing"},
        BadCase{"GoalUnknownObject", [](json& d) { d["goals"] = {{{"kind", "holding"}, {"object", "cup"}}}; }, "goals[0].object: unknown object \"cup\" (objects: "},
        BadCase{"GoalRelationWithoutTarget", [](json& d) { d["goals"] = {{{"kind", "relation"}, {"object", "marker"}, {"relation", "in"}}}; }, "goals[0].target: missing; a relation goal needs it"},
        BadCase{"GoalUnknownRelation", [](json& d) { d["goals"] = {{{"kind", "relation"}, {"object", "marker"}, {"relation", "under"}, {"target", "holder"}}}; }, "goals[0].relation: unknown relation string \"under\""},
        BadCase{"GoalFieldOfAnotherKind", [](json& d) { d["goals"] = {{{"kind", "holding"}, {"object", "marker"}, {"target", "holder"}}}; }, "goals[0].target: must be null for a holding goal"},
        BadCase{"GoalZeroDisplacement", [](json& d) { d["goals"] = {{{"kind", "displaced"}, {"object", "eraser"}, {"displacement", {0, 0, 0}}}}; }, "goals[0].displacement: a displacement of zero moves nothing"},
        BadCase{"GoalBadDisplacement", [](json& d) { d["goals"] = {{{"kind", "displaced"}, {"object", "eraser"}, {"displacement", "5 cm left"}}}; }, "goals[0].displacement: expected {x, y, z} in metres, got string"},
        BadCase{"GoalNegativeDistance", [](json& d) { d["goals"] = {{{"kind", "relation"}, {"object", "marker"}, {"relation", "left_of"}, {"target", "holder"}, {"distance", -1}}}; }, "goals[0].distance: expected a positive number of metres, got number -1"},
        BadCase{"GoalUnknownField", [](json& d) { d["goals"] = {{{"kind", "holding"}, {"object", "marker"}, {"when", "now"}}}; }, "goals[0].when: unknown field"},
        BadCase{"ObjectNotString", [](json& d) { d["actions"][0]["object"] = json::array({"marker"}); }, "actions[0].object: expected a string, got array"},
        BadCase{"MissingObjectForPick", [](json& d) { d["actions"][0].erase("object"); }, "actions[0].object: missing; pick needs an object"},
        BadCase{"UnknownRelation", [](json& d) { d["actions"][1]["params"]["relation"] = "under"; }, "actions[1].params.relation: unknown relation \"under\" (valid relations: in, on, left_of, right_of, in_front_of, behind, next_to)"},
        BadCase{"PlaceWithoutTarget", [](json& d) { d["actions"][1]["params"]["target"] = nullptr; }, "actions[1].params.target: missing; place needs a target object"},
        BadCase{"PlaceWithoutParams", [](json& d) { d["actions"][1]["params"] = nullptr; }, "actions[1].params: place needs a relation and a target object, or a position"},
        BadCase{"ParamsNotObject", [](json& d) { d["actions"][1]["params"] = "in holder"; }, "actions[1].params: expected an object or null, got string"},
        BadCase{"PlaceRelativeToItself", [](json& d) { d["actions"][1]["params"]["target"] = "marker"; }, "actions[1].params.target: the object cannot be placed relative to itself"},
        BadCase{"PlaceRelationAndPosition", [](json& d) { d["actions"][1]["params"]["position"] = {{"x", 0.1}, {"y", 0.0}, {"z", 0.8}}; }, "actions[1].params.position: give either a relation with a target or a position, not both"},
        BadCase{"DistanceWithIn", [](json& d) { d["actions"][1]["params"]["distance"] = 0.05; }, "actions[1].params.distance: not used with relation \"in\""},
        BadCase{"NegativeDistance", [](json& d) { d["actions"][1]["params"]["relation"] = "left_of"; d["actions"][1]["params"]["distance"] = -0.1; }, "actions[1].params.distance: negative distance -0.1"},
        BadCase{"DistanceNotNumber", [](json& d) { d["actions"][1]["params"]["relation"] = "left_of"; d["actions"][1]["params"]["distance"] = "5cm"; }, "actions[1].params.distance: expected a number, got string"},
        BadCase{"PickWithParams", [](json& d) { d["actions"][0]["params"] = {{"target", "holder"}}; }, "actions[0].params.target: not used by pick (it takes no parameters)"},
        BadCase{"UnknownParamField", [](json& d) { d["actions"][1]["params"]["height"] = 0.2; }, "actions[1].params.height: unknown field"},
        BadCase{"PositionMissingComponent", [](json& d) { d["actions"][1]["params"] = {{"position", {{"x", 0.1}, {"y", 0.2}}}}; }, "actions[1].params.position.z: missing"},
        BadCase{"PositionWrongArray", [](json& d) { d["actions"][1]["params"] = {{"position", {0.1, 0.2}}}; }, "actions[1].params.position: expected an object {x, y, z}, got array"},
        BadCase{"PositionComponentNotNumber", [](json& d) { d["actions"][1]["params"] = {{"position", {{"x", "a"}, {"y", 0.2}, {"z", 0.8}}}}; }, "actions[1].params.position.x: expected a number, got string"},
        BadCase{"ZeroQuaternion", [](json& d) { d["actions"][1]["params"] = {{"position", {0.1, 0.2, 0.8}}, {"orientation", {0, 0, 0, 0}}}; }, "actions[1].params.orientation: zero quaternion"},
        BadCase{"PushZeroDirection", [](json& d) { d["actions"][2] = pushAction({{"x", 0}, {"y", 0}, {"z", 0}}, 0.05); }, "actions[2].params.direction: zero vector; give a unit direction"},
        BadCase{"PushNonUnitDirection", [](json& d) { d["actions"][2] = pushAction({{"x", 2}, {"y", 0}, {"z", 0}}, 0.05); }, "actions[2].params.direction: not a unit vector (length 2"},
        BadCase{"PushZeroDistance", [](json& d) { d["actions"][2] = pushAction({{"x", 1}, {"y", 0}, {"z", 0}}, 0.0); }, "actions[2].params.distance: zero distance"},
        BadCase{"PushWithoutDistance", [](json& d) { d["actions"][2] = pushAction({{"x", 1}, {"y", 0}, {"z", 0}}, nullptr); }, "actions[2].params.distance: missing; push needs a distance in metres"},
        BadCase{"PushWithoutDirection", [](json& d) { d["actions"][2] = pushAction(nullptr, 0.05); }, "actions[2].params.direction: missing; push needs a unit direction"},
        BadCase{"MoveWithoutGoal", [](json& d) { d["actions"][3] = {{"action", "move"}}; }, "actions[3].params: move needs either a configuration (such as \"home\") or a position"},
        BadCase{"MoveWithRelation", [](json& d) { d["actions"][3] = {{"action", "move"}, {"params", {{"configuration", "home"}, {"relation", "in"}}}}; }, "actions[3].params.relation: not used by move (it takes: position, orientation, configuration)"},
        BadCase{"UnknownGrasp", [](json& d) { d["actions"][0]["refinements"] = {{"grasp", "bottom"}}; }, "actions[0].refinements.grasp: unknown grasp \"bottom\" (valid grasps: auto, top, side, front)"},
        BadCase{"RefinementsNotObject", [](json& d) { d["actions"][0]["refinements"] = "top"; }, "actions[0].refinements: expected an object or null, got string"},
        BadCase{"ZeroApproach", [](json& d) { d["actions"][0]["refinements"] = {{"approach", {0, 0, 0}}}; }, "actions[0].refinements.approach: zero vector"},
        BadCase{"PlannerNotString", [](json& d) { d["actions"][0]["planner"] = 3; }, "actions[0].planner: expected a string, got number 3"},
        BadCase{"ReasoningNotString", [](json& d) { d["reasoning"] = json::array(); }, "reasoning: expected a string, got array"},
        BadCase{"DocumentIsString", [](json& d) { d = "pick marker"; }, "(document): expected a plan object {\"actions\": [...]}, got string"}),
    [](const ::testing::TestParamInfo<BadCase>& caseInfo) { return caseInfo.param.name; });

TEST(PlanParserTest, AcceptsAbsentFieldsBareArraysLooseNamesAndArrayVectors) {
  const json document = json::parse(R"([
    {"action": "Pick", "object": "Marker", "refinements": {"grasp": "TOP"}},
    {"action": "place", "object": "marker", "params": {"relation": "in front of", "target": "holder", "distance": 0.1}},
    {"action": "push", "object": "eraser", "params": {"direction": [0, 1, 0], "distance": 0.05}},
    {"action": "move", "params": {"configuration": "home"}}])");
  const Plan plan = parsePlan(document, parserDeskContext());
  ASSERT_EQ(plan.actions.size(), 4U);
  EXPECT_EQ(plan.actions[0].object, "marker");
  EXPECT_EQ(plan.actions[0].refinements.grasp, GraspDirection::kTop);
  EXPECT_EQ(plan.actions[1].params.relation, SpatialRelation::kInFrontOf);
  EXPECT_DOUBLE_EQ(*plan.actions[1].params.distance, 0.1);
  EXPECT_TRUE(plan.actions[2].params.direction->isApprox(Vector3::UnitY()));
  EXPECT_EQ(plan.actions[3].params.configuration, "home");
  EXPECT_TRUE(plan.actions[3].object.empty());
}

TEST(PlanParserTest, TextAnswersWithFencesOrLeadingProseAreAccepted) {
  const std::string body = paperPlan().dump();
  EXPECT_EQ(parsePlanText("```json\n" + body + "\n```", parserDeskContext()).actions.size(), 4U);
  EXPECT_EQ(parsePlanText("Here is the plan:\n" + body + "\nHope this helps!", parserDeskContext()).actions.size(), 4U);
  EXPECT_EQ(parsePlanText("  " + body + "  trailing words", parserDeskContext()).actions.size(), 4U);
}

TEST(PlanParserTest, GarbageTextGetsAClearError) {
  EXPECT_THAT(problemsOfText(""), Contains("(answer): empty answer; expected a JSON plan"));
  EXPECT_THAT(problemsOfText("I cannot help with that."), Contains(HasSubstr("(answer): no JSON object found")));
  const std::string truncated = paperPlan().dump().substr(0, 60);
  EXPECT_THAT(problemsOfText(truncated), Contains(HasSubstr("(answer): not valid JSON: parse error")));
  EXPECT_THAT(problemsOfText("{\"actions\": [pick marker]}"), Contains(HasSubstr("not valid JSON")));
}

TEST(PlanParserTest, ErrorMessageListsAllProblems) {
  json document = paperPlan();
  document["actions"][0]["object"] = "cup";
  document["actions"][1]["object"] = "mug";
  try {
    parsePlan(document, parserDeskContext());
    FAIL() << "expected PlanParseError";
  } catch (const PlanParseError& error) {
    EXPECT_THAT(error.what(), HasSubstr("the plan has 2 problems:"));
    EXPECT_THAT(error.what(), HasSubstr("\"cup\""));
    EXPECT_THAT(error.what(), HasSubstr("\"mug\""));
  }
}

TEST(PlanJsonTest, RoundTripThroughJsonGivesTheSamePlan) {
  Plan plan;
  plan.reasoning = "test";
  SymbolicAction pickMarker{ActionType::kPick, "marker", {}, {GraspDirection::kSide, Vector3(0, 0, -1)}, "RRTConnect"};
  SymbolicAction placeLeft{ActionType::kPlace, "marker", {}, {}, ""};
  placeLeft.params.relation = SpatialRelation::kLeftOf;
  placeLeft.params.target = "holder";
  placeLeft.params.distance = 0.07;
  SymbolicAction placeAt{ActionType::kPlace, "eraser", {}, {}, "PRM"};
  placeAt.params.position = Vector3(0.4, -0.1, 0.02);
  placeAt.params.orientation = Quaternion(0.7071067811865476, 0, 0, 0.7071067811865476);
  SymbolicAction push{ActionType::kPush, "eraser", {}, {}, ""};
  push.params.direction = Vector3(0, -1, 0);
  push.params.distance = 0.05;
  SymbolicAction home{ActionType::kMove, "", {}, {}, ""};
  home.params.configuration = "home";
  plan.actions = {pickMarker, placeLeft, pickMarker, placeAt, push, home};
  plan.actions[2].object = "eraser";

  const json document = toJson(plan);
  const Plan again = parsePlan(json::parse(document.dump()), parserDeskContext());
  EXPECT_EQ(toJson(again), document);
  ASSERT_EQ(again.actions.size(), plan.actions.size());
  EXPECT_EQ(again.actions[0].refinements.grasp, GraspDirection::kSide);
  EXPECT_EQ(again.actions[3].planner, "PRM");
  EXPECT_TRUE(again.actions[3].params.orientation->isApprox(*placeAt.params.orientation));
  EXPECT_EQ(describeAction(again.actions[1]), "place marker 0.07 m left of holder");
  EXPECT_EQ(describeAction(again.actions[5]), "move to home");
}

/// Walks every subschema: each object schema lists all properties as required and forbids
/// others; no keyword outside what OpenAI's strict mode supports.
void checkStrict(const json& schema, const std::string& path, std::vector<std::string>& problems) {
  static const std::set<std::string> kAllowed{"type", "properties", "required", "additionalProperties",
                                              "items", "enum", "anyOf", "description"};
  for (const auto& [keyword, value] : schema.items()) {
    if (!kAllowed.count(keyword)) problems.push_back(path + ": keyword " + keyword);
  }
  const json type = schema.value("type", json());
  const bool isObject = type == "object" || (type.is_array() && std::find(type.begin(), type.end(), "object") != type.end());
  if (isObject) {
    if (schema.value("additionalProperties", json(true)) != false) problems.push_back(path + ": additionalProperties");
    std::set<std::string> required;
    for (const json& name : schema.value("required", json::array())) required.insert(name.get<std::string>());
    for (const auto& [name, sub] : schema.at("properties").items()) {
      if (!required.count(name)) problems.push_back(path + "." + name + ": not required");
      checkStrict(sub, path + "." + name, problems);
    }
    if (required.size() != schema.at("properties").size()) problems.push_back(path + ": required lists unknown names");
  }
  if (schema.contains("items")) checkStrict(schema["items"], path + "[]", problems);
  if (schema.contains("anyOf")) {
    for (std::size_t i = 0; i < schema["anyOf"].size(); ++i) checkStrict(schema["anyOf"][i], path + "|" + std::to_string(i), problems);
  }
  if (schema.contains("enum") && type.is_array() && std::find(type.begin(), type.end(), "null") != type.end()) {
    if (std::find(schema["enum"].begin(), schema["enum"].end(), nullptr) == schema["enum"].end()) {
      problems.push_back(path + ": nullable enum without null");
    }
  }
}

TEST(PlanJsonTest, SchemaIsValidForStrictMode) {
  const json schema = planJsonSchema();
  EXPECT_EQ(schema["type"], "object");
  std::vector<std::string> problems;
  checkStrict(schema, "$", problems);
  EXPECT_TRUE(problems.empty()) << ::testing::PrintToString(problems);
  EXPECT_EQ(schema["properties"]["actions"]["items"]["properties"]["action"]["enum"],
            json({"pick", "place", "move", "push"}));
}

TEST(PlanJsonTest, StrictCheckerCatchesAViolation) {
  json schema = planJsonSchema();
  schema["properties"]["actions"]["items"]["required"].erase(0);
  schema["properties"]["actions"]["minItems"] = 1;
  std::vector<std::string> problems;
  checkStrict(schema, "$", problems);
  EXPECT_THAT(problems, Contains("$.actions[].action: not required"));
  EXPECT_THAT(problems, Contains("$.actions: keyword minItems"));
}

TEST(PlanJsonTest, EveryNullFieldDocumentOfTheSchemaParses) {
  // What a strict-mode model answers: every field present, null where unused.
  const json answer = json::parse(R"({"reasoning": null, "actions": [
    {"action": "move", "object": null, "params": {"relation": null, "target": null, "distance": null,
     "position": null, "orientation": null, "configuration": "home", "direction": null},
     "refinements": {"grasp": null, "approach": null}, "planner": null}]})");
  const Plan plan = parsePlan(answer, parserDeskContext());
  ASSERT_EQ(plan.actions.size(), 1U);
  EXPECT_EQ(plan.actions[0].refinements.grasp, GraspDirection::kAuto);
}

}  // namespace
}  // namespace lang2manip
