// Placement on the built-in desk scenes: in the holder, on the desk, beside other objects, at an
// explicit pose; a full holder, a too-large object and a blocked pose are refused with reasons.

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "grounding_test_support.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/grounding/grasp_planner.hpp"
#include "lang2manip/grounding/placement.hpp"
#include "lang2manip/grounding/object_geometry.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"
#include "lang2manip/symbolic/surface_region.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;

/// Every top/front/side grasp the planner finds for `object`, as X_OG.
std::vector<Pose> graspsOf(const ReachabilityChecker& reach, const std::string& object) {
  GraspRequest request;
  request.object = object;
  request.settings.maxCandidates = 12;
  const GraspPlan plan = makeGraspPlanner("heuristic")->plan(reach, request);
  std::vector<Pose> grasps;
  for (const GraspCandidate& c : plan.candidates) grasps.push_back(c.objectToGripper);
  return grasps;
}

PlacementPlan place(const ReachabilityChecker& reach, const std::string& object, PlacementTarget target) {
  PlacementRequest request;
  request.object = object;
  request.target = std::move(target);
  request.grasps = graspsOf(reach, object);
  return planPlacement(reach, request);
}

PlacementTarget relation(SpatialRelation r, const std::string& target, std::optional<double> distance = {}) {
  return {r, target, distance, {}, {}};
}

/// The scene after releasing the object at the first candidate's pose.
Scene placed(const ReachabilityChecker& reach, const PlacementPlan& plan) {
  Scene scene = reach.scene();
  scene.object(plan.candidates.front().object).pose = plan.candidates.front().objectPose;
  return scene;
}

class PlacementOnRobot : public ::testing::TestWithParam<std::string> {};

TEST_P(PlacementOnRobot, MarkerAndEraserGoInTheHolder) {
  const ReachabilityChecker reach = reachFor(GetParam(), deskScene(GetParam()));
  for (const std::string object : {"eraser", "marker"}) {
    const PlacementPlan plan = place(reach, object, relation(SpatialRelation::kIn, "holder"));
    ASSERT_TRUE(plan.success()) << plan.reason;
    const PlacementCandidate& c = plan.candidates.front();
    EXPECT_EQ(c.support, "holder");
    EXPECT_FALSE(c.placeSolutions.empty());
    EXPECT_FALSE(c.prePlaceSolutions.empty());
    const Pose release = Pose(Eigen::Translation3d(Vector3::UnitZ() * c.dropHeight)) * c.objectPose;
    EXPECT_TRUE(c.placePose.isApprox(release * c.objectToGripper));
    // Released inside, or at most just above the rim (the open Panda and UR5 fingers do not fit
    // in the holder's opening).
    const double rim = reach.scene().object("holder").worldBounds().max().z();
    EXPECT_LE(boundsAtPose(reach.scene().object(object), release).min().z(), rim + PlacementSettings{}.rimClearance + 1e-9);
    const SymbolicState state = observeSymbolicState(placed(reach, plan));
    EXPECT_EQ(state.inside.count(object), 1u) << object;
  }
}

TEST_P(PlacementOnRobot, EraserOnTheDeskAndBesideTheMarker) {
  const ReachabilityChecker reach = reachFor(GetParam(), deskScene(GetParam()));
  const PlacementPlan on = place(reach, "eraser", relation(SpatialRelation::kOn, "desk"));
  ASSERT_TRUE(on.success()) << on.reason;
  EXPECT_EQ(observeSymbolicState(placed(reach, on)).onTopOf.at("eraser"), "desk");
  for (SpatialRelation r : {SpatialRelation::kLeftOf, SpatialRelation::kRightOf, SpatialRelation::kInFrontOf,
                            SpatialRelation::kBehind, SpatialRelation::kNextTo}) {
    const PlacementPlan plan = place(reach, "eraser", relation(r, "marker"));
    ASSERT_TRUE(plan.success()) << spatialRelationName(r) << ": " << plan.reason;
    Goal goal{GoalKind::kRelation, "eraser", r, "marker", {}, Vector3::Zero(), {}, {}, 0.0};
    const GoalCheck check = checkGoalInScene(placed(reach, plan), goal);
    EXPECT_TRUE(check.holds) << check.explanation;
  }
}

