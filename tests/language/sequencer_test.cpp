#include <gtest/gtest.h>

#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/language/sequencer.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"
#include "lang2manip/symbolic/task_planner.hpp"
#include "language/language_test_scenes.hpp"
#include "language/plan_check.hpp"

namespace lang2manip {
namespace {

std::string describeAction(const SymbolicAction& action) {
  std::string text = actionTypeName(action.type);
  if (!action.object.empty()) text += " " + action.object;
  if (action.params.relation) {
    text += " " + spatialRelationName(*action.params.relation) + " " + action.params.target;
  }
  if (!action.params.configuration.empty()) text += " " + action.params.configuration;
  return text;
}

std::vector<std::string> describePlan(const Plan& plan) {
  std::vector<std::string> steps;
  for (const SymbolicAction& action : plan.actions) steps.push_back(describeAction(action));
  return steps;
}

Plan planFor(const Scene& scene, const std::string& instruction) {
  const TaskSpecification specification = understandInstruction(instruction, describeObjects(scene));
  return sequenceGoals(specification, observeSymbolicState(scene), sequencingOptionsFor(scene));
}

using Steps = std::vector<std::string>;

TEST(SequencerTest, PaperTaskIsExactlyFourActions) {
  const Plan plan = planFor(test::deskScene(), "put the marker and eraser in the holder");
  EXPECT_EQ(describePlan(plan), (Steps{"pick marker", "place marker in holder", "pick eraser",
                                       "place eraser in holder"}));
  for (const SymbolicAction& action : plan.actions) {
    EXPECT_EQ(action.refinements.grasp, GraspDirection::kAuto);
    EXPECT_TRUE(action.planner.empty());
  }
}

TEST(SequencerTest, GoalsAlreadyTrueAreSkipped) {
  Scene scene = test::deskScene();
  test::putInside(scene, "marker", "holder");
  EXPECT_EQ(describePlan(planFor(scene, "put the marker and eraser in the holder")),
            (Steps{"pick eraser", "place eraser in holder"}));
  test::putInside(scene, "eraser", "holder");
  const Plan nothing = planFor(scene, "put the marker and eraser in the holder");
  EXPECT_TRUE(nothing.actions.empty());
  EXPECT_NE(nothing.reasoning.find("marker in holder (already true)"), std::string::npos);
  EXPECT_TRUE(planFor(scene, "put the holder on the desk").actions.empty());
}

TEST(SequencerTest, OccupiedContainerIsClearedFirstWhenThereIsNoRoom) {
  Scene scene = test::workbenchScene();
  test::putInside(scene, "red_block", "yellow_cup");
  EXPECT_EQ(describePlan(planFor(scene, "put the blue block in the yellow cup")),
            (Steps{"pick red_block", "place red_block on table", "pick blue_block",
                   "place blue_block in yellow_cup"}));
}

TEST(SequencerTest, ContainerWithRoomIsNotCleared) {
  Scene scene = test::workbenchScene();
  test::putInside(scene, "red_block", "box");
  EXPECT_EQ(describePlan(planFor(scene, "put the blue block in the box")),
            (Steps{"pick blue_block", "place blue_block in box"}));
}

TEST(SequencerTest, ObjectTooBigForTheContainerIsAnError) {
  const Scene scene = test::workbenchScene();
  try {
    (void)planFor(scene, "put the green block in the yellow cup");
    FAIL() << "expected PlanningError";
  } catch (const PlanningError& error) {
    EXPECT_NE(std::string(error.what()).find("green_block does not fit in yellow_cup"),
              std::string::npos)
        << error.what();
  }
}

TEST(SequencerTest, StackOnTheObjectIsClearedBeforePickingIt) {
  Scene scene = test::workbenchScene();
  test::restOn(scene, "blue_block", "red_block");
  test::restOn(scene, "marker_1", "blue_block");
  EXPECT_EQ(describePlan(planFor(scene, "put the red block in the box")),
            (Steps{"pick marker_1", "place marker_1 on table", "pick blue_block",
                   "place blue_block on table", "pick red_block", "place red_block in box"}));
}

TEST(SequencerTest, StackTargetIsClearedBeforeStackingOnIt) {
  Scene scene = test::workbenchScene();
  test::restOn(scene, "blue_block", "green_block");
  EXPECT_EQ(describePlan(planFor(scene, "put the red block on the green block")),
            (Steps{"pick blue_block", "place blue_block on table", "pick red_block",
                   "place red_block on green_block"}));
}

TEST(SequencerTest, StackingThreeBlocksBuildsFromTheBottom) {
  EXPECT_EQ(describePlan(planFor(test::workbenchScene(), "stack the blocks")),
            (Steps{"pick red_block", "place red_block on green_block", "pick blue_block",
                   "place blue_block on red_block"}));
}

TEST(SequencerTest, OrderIsChangedWhenTheInstructionOrderCannotWork) {
  EXPECT_EQ(describePlan(planFor(test::workbenchScene(),
                                 "put the red block on the blue block, then put the blue block "
                                 "in the box")),
            (Steps{"pick blue_block", "place blue_block in box", "pick red_block",
                   "place red_block on blue_block"}));
}

TEST(SequencerTest, HoldingGoalIsReachedLast) {
  EXPECT_EQ(describePlan(planFor(test::deskScene(),
                                 "pick up the marker and put the eraser in the holder")),
            (Steps{"pick eraser", "place eraser in holder", "pick marker"}));
}

TEST(SequencerTest, HeldObjectIsPutDownWhenTheGripperIsNeeded) {
  const Scene scene = test::deskScene();
  SymbolicState state = observeSymbolicState(scene);
  state.onTopOf.erase("marker");
  state.held = "marker";
  const TaskSpecification specification =
      understandInstruction("put the eraser in the holder", describeObjects(scene));
  EXPECT_EQ(describePlan(sequenceGoals(specification, state)),
            (Steps{"place marker on desk", "pick eraser", "place eraser in holder"}));
}

TEST(SequencerTest, PickUpAndPlaceDoesNotPickTwice) {
  EXPECT_EQ(describePlan(planFor(test::deskScene(), "pick up the marker and put it in the holder")),
            (Steps{"pick marker", "place marker in holder"}));
}

TEST(SequencerTest, PushesMovesAndRefinementsAreCarried) {
  const Plan plan = planFor(test::deskScene(),
                            "push the eraser 5 cm to the left using PRM, then put the marker in "
                            "the holder with a side grasp using RRT* and go home with RRTConnect");
  ASSERT_EQ(describePlan(plan), (Steps{"push eraser", "pick marker", "place marker in holder",
                                       "move home"}));
  EXPECT_TRUE(plan.actions[0].params.direction->isApprox(Vector3(0, 1, 0)));
  EXPECT_NEAR(*plan.actions[0].params.distance, 0.05, 1e-12);
  EXPECT_EQ(plan.actions[0].planner, "PRM");
  EXPECT_EQ(plan.actions[1].refinements.grasp, GraspDirection::kSide);
  EXPECT_EQ(plan.actions[1].planner, "RRTstar");
  EXPECT_EQ(plan.actions[2].planner, "RRTstar");
  EXPECT_EQ(plan.actions[3].params.configuration, "home");
  EXPECT_EQ(plan.actions[3].planner, "RRTConnect");
}

TEST(SequencerTest, DirectionalRelationsKeepTheirDistance) {
  const Plan plan = planFor(test::deskScene(), "put the eraser 5 cm to the left of the holder");
  ASSERT_EQ(plan.actions.size(), 2u);
  EXPECT_EQ(plan.actions[1].params.relation, SpatialRelation::kLeftOf);
  EXPECT_NEAR(*plan.actions[1].params.distance, 0.05, 1e-12);
}

TEST(SequencerTest, UnmovableObjectIsAnErrorNamingIt) {
  try {
    (void)planFor(test::deskScene(), "move the desk 5 cm to the left");
    FAIL() << "expected PlanningError";
  } catch (const PlanningError& error) {
    EXPECT_NE(std::string(error.what()).find("desk is not movable"), std::string::npos)
        << error.what();
  }
}

TEST(SequencerTest, UnknownObjectInAGoalIsAnError) {
  TaskSpecification specification;
  Goal goal;
  goal.object = "cup";
  goal.relation = SpatialRelation::kIn;
  goal.target = "holder";
  specification.goals.push_back(goal);
  try {
    (void)sequenceGoals(specification, observeSymbolicState(test::deskScene()));
    FAIL() << "expected PlanningError";
  } catch (const PlanningError& error) {
    EXPECT_NE(std::string(error.what()).find("unknown object \"cup\""), std::string::npos);
  }
}

TEST(SequencerTest, ContradictoryGoalsAreAnError) {
  try {
    (void)planFor(test::workbenchScene(),
                  "put the red block on the blue block and the blue block on the red block");
    FAIL() << "expected PlanningError";
  } catch (const PlanningError& error) {
    EXPECT_NE(std::string(error.what()).find("no order of actions achieves every goal"),
              std::string::npos)
        << error.what();
  }
}

TEST(SequencerTest, PlanCheckerCatchesBrokenPlans) {
  const Scene scene = test::deskScene();
  const TaskSpecification specification =
      understandInstruction("put the marker and eraser in the holder", describeObjects(scene));
  const SymbolicState state = observeSymbolicState(scene);
  Plan plan = sequenceGoals(specification, state, sequencingOptionsFor(scene));
  ASSERT_EQ(test::checkPlan(plan, state, specification), "");
  Plan swapped = plan;
  std::swap(swapped.actions[0], swapped.actions[1]);
  EXPECT_EQ(test::checkPlan(swapped, state, specification),
            "action 1 (place marker): not holding marker");
  Plan doublePick = plan;
  doublePick.actions.erase(doublePick.actions.begin() + 1);
  EXPECT_EQ(test::checkPlan(doublePick, state, specification),
            "action 2 (pick eraser): gripper holds marker");
  Plan shortPlan = plan;
  shortPlan.actions.resize(2);
  EXPECT_EQ(test::checkPlan(shortPlan, state, specification),
            "eraser in holder does not hold at the end");
}

TEST(SequencerTest, SamePlanEveryTime) {
  const Scene scene = test::workbenchScene();
  const std::string task = "put all the blocks in the box, then stack the cups";
  EXPECT_EQ(describePlan(planFor(scene, task)), describePlan(planFor(scene, task)));
}

}  // namespace
}  // namespace lang2manip
