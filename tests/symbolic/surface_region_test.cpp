// Regions of a support's top (issue 23): names, geometry, the reachable part, the goal check, the
// plan grammar and the validator.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/symbolic/arm_reach.hpp"
#include "lang2manip/symbolic/goal_statement.hpp"
#include "lang2manip/symbolic/observation.hpp"
#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/plan_parser.hpp"
#include "lang2manip/symbolic/plan_validation.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"
#include "lang2manip/symbolic/surface_region.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;
using nlohmann::json;
using Kind = SurfaceRegion::Kind;

Scene desk(const std::string& robot = "panda") {
  return readKauthamProblem(resolveProblem(robot + "_desk")).scene;
}

/// Moves `object` so that the centre of its bounds is at (x, y) of the base frame.
void moveTo(Scene& scene, const std::string& object, double x, double y) {
  const Pose base = robotBaseFrame(scene, "");
  SceneObject& o = scene.object(object);
  const Vector3 centre = base.inverse() * o.worldBounds().center();
  o.pose.translation() += base.linear() * Vector3(x - centre.x(), y - centre.y(), 0.0);
}

TEST(SurfaceRegion, EveryNameReadsBackAndUnknownNamesDoNot) {
  const std::vector<std::string> names = surfaceRegionNames();
  EXPECT_EQ(names.size(), 17u);  // 4 corners, 4 edges, the centre, 4 halves, 4 quadrants
  for (const std::string& name : names) {
    const auto region = surfaceRegionFromName(name);
    ASSERT_TRUE(region) << name;
    EXPECT_EQ(surfaceRegionName(*region), name);
  }
  for (const char* bad : {"", "corner", "far_corner", "left_far_corner", "middle", "far_left_edge", "centre_half"}) {
    EXPECT_FALSE(surfaceRegionFromName(bad)) << bad;
  }
  EXPECT_EQ(surfaceRegionName({Kind::kCorner, 1, 1}), "far_left_corner");
  EXPECT_EQ(surfaceRegionName({Kind::kEdge, -1, 0}), "near_edge");
  EXPECT_EQ(surfaceRegionName({Kind::kQuadrant, -1, -1}), "near_right_quadrant");
}

TEST(SurfaceRegion, ThirdsMakeCornersEdgesAndTheCentreHalvesMakeHalvesAndQuadrants) {
  const AlignedBox3 area(Vector3(0.3, -0.3, 0.0), Vector3(0.9, 0.3, 0.0));
  const AlignedBox3 corner = regionBox(area, {Kind::kCorner, 1, 1});
  EXPECT_TRUE(corner.min().isApprox(Vector3(0.7, 0.1, 0.0)));
  EXPECT_TRUE(corner.max().isApprox(Vector3(0.9, 0.3, 0.0)));
  const AlignedBox3 edge = regionBox(area, {Kind::kEdge, -1, 0});
  EXPECT_NEAR(edge.min().x(), 0.3, 1e-12);
  EXPECT_NEAR(edge.max().x(), 0.5, 1e-12);
  EXPECT_NEAR(edge.min().y(), -0.1, 1e-12);
  EXPECT_NEAR(edge.max().y(), 0.1, 1e-12);
  const AlignedBox3 half = regionBox(area, {Kind::kHalf, 0, -1});
  EXPECT_NEAR(half.max().y(), 0.0, 1e-12);
  EXPECT_NEAR(half.sizes().x(), 0.6, 1e-12);
  const AlignedBox3 quadrant = regionBox(area, {Kind::kQuadrant, 1, -1});
  EXPECT_TRUE(quadrant.min().isApprox(Vector3(0.6, -0.3, 0.0)));
  EXPECT_EQ(surfaceRegionName(cellOfPoint(area, Vector3(0.85, -0.25, 0.0))), "far_right_corner");
  EXPECT_EQ(surfaceRegionName(cellOfPoint(area, Vector3(0.6, 0.0, 0.0))), "centre");
  EXPECT_EQ(surfaceRegionName(cellOfPoint(area, Vector3(0.6, 0.29, 0.0))), "left_edge");
}