INSTANTIATE_TEST_SUITE_P(DeskRobots, PlacementOnRobot, ::testing::Values("panda", "ur5"));

TEST(Placement, GivenDistanceIsKept) {
  const ReachabilityChecker reach = reachFor("panda", deskScene("panda"));
  const PlacementPlan plan = place(reach, "eraser", relation(SpatialRelation::kLeftOf, "marker", 0.12));
  ASSERT_TRUE(plan.success()) << plan.reason;
  Goal goal{GoalKind::kRelation, "eraser", SpatialRelation::kLeftOf, "marker", 0.12, Vector3::Zero(), {}, {}, 0.0};
  Scene world = placed(reach, plan);
  EXPECT_TRUE(checkGoalInScene(world, goal).holds);
  // "12 cm to the left of" is the whole offset: 12 cm left but 10 cm further forward is not it.
  world.object("eraser").pose.translation() += robotBaseFrame(world, "").linear() * Vector3(0.10, 0.0, 0.0);
  const GoalCheck forward = checkGoalInScene(world, goal);
  EXPECT_FALSE(forward.holds);
  EXPECT_THAT(forward.explanation, HasSubstr("0.100 m off the line through it"));
}

/// An open box (floor and four walls) of inner size `inner` and wall height `height`, its floor's
/// bottom centre at `bottomCentre`.
SceneObject tray(const Vector3& inner, double height, const Vector3& bottomCentre) {
  SceneObject object;
  object.name = "tray";
  object.kind = "tray";
  object.movable = false;
  object.role = ObjectRole::kContainer;
  const double wall = 0.01;
  auto add = [&](const Vector3& size, const Vector3& centre) {
    Shape shape;
    shape.geometry = Box{size};
    shape.origin.translation() = centre;
    object.collisions.push_back(shape);
  };
  add(Vector3(inner.x() + 2 * wall, inner.y() + 2 * wall, wall), Vector3(0, 0, wall / 2));
  add(Vector3(wall, inner.y(), height), Vector3(inner.x() / 2 + wall / 2, 0, height / 2));
  add(Vector3(wall, inner.y(), height), Vector3(-inner.x() / 2 - wall / 2, 0, height / 2));
  add(Vector3(inner.x() + 2 * wall, wall, height), Vector3(0, inner.y() / 2 + wall / 2, height / 2));
  add(Vector3(inner.x() + 2 * wall, wall, height), Vector3(0, -inner.y() / 2 - wall / 2, height / 2));
  object.cavity = AlignedBox3(Vector3(-inner.x() / 2, -inner.y() / 2, wall), Vector3(inner.x() / 2, inner.y() / 2, height));
  object.pose.translation() = bottomCentre;
  return object;
}

TEST(Placement, AWideContainerIsEnteredAndANarrowOneIsDroppedInto) {
  Scene scene = deskScene("panda");
  scene.addObject(tray(Vector3(0.25, 0.25, 0.0), 0.05, Vector3(0.15, -0.15, 0.75)));
  const ReachabilityChecker reach = reachFor("panda", scene);
  const PlacementPlan wide = place(reach, "eraser", relation(SpatialRelation::kIn, "tray"));
  ASSERT_TRUE(wide.success()) << wide.reason;
  EXPECT_EQ(wide.candidates.front().dropHeight, 0.0) << "the open fingers fit inside the tray";
  const PlacementPlan narrow = place(reach, "eraser", relation(SpatialRelation::kIn, "holder"));
  ASSERT_TRUE(narrow.success()) << narrow.reason;
  // The open Panda fingers are wider than the holder's opening: they stay above its rim.
  const double rim = reach.scene().object("holder").worldBounds().max().z();
  for (const PlacementCandidate& c : narrow.candidates) {
    EXPECT_GE(transformedBox(reach.gripper().fingerBounds, c.placePose).min().z(), rim - 1e-9) << c.label;
  }
}

