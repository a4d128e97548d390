#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lang2manip/core/error.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/symbolic/plan_validation.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"

namespace lang2manip {
namespace {

using ::testing::Contains;
using ::testing::HasSubstr;

SymbolicAction pickAction(const std::string& object) { return {ActionType::kPick, object, {}, {}, ""}; }

SymbolicAction place(const std::string& object, SpatialRelation relation, const std::string& target) {
  SymbolicAction action{ActionType::kPlace, object, {}, {}, ""};
  action.params.relation = relation;
  action.params.target = target;
  return action;
}

SymbolicAction moveTo(const std::string& configuration) {
  SymbolicAction action{ActionType::kMove, "", {}, {}, ""};
  action.params.configuration = configuration;
  return action;
}

SymbolicAction push(const std::string& object) {
  SymbolicAction action{ActionType::kPush, object, {}, {}, ""};
  action.params.direction = Vector3::UnitY();
  action.params.distance = 0.05;
  return action;
}

Goal relationGoal(const std::string& object, SpatialRelation relation, const std::string& target) {
  Goal goal;
  goal.object = object;
  goal.relation = relation;
  goal.target = target;
  return goal;
}

Goal kindGoal(GoalKind kind, const std::string& object) {
  Goal goal;
  goal.kind = kind;
  goal.object = object;
  return goal;
}

class PlanValidationTest : public ::testing::Test {
 protected:
  PlanValidationTest()
      : problem_(readKauthamProblem(resolveProblem("panda_desk"))), state_(observeSymbolicState(problem_.scene)) {}

  PlanValidation validate(std::vector<SymbolicAction> actions) const {
    Plan plan;
    plan.actions = std::move(actions);
    return validatePlan(plan, state_);
  }