TEST(SurfaceRegion, AFootprintMustFitInsideTheTopWithItsCentreInTheRegion) {
  const AlignedBox3 area(Vector3(0.3, -0.3, 0.0), Vector3(0.9, 0.3, 0.0));
  const auto centres = regionCentres(area, {Kind::kCorner, 1, 1}, Vector3(0.04, 0.04, 0.04));
  ASSERT_TRUE(centres);
  EXPECT_NEAR(centres->max().x(), 0.9 - 0.02 - kRegionEdgeMargin, 1e-12);
  EXPECT_NEAR(centres->min().y(), 0.1, 1e-12);
  EXPECT_FALSE(regionCentres(area, {Kind::kCorner, 1, 1}, Vector3(0.7, 0.04, 0.04)));
  // A long object may overhang its region as long as its centre is in it.
  EXPECT_TRUE(regionCentres(area, {Kind::kCentre, 0, 0}, Vector3(0.5, 0.04, 0.04)));
}

TEST(SurfaceRegion, TheReachablePartOfTheDeskIsInFrontOfEveryBuiltInRobotAndInsideTheTop) {
  for (const char* robot : {"panda", "ur5", "iiwa14", "tx90", "yumi"}) {
    SCOPED_TRACE(robot);
    const Scene scene = desk(robot);
    std::string why;
    const auto area = supportArea(scene, "desk", "", &why);
    ASSERT_TRUE(area) << why;
    EXPECT_TRUE(area->top.contains(area->reachable));
    EXPECT_TRUE(area->clipped);  // the 1.2 m desk reaches behind every robot
    EXPECT_GE(area->reachable.min().x(), 0.0);
    EXPECT_GT(area->reachable.sizes().x(), 0.2);
    EXPECT_GT(area->reachable.sizes().y(), 0.35);  // YuMi's arms keep clear of its torso
    // The same wherever the arm is.
    Scene moved = scene;
    SceneRobot& arm = moved.robot(moved.robots().front().name);
    moved.setConfiguration(arm.name, arm.model->lowerLimits());
    EXPECT_TRUE(supportArea(moved, "desk", "")->reachable.isApprox(area->reachable));
  }
}

TEST(SurfaceRegion, TheReachablePartIsMeasuredFromTheArmsJointsAndLimits) {
  // The iiwa's elbow folds at most 120 degrees: with links of 0.42 and 0.40 m its wrist stays
  // 0.41 m from its shoulder, and its shoulder stands 0.36 m above a desk it is mounted on, so
  // with the hand pointing down it reaches nothing nearer than about 0.3 m; the Panda does.
  const auto iiwa = supportArea(desk("iiwa14"), "desk", "");
  const auto panda = supportArea(desk("panda"), "desk", "");
  ASSERT_TRUE(iiwa && panda);
  EXPECT_GT(iiwa->reachable.min().x(), 0.28);
  EXPECT_LT(panda->reachable.min().x(), iiwa->reachable.min().x());
  // Along the measured rays, IK agrees: points inside reach, points beyond do not.
  const Scene scene = desk("iiwa14");
  const std::vector<ArmReach> arms = measuredArmReaches(scene.robots().front(), robotBaseFrame(scene, ""), iiwa->top.max().z());
  ASSERT_EQ(arms.size(), 1u);
  EXPECT_TRUE(arms.front().reaches(Vector3(0.55, 0.0, 0.0)));
  EXPECT_FALSE(arms.front().reaches(Vector3(0.2, 0.0, 0.0)));
  EXPECT_FALSE(arms.front().reaches(Vector3(1.2, 0.0, 0.0)));
}