/// The Panda desk with an 11.6 cm tray and four 4.5 cm blocks ("block0".."block3") beside it.
Scene trayAndFourBlocks() {
  Scene scene = deskScene("panda");
  scene.removeObject("marker");
  scene.removeObject("eraser");
  scene.addObject(tray(Vector3(0.116, 0.116, 0.0), 0.04, Vector3(0.15, -0.15, 0.75)));
  const std::vector<Vector3> starts{{-0.05, 0.1, 0.75}, {-0.05, 0.2, 0.75}, {0.05, 0.2, 0.75}, {-0.05, -0.05, 0.75}};
  for (std::size_t i = 0; i < starts.size(); ++i) scene.addObject(boxObject("block" + std::to_string(i), Vector3::Constant(0.045), starts[i]));
  return scene;
}

// The yaw of the object placed at `spot` among four slabs `distance` from it on each side, with
// the one top grasp square to its faces kept from the pick.
double yawPlacedAmongSlabs(double distance) {
  Scene scene = emptyDeskScene("panda");
  const Vector3 spot(0.15, 0.0, 0.75);
  scene.addObject(boxObject("piece", Vector3::Constant(0.04), Vector3(0.0, -0.2, 0.75)));
  const std::vector<Vector3> around{{distance, 0, 0}, {-distance, 0, 0}, {0, distance, 0}, {0, -distance, 0}};
  for (std::size_t i = 0; i < around.size(); ++i) {
    const Vector3 slab = i < 2 ? Vector3(0.02, 0.04, 0.04) : Vector3(0.04, 0.02, 0.04);
    scene.addObject(boxObject("n" + std::to_string(i), slab, spot + around[i]));
  }
  const ReachabilityChecker reach = reachFor("panda", scene);
  PlacementTarget at;
  at.position = robotBaseFrame(scene, "").inverse() * spot;
  PlacementRequest request;
  request.object = "piece";
  request.target = at;
  for (const Pose& grasp : graspsOf(reach, "piece")) {
    const double graspYaw = std::atan2(grasp.linear()(1, 0), grasp.linear()(0, 0));
    const bool square = std::abs(grasp.linear()(2, 2)) > 0.99 && std::abs(std::remainder(graspYaw, M_PI / 2.0)) < 1e-6;
    if (square && request.grasps.empty()) request.grasps.push_back(grasp);
  }
  EXPECT_EQ(request.grasps.size(), 1u);
  const PlacementPlan plan = planPlacement(reach, request);
  EXPECT_TRUE(plan.success()) << plan.reason;
  if (!plan.success()) return std::nan("");
  const Matrix3 turned = plan.candidates.front().objectPose.linear();
  return std::atan2(turned(1, 0), turned(0, 0));
}

TEST(Placement, AtAPositionAmongNeighboursTheHandMayTurnAnEighth) {
  // Slabs 5.5 cm from the spot leave no room for a finger along either axis; between them,
  // diagonally, the fingers fit. 7 cm away a quarter turn fits, and is preferred.
  EXPECT_NEAR(std::abs(std::remainder(yawPlacedAmongSlabs(0.055), M_PI / 2.0)), M_PI / 4.0, 1e-6);
  EXPECT_NEAR(std::abs(std::remainder(yawPlacedAmongSlabs(0.07), M_PI / 2.0)), 0.0, 1e-6);
}