  KauthamProblem problem_;
  SymbolicState state_;
};

TEST_F(PlanValidationTest, PaperPlanIsValidAndPutsBothObjectsInTheHolder) {
  const PlanValidation result = validate({pickAction("marker"), place("marker", SpatialRelation::kIn, "holder"),
                                          pickAction("eraser"), place("eraser", SpatialRelation::kIn, "holder"),
                                          moveTo("home")});
  EXPECT_TRUE(result.valid()) << result.summary();
  EXPECT_EQ(result.finalState.inside.at("marker"), "holder");
  EXPECT_EQ(result.finalState.inside.at("eraser"), "holder");
  EXPECT_TRUE(result.finalState.held.empty());
  EXPECT_EQ(result.finalState.atConfiguration, "home");
  EXPECT_EQ(goalHolds(result.finalState, relationGoal("marker", SpatialRelation::kIn, "holder")), true);
  EXPECT_EQ(goalHolds(state_, relationGoal("marker", SpatialRelation::kIn, "holder")), false);
}

TEST_F(PlanValidationTest, PlaceBeforePickNamesTheStepAndTheObject) {
  const PlanValidation result = validate({pickAction("marker"), place("marker", SpatialRelation::kIn, "holder"),
                                          place("eraser", SpatialRelation::kIn, "holder")});
  EXPECT_FALSE(result.valid());
  EXPECT_EQ(result.failedStep, 2U);
  EXPECT_THAT(result.problems, Contains("step 3 (place eraser in holder): eraser is not held; pick it first"));
}

TEST_F(PlanValidationTest, UnknownObjectIsNamedWithTheValidOnes) {
  const PlanValidation result = validate({pickAction("cup")});
  EXPECT_THAT(result.problems, Contains("step 1 (pick cup): there is no object \"cup\" (objects: desk, marker, eraser, holder)"));
}

TEST_F(PlanValidationTest, PickingTheHeldObjectAgainIsRejected) {
  const PlanValidation result = validate({pickAction("marker"), pickAction("marker")});
  EXPECT_THAT(result.problems, Contains("step 2 (pick marker): marker is already held"));
}

TEST_F(PlanValidationTest, PickingASecondObjectNeedsAFreeGripper) {
  const PlanValidation result = validate({pickAction("marker"), pickAction("eraser")});
  EXPECT_THAT(result.problems,
              Contains("step 2 (pick eraser): the gripper is not free: the gripper holds marker; place it first"));
}

TEST_F(PlanValidationTest, PlacingInANonContainerListsTheContainers) {
  const PlanValidation result = validate({pickAction("marker"), place("marker", SpatialRelation::kIn, "eraser")});
  EXPECT_THAT(result.problems, Contains("step 2 (place marker in eraser): eraser is not a container (containers: holder)"));
}

TEST_F(PlanValidationTest, FixedObjectsCannotBePicked) {
  EXPECT_THAT(validate({pickAction("desk")}).problems, Contains(HasSubstr("desk is fixed and cannot be picked")));
}

TEST_F(PlanValidationTest, AnObjectWithSomethingInItIsNotClear) {
  const PlanValidation result = validate({pickAction("marker"), place("marker", SpatialRelation::kIn, "holder"), pickAction("holder")});
  EXPECT_THAT(result.problems, Contains("step 3 (pick holder): holder is not clear: marker is in it; move them first"));
}

TEST_F(PlanValidationTest, PlacingWhileHoldingAnotherObjectSaysWhatIsHeld) {
  const PlanValidation result = validate({pickAction("marker"), place("eraser", SpatialRelation::kOn, "desk")});
  EXPECT_THAT(result.problems, Contains(HasSubstr("eraser is not held (the gripper holds marker)")));
}

/// A movable box of `size` standing on the desk at (x, y).
SceneObject blockOnDesk(const std::string& name, const Vector3& size, double x, double y) {
  SceneObject block;
  block.name = name;
  block.kind = "block";
  block.movable = true;
  Shape shape;
  shape.geometry = Box{size};
  block.collisions.push_back(shape);
  block.pose.translation() = Vector3(x, y, 0.75 + size.z() / 2.0);
  return block;
}

TEST_F(PlanValidationTest, StackingNeedsAClearTarget) {
  Scene scene = problem_.scene;
  scene.addObject(blockOnDesk("block", Vector3(0.06, 0.06, 0.03), 0.1, 0.3));
  Plan plan;
  plan.actions = {pickAction("eraser"), place("eraser", SpatialRelation::kOn, "block"), pickAction("holder"),
                  place("holder", SpatialRelation::kOn, "block")};
  const PlanValidation result = validatePlan(plan, observeSymbolicState(scene));
  EXPECT_THAT(result.problems, Contains("step 4 (place holder on block): block is not clear: eraser is on it"));
}

TEST_F(PlanValidationTest, StackingNeedsAFlatTopTheObjectFitsOn) {
  EXPECT_THAT(validate({pickAction("eraser"), place("eraser", SpatialRelation::kOn, "marker")}).problems,
              Contains("step 2 (place eraser on marker): eraser cannot rest on marker: its top is round (a cylinder lying on its side)"));
  EXPECT_THAT(validate({pickAction("holder"), place("holder", SpatialRelation::kOn, "eraser")}).problems,
              Contains("step 2 (place holder on eraser): holder (0.086 x 0.086 m) does not fit on the top of eraser (0.050 x 0.020 m)"));
  EXPECT_THAT(validate({pickAction("marker"), place("marker", SpatialRelation::kOn, "holder")}).problems,
              Contains(HasSubstr("marker cannot rest on holder: it is open at the top (a container: put things in it)")));
  Scene scene = problem_.scene;
  scene.addObject(blockOnDesk("block", Vector3(0.06, 0.06, 0.03), 0.1, 0.3));
  Plan plan;
  plan.actions = {pickAction("eraser"), place("eraser", SpatialRelation::kOn, "block")};
  EXPECT_TRUE(validatePlan(plan, observeSymbolicState(scene)).valid());
}

TEST_F(PlanValidationTest, PushNeedsAFreeGripperAndMoveAKnownConfiguration) {
  EXPECT_THAT(validate({pickAction("marker"), push("eraser")}).problems,
              Contains(HasSubstr("step 2 (push eraser 0.05 m along (0, 1, 0)): push needs a free gripper")));
  EXPECT_THAT(validate({moveTo("dance")}).problems,
              Contains("step 1 (move to dance): the robot has no configuration \"dance\" (configurations: home)"));
  EXPECT_TRUE(validate({push("eraser"), moveTo("home")}).valid());
}

TEST_F(PlanValidationTest, PlacingBesideAnObjectLandsOnItsSupport) {
  const PlanValidation result = validate({pickAction("marker"), place("marker", SpatialRelation::kLeftOf, "holder")});
  ASSERT_TRUE(result.valid()) << result.summary();
  EXPECT_EQ(result.finalState.onTopOf.at("marker"), "desk");
  EXPECT_FALSE(goalHolds(result.finalState, relationGoal("marker", SpatialRelation::kLeftOf, "holder")).has_value());
}

TEST(SymbolicStateConfigurationTest, PaperSceneStartsAtHome) {
  KauthamProblem problem = readKauthamProblem(resolveProblem("panda_desk"));
  SymbolicState state = observeSymbolicState(problem.scene);
  EXPECT_EQ(state.atConfiguration, "home");
  EXPECT_EQ(state.namedConfigurations, std::set<std::string>{"home"});
  VectorX q = problem.scene.robots().front().configuration;
  q[0] += 0.3;
  problem.scene.setConfiguration(problem.scene.robots().front().name, q);
  EXPECT_EQ(observeSymbolicState(problem.scene).atConfiguration, "");
  EXPECT_THROW(observeSymbolicState(problem.scene, {}, "no_such_robot"), InputError);
}

class GeometricGoalTest : public ::testing::Test {
 protected:
  GeometricGoalTest() : problem_(readKauthamProblem(resolveProblem("panda_desk"))) {}
  Scene& scene() { return problem_.scene; }
  KauthamProblem problem_;
};

TEST_F(GeometricGoalTest, SideRelationsAreInTheRobotBaseFrame) {
  // Marker at y = -0.18, eraser at y = +0.17, robot facing +x: the eraser is left of the marker.
  const Goal eraserLeft = relationGoal("eraser", SpatialRelation::kLeftOf, "marker");
  const Goal markerLeft = relationGoal("marker", SpatialRelation::kLeftOf, "eraser");
  const Goal markerRight = relationGoal("marker", SpatialRelation::kRightOf, "eraser");
  EXPECT_TRUE(checkGoalInScene(scene(), eraserLeft).holds);
  EXPECT_FALSE(checkGoalInScene(scene(), markerLeft).holds);
  EXPECT_TRUE(checkGoalInScene(scene(), markerRight).holds);
  EXPECT_THAT(checkGoalInScene(scene(), markerLeft).explanation, HasSubstr("left of eraser"));
  // Turning the robot around swaps left and right.
  Pose turned = scene().robots().front().basePose;
  turned.linear() = Eigen::AngleAxisd(3.14159265358979, Vector3::UnitZ()).toRotationMatrix();
  scene().robot(scene().robots().front().name).basePose = turned;
  EXPECT_TRUE(checkGoalInScene(scene(), markerLeft).holds);
}

TEST_F(GeometricGoalTest, ExplicitDistancesAndNextTo) {
  Goal left = relationGoal("eraser", SpatialRelation::kLeftOf, "marker");
  const double offset = scene().object("eraser").worldBounds().center().y() - scene().object("marker").worldBounds().center().y();
  left.distance = offset;
  // A distance is the whole offset: left of the marker by it, and not in front of or behind it.
  const double across = scene().object("eraser").worldBounds().center().x() - scene().object("marker").worldBounds().center().x();
  EXPECT_GT(std::abs(across), 0.02);
  EXPECT_FALSE(checkGoalInScene(scene(), left).holds);
  scene().object("eraser").pose.translation().x() -= across;
  EXPECT_TRUE(checkGoalInScene(scene(), left).holds) << checkGoalInScene(scene(), left).explanation;
  left.distance = offset + 0.1;
  EXPECT_FALSE(checkGoalInScene(scene(), left).holds);
  const Goal nextTo = relationGoal("eraser", SpatialRelation::kNextTo, "marker");
  EXPECT_FALSE(checkGoalInScene(scene(), nextTo).holds);
  Pose near = scene().object("marker").pose;
  near.translation().y() += 0.06;
  scene().object("eraser").pose = near;
  EXPECT_TRUE(checkGoalInScene(scene(), nextTo).holds) << checkGoalInScene(scene(), nextTo).explanation;
}

TEST_F(GeometricGoalTest, InHoldingDisplacedAndErrors) {
  const Scene before = scene();
  const Goal inHolder = relationGoal("eraser", SpatialRelation::kIn, "holder");
  const GoalCheck notYet = checkGoalInScene(scene(), inHolder);
  EXPECT_FALSE(notYet.holds);
  EXPECT_THAT(notYet.explanation, HasSubstr("eraser is on desk"));
  Pose inside = scene().object("holder").pose;
  inside.translation().z() += 0.02;
  scene().object("eraser").pose = inside;
  EXPECT_TRUE(checkGoalInScene(scene(), inHolder).holds);

  Goal displaced = kindGoal(GoalKind::kDisplaced, "marker");
  displaced.displacement = Vector3(0.0, 0.05, 0.0);
  scene().object("marker").pose.translation().y() += 0.05;
  GoalCheckOptions options;
  options.initialScene = &before;
  EXPECT_TRUE(checkGoalInScene(scene(), displaced, options).holds);
  displaced.displacement = Vector3(0.05, 0.0, 0.0);
  EXPECT_FALSE(checkGoalInScene(scene(), displaced, options).holds);
  EXPECT_THROW(checkGoalInScene(scene(), displaced), InputError);
  EXPECT_THROW(checkGoalInScene(scene(), relationGoal("cup", SpatialRelation::kIn, "holder")), InputError);
  EXPECT_FALSE(checkGoalInScene(scene(), kindGoal(GoalKind::kHolding, "marker")).holds);
  Goal home = kindGoal(GoalKind::kAtConfiguration, "");
  home.configuration = "home";
  EXPECT_TRUE(checkGoalInScene(scene(), home).holds);
}

}  // namespace
}  // namespace lang2manip