TEST(SurfaceRegion, EachArmOfATwoArmedRobotHasItsOwnReachableRegions) {
  const Scene scene = desk("yumi");
  const auto right = supportArea(scene, "desk", "", nullptr, "right_arm");
  const auto left = supportArea(scene, "desk", "", nullptr, "left_arm");
  const auto both = supportArea(scene, "desk", "");
  ASSERT_TRUE(right && left && both);
  EXPECT_LT(right->reachable.center().y(), left->reachable.center().y());
  EXPECT_GT(both->reachable.sizes().y(), right->reachable.sizes().y());
  // The hand does not come down on the robot's own body standing on the desk.
  EXPECT_GT(both->reachable.min().x(), 0.1);
  // The goal check measures regions of the arm that acted.
  EXPECT_FALSE(regionBox(right->reachable, {Kind::kCorner, 1, 1}).isApprox(regionBox(left->reachable, {Kind::kCorner, 1, 1})));
  EXPECT_THROW(
      {
        try {
          (void)supportArea(scene, "desk", "", nullptr, "third_arm");
        } catch (const InputError& error) {
          EXPECT_THAT(error.what(), HasSubstr("robot yumi has no arm \"third_arm\"; its arms: right_arm, left_arm"));
          throw;
        }
      },
      InputError);
}

TEST(SurfaceRegion, ASceneWithoutRobotsUsesTheWholeTopAndATopOutOfReachHasNoRegions) {
  Scene scene = desk();
  Scene bare;
  bare.addObject(scene.object("desk"));
  const auto area = supportArea(bare, "desk", "");
  ASSERT_TRUE(area);
  EXPECT_FALSE(area->clipped);
  EXPECT_TRUE(area->reachable.isApprox(area->top));
  scene.object("desk").pose.translation().x() += 5.0;
  std::string why;
  EXPECT_FALSE(supportArea(scene, "desk", "", &why));
  EXPECT_THAT(why, HasSubstr("no part of the top of desk is within reach of panda"));
  EXPECT_FALSE(supportArea(scene, "marker", "", &why));
  EXPECT_THAT(why, HasSubstr("marker has no flat top"));
}

TEST(SurfaceRegion, TheGoalCheckMeasuresTheObjectsCentreInTheRegion) {
  Scene scene = desk();
  const AlignedBox3 reachable = supportArea(scene, "desk", "")->reachable;
  const AlignedBox3 corner = regionBox(reachable, {Kind::kCorner, 1, 1});
  moveTo(scene, "eraser", corner.center().x(), corner.center().y());
  Goal goal;
  goal.object = "eraser";
  goal.relation = SpatialRelation::kOn;
  goal.target = "desk";
  goal.region = SurfaceRegion{Kind::kCorner, 1, 1};
  GoalCheck check = checkGoalInScene(scene, goal);
  EXPECT_TRUE(check.holds) << check.explanation;
  goal.region = SurfaceRegion{Kind::kCorner, -1, -1};
  check = checkGoalInScene(scene, goal);
  EXPECT_FALSE(check.holds);
  EXPECT_THAT(check.explanation, HasSubstr("from the near_right_corner of desk"));
  // Just outside the region, within half the distance tolerance: still there.
  goal.region = SurfaceRegion{Kind::kCorner, 1, 1};
  moveTo(scene, "eraser", corner.min().x() - 0.005, corner.center().y());
  EXPECT_TRUE(checkGoalInScene(scene, goal).holds);
  moveTo(scene, "eraser", corner.min().x() - 0.03, corner.center().y());
  EXPECT_FALSE(checkGoalInScene(scene, goal).holds);
}

TEST(SurfaceRegion, TheObservationGivesTopsTheirReachablePartAndObjectsTheirCell) {
  const json observation = observeEnvironment(desk());
  const std::string text = observationText(observation);
  EXPECT_THAT(text, HasSubstr("flat top at z"));
  EXPECT_THAT(text, HasSubstr("of which the arm reaches x"));
  EXPECT_THAT(text, HasSubstr("regions of a support's top"));
  for (const json& object : observation["objects"]) {
    if (object["on"] == "desk") {
      EXPECT_TRUE(surfaceRegionFromName(object["region"].get<std::string>()) || object["region"] == "out_of_reach");
    }
  }
}

PlanParseContext deskContext() {
  PlanParseContext context;
  context.objects = {"desk", "marker", "eraser", "holder"};
  return context;
}

json placeWithRegion(const std::string& relation, const json& region) {
  json params = {{"relation", relation}, {"target", relation == "in" ? "holder" : "desk"}, {"region", region}};
  return {{"actions", {{{"action", "pick"}, {"object", "eraser"}},
                       {{"action", "place"}, {"object", "eraser"}, {"params", params}}}}};
}