TEST(Placement, AtAPositionOverTwoBlocksItRestsOnBoth) {
  // Two 4 cm blocks 1 cm apart, the third asked for over the gap between them at their height:
  // it goes onto both (the top of a pyramid), the symbolic state sees it on one of them.
  Scene scene = emptyDeskScene("panda");
  const Vector3 middle(0.15, 0.0, 0.75);
  scene.addObject(boxObject("left", Vector3::Constant(0.04), middle + Vector3(0.0, 0.025, 0.0)));
  scene.addObject(boxObject("right", Vector3::Constant(0.04), middle + Vector3(0.0, -0.025, 0.0)));
  scene.addObject(boxObject("top", Vector3::Constant(0.04), Vector3(0.0, -0.2, 0.75)));
  const double baseTop = scene.object("left").worldBounds().max().z();
  const ReachabilityChecker reach = reachFor("panda", scene);
  PlacementTarget at;
  const SceneObject& top = scene.object("top");
  at.position = robotBaseFrame(scene, "").inverse() * Vector3(middle.x(), middle.y(), top.pose.translation().z() + baseTop - top.worldBounds().min().z());
  const PlacementPlan plan = place(reach, "top", at);
  ASSERT_TRUE(plan.success()) << plan.reason;
  const PlacementCandidate& candidate = plan.candidates.front();
  EXPECT_TRUE(candidate.support == "left" || candidate.support == "right") << candidate.support;
  const Scene after = placed(reach, plan);
  EXPECT_NEAR(after.object("top").worldBounds().min().z(), baseTop, 0.005);
  const SceneObject* support = currentSupport(after, after.object("top"), kSupportTolerance);
  ASSERT_NE(support, nullptr);
  EXPECT_TRUE(support->name == "left" || support->name == "right");
  const SymbolicState state = observeSymbolicState(after);
  ASSERT_TRUE(state.onTopOf.count("top"));
  EXPECT_EQ(state.onTopOf.at("top"), support->name);

  // Over one block's edge only (its centre beyond the gap), nothing holds it there.
  at.position = robotBaseFrame(scene, "").inverse() * Vector3(middle.x(), middle.y() + 0.05, top.pose.translation().z() + baseTop - top.worldBounds().min().z());
  EXPECT_FALSE(place(reach, "top", at).success());
}

TEST(Placement, ObjectsPutInOneAtATimeArePackedSoThatTheLastStillFits) {
  // Four 4.5 cm blocks fit a 11.6 cm tray only two by two: each one, placed without knowing
  // what follows, leaves the most room for more like it (a corner, not the middle).
  Scene scene = trayAndFourBlocks();
  for (std::size_t i = 0; i < 4; ++i) {
    const std::string block = "block" + std::to_string(i);
    const ReachabilityChecker reach = reachFor("panda", scene);
    const PlacementPlan plan = place(reach, block, relation(SpatialRelation::kIn, "tray"));
    ASSERT_TRUE(plan.success()) << block << ": " << plan.reason;
    scene = placed(reach, plan);
    const Vector3 offCentre = scene.object(block).worldBounds().center() - Vector3(0.15, -0.15, 0.0);
    EXPECT_GT(std::abs(offCentre.x()), 0.03) << block;
    EXPECT_GT(std::abs(offCentre.y()), 0.03) << block;
  }
}

TEST(Placement, ObjectsKnownToFollowAllKeepAPlace) {
  // The same four blocks put in by one plan: each placement leaves one free position for every
  // block that follows it, all at once (each alone would find one in the middle's way).
  Scene scene = trayAndFourBlocks();
  const std::vector<std::string> blocks{"block0", "block1", "block2", "block3"};
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const ReachabilityChecker reach = reachFor("panda", scene);
    PlacementRequest request;
    request.object = blocks[i];
    request.target = relation(SpatialRelation::kIn, "tray");
    request.grasps = graspsOf(reach, blocks[i]);
    request.placedAfter.assign(blocks.begin() + static_cast<std::ptrdiff_t>(i + 1), blocks.end());
    const PlacementPlan plan = planPlacement(reach, request);
    ASSERT_TRUE(plan.success()) << blocks[i] << ": " << plan.reason;
    scene = placed(reach, plan);
  }
}

TEST(Placement, TheNearCornersOfTheReachablePartOfTheDeskArePlaceableOnEveryRobot) {
  // The reach stated to planners is measured without the arm hitting itself (the UR5's wrist
  // folds into its forearm near its base): a block standing in the near corners of the reachable
  // part of the desk is placeable.
  for (const char* robot : {"panda", "ur5", "iiwa14", "tx90", "yumi"}) {
    Scene scene = deskScene(robot);
    scene.removeObject("holder");
    scene.addObject(boxObject("block", Vector3::Constant(0.04), scene.object("eraser").pose.translation() + Vector3(0.0, 0.0, 0.0)));
    scene.removeObject("eraser");
    const std::string arm = scene.robots().front().model->semantics().manipulators.front().name;
    const auto area = supportArea(scene, "desk", "", nullptr, arm);
    ASSERT_TRUE(area);
    const ReachabilityChecker reach = reachFor(robot, scene);
    for (const double y : {area->reachable.min().y() + 0.02, area->reachable.max().y() - 0.02}) {
      SCOPED_TRACE(std::string(robot) + " y " + std::to_string(y));
      PlacementTarget target;
      target.position = Vector3(area->reachable.min().x() + 0.02, y, area->top.max().z());
      const PlacementPlan plan = place(reach, "block", target);
      EXPECT_TRUE(plan.success()) << plan.reason;
    }
  }
}

TEST(Placement, FullHolderIsRefused) {
  Scene scene = deskScene("panda");
  scene.addObject(boxObject("block", Vector3(0.055, 0.055, 0.09), Vector3(0.12, 0.02, 0.755)));
  const PlacementPlan plan = place(reachFor("panda", scene), "eraser", relation(SpatialRelation::kIn, "holder"));
  EXPECT_FALSE(plan.success());
  EXPECT_EQ(plan.failure, PlacementFailure::kBlocked);
  EXPECT_THAT(plan.reason, HasSubstr("eraser in holder"));
  EXPECT_THAT(plan.reason, HasSubstr("block"));
}

TEST(Placement, TooLargeObjectIsRefused) {
  Scene scene = deskScene("panda");
  scene.addObject(boxObject("cube", Vector3(0.07, 0.07, 0.07), Vector3(0.1, -0.3, 0.75)));
  PlacementRequest request;
  request.object = "cube";
  request.target = relation(SpatialRelation::kIn, "holder");
  request.grasps = {Pose::Identity()};
  const PlacementPlan plan = planPlacement(reachFor("panda", scene), request);
  EXPECT_EQ(plan.failure, PlacementFailure::kTooLarge);
  EXPECT_THAT(plan.reason, HasSubstr("cube"));
  EXPECT_THAT(plan.reason, HasSubstr("too large for the cavity of holder"));
}

TEST(Placement, BlockedExplicitPoseAndMidAirAreRefused) {
  const ReachabilityChecker reach = reachFor("panda", deskScene("panda"));
  const Pose base = reach.robot().basePose;
  PlacementTarget onMarker;
  onMarker.position = base.inverse() * Vector3(0.02, -0.18, 0.75);
  const PlacementPlan blocked = place(reach, "eraser", onMarker);
  EXPECT_EQ(blocked.failure, PlacementFailure::kBlocked);
  EXPECT_THAT(blocked.reason, HasSubstr("blocked by marker"));
  EXPECT_EQ(blocked.blockers, std::vector<std::string>{"marker"});
  PlacementTarget midAir;
  midAir.position = base.inverse() * Vector3(0.2, -0.1, 1.2);
  const PlacementPlan air = place(reach, "eraser", midAir);
  EXPECT_EQ(air.failure, PlacementFailure::kNoSupport);
  PlacementTarget free;
  free.position = base.inverse() * Vector3(0.1, -0.25, 0.75);
  const PlacementPlan ok = place(reach, "eraser", free);
  EXPECT_TRUE(ok.success()) << ok.reason;
}

TEST(Placement, BadTargetsAndInput) {
  const ReachabilityChecker reach = reachFor("panda", deskScene("panda"));
  EXPECT_EQ(place(reach, "eraser", relation(SpatialRelation::kIn, "desk")).failure, PlacementFailure::kBadTarget);
  EXPECT_EQ(place(reach, "eraser", relation(SpatialRelation::kLeftOf, "eraser")).failure, PlacementFailure::kBadTarget);
  PlacementRequest request;
  request.object = "eraser";
  request.target = relation(SpatialRelation::kOn, "desk");
  EXPECT_THROW(static_cast<void>(planPlacement(reach, request)), InputError);  // not held, no grasp
  request.grasps = {Pose::Identity()};
  request.target = relation(SpatialRelation::kOn, "shelf");
  EXPECT_THROW(static_cast<void>(planPlacement(reach, request)), InputError);
  request.target = relation(SpatialRelation::kOn, "desk");
  request.settings.cavityGrid = 0;
  EXPECT_THROW(static_cast<void>(planPlacement(reach, request)), InputError);
}

}  // namespace
}  // namespace lang2manip::test