std::string parseProblems(const json& document) {
  try {
    parsePlan(document, deskContext());
  } catch (const PlanParseError& error) {
    return error.what();
  }
  return "";
}

TEST(SurfaceRegion, PlansAndGoalStatementsCarryRegionsOfOnOnly) {
  const Plan plan = parsePlan(placeWithRegion("on", "far_left_corner"), deskContext());
  ASSERT_TRUE(plan.actions[1].params.region);
  EXPECT_EQ(surfaceRegionName(*plan.actions[1].params.region), "far_left_corner");
  EXPECT_EQ(describeAction(plan.actions[1]), "place eraser on desk (far left corner)");
  EXPECT_EQ(toJson(plan)["actions"][1]["params"]["region"], "far_left_corner");
  EXPECT_THAT(parseProblems(placeWithRegion("in", "centre")), HasSubstr("only used with relation \"on\""));
  EXPECT_THAT(parseProblems(placeWithRegion("on", "top_corner")), HasSubstr("unknown region \"top_corner\" (valid regions: far_left_corner"));
  EXPECT_THAT(parseProblems(placeWithRegion("on", 3)), HasSubstr("actions[1].params.region"));

  std::vector<std::string> problems;
  const json goals = {{{"kind", "relation"}, {"object", "eraser"}, {"relation", "on"}, {"target", "desk"}, {"region", "near_edge"}}};
  const std::vector<Goal> read = readGoalStatement(goals, "goals", deskContext().objects, problems);
  ASSERT_TRUE(problems.empty()) << problems.front();
  EXPECT_EQ(describeGoal(read.front()), "eraser on desk (near edge)");
  EXPECT_EQ(goalStatementJson(read)[0]["region"], "near_edge");
  const json wrong = {{{"kind", "relation"}, {"object", "eraser"}, {"relation", "in"}, {"target", "holder"}, {"region", "centre"}},
                      {{"kind", "holding"}, {"object", "eraser"}, {"region", "centre"}},
                      {{"kind", "relation"}, {"object", "eraser"}, {"relation", "on"}, {"target", "desk"}, {"region", "middle"}}};
  readGoalStatement(wrong, "goals", deskContext().objects, problems);
  ASSERT_EQ(problems.size(), 3u);
  EXPECT_THAT(problems[0], HasSubstr("goals[0].region: only used with relation \"on\""));
  EXPECT_THAT(problems[1], HasSubstr("goals[1].region: must be null for a holding goal"));
  EXPECT_THAT(problems[2], HasSubstr("goals[2].region: unknown region"));
}

TEST(SurfaceRegion, TheValidatorAcceptsWhatFitsInTheRegionAndSaysWhyOtherwise) {
  Scene scene = desk();
  const SymbolicState state = observeSymbolicState(scene);
  ASSERT_TRUE(state.reachableTops.count("desk"));
  Plan plan;
  plan.actions.push_back({ActionType::kPick, "marker", {}, {}, ""});
  SymbolicAction place{ActionType::kPlace, "marker", {}, {}, ""};
  place.params.relation = SpatialRelation::kOn;
  place.params.target = "desk";
  place.params.region = SurfaceRegion{Kind::kCorner, 1, -1};
  plan.actions.push_back(place);
  EXPECT_TRUE(validatePlan(plan, state).valid()) << validatePlan(plan, state).summary();
  // The region's support must have a reachable flat top.
  plan.actions[1].params.target = "eraser";
  EXPECT_THAT(validatePlan(plan, state).summary(), HasSubstr("eraser has no far_right_corner: regions are of a support's flat top"));
  // A 1 m object fits no corner of the reachable desk.
  SymbolicState large = state;
  large.sizes["marker"] = Vector3(1.0, 1.0, 0.02);
  plan.actions[1].params.target = "desk";
  EXPECT_THAT(validatePlan(plan, large).summary(), HasSubstr("does not fit in the far_right_corner of desk"));
}

}  // namespace
}  // namespace lang2manip
