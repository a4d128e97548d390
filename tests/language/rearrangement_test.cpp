// Rearrangements and turns (issue 15, classes 5 and 6): swapping two objects, putting one where
// another stands (that one set aside on a free spot first), turning by an angle, pointing at an
// object; and the refusals: a turn that leaves the object looking the same, an object without a
// long side to point with, a swap of one object. On the desk of every built-in robot.

#include <cmath>

#include <gtest/gtest.h>

#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/language/sequencer.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/symbolic/object_heading.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"
#include "lang2manip/symbolic/task_planner.hpp"
#include "language/language_test_scenes.hpp"
#include "language/language_test_support.hpp"
#include "language/plan_check.hpp"

namespace lang2manip {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Understood {
  TaskSpecification specification;
  Plan plan;
};

Understood understandAndPlan(const Scene& scene, const std::string& instruction) {
  Understood result;
  result.specification = understandInstruction(instruction, describeObjects(scene));
  result.plan = sequenceGoals(result.specification, observeSymbolicState(scene), sequencingOptionsFor(scene));
  return result;
}

/// Where `object`'s origin must go to stand where `owner` stands (base frame, x and y).
Vector3 placeOf(const Scene& scene, const std::string& object, const std::string& owner) {
  const Pose toBase = robotBaseFrame(scene, "").inverse();
  const Vector3 origin = toBase * scene.object(object).pose.translation();
  const Vector3 centre = toBase * scene.object(object).worldBounds().center();
  const Vector3 target = toBase * scene.object(owner).worldBounds().center();
  return origin + target - centre;
}

void expectAtPositionGoal(const Scene& scene, const Goal& goal, const std::string& object, const std::string& owner) {
  EXPECT_EQ(goal.kind, GoalKind::kAtPosition);
  EXPECT_EQ(goal.object, object);
  EXPECT_EQ(goal.target, owner);
  ASSERT_TRUE(goal.position.has_value());
  EXPECT_LT((*goal.position - placeOf(scene, object, owner)).head<2>().norm(), 1e-9);
}

/// The footprint (base frame) of `object` with its origin moved to `origin`.
AlignedBox3 footprintAt(const Scene& scene, const std::string& object, const Vector3& origin) {
  const Pose toBase = robotBaseFrame(scene, "").inverse();
  const AlignedBox3 bounds = scene.object(object).worldBounds().transformed(toBase);
  const Vector3 shift = origin - toBase * scene.object(object).pose.translation();
  return {bounds.min() + Vector3(shift.x(), shift.y(), 0.0), bounds.max() + Vector3(shift.x(), shift.y(), 0.0)};
}

bool overlapInPlan(const AlignedBox3& a, const AlignedBox3& b) {
  return a.min().x() < b.max().x() && b.min().x() < a.max().x() && a.min().y() < b.max().y() && b.min().y() < a.max().y();
}

class OnEveryDesk : public ::testing::Test {
 protected:
  template <typename Check>
  void forEachDesk(Check check) {
    for (const BuiltinProblem& problem : builtinProblems()) {
      SCOPED_TRACE(problem.shortName);
      check(readKauthamProblem(problem.file).scene);
    }
  }
};

TEST_F(OnEveryDesk, SwapsPutEachObjectWhereTheOtherStoodAfterSettingOneAside) {
  const char* phrasings[] = {"swap the marker and the eraser", "exchange the places of the pen and the rubber",
                             "switch the eraser with the marker", "swap the positions of the marker and the eraser",
                             "please trade the places of the eraser and the marker", "swap the eraser and the marker around",
                             "interchange the marker and the eraser"};
  forEachDesk([&](const Scene& scene) {
    for (const char* instruction : phrasings) {
      SCOPED_TRACE(instruction);
      const Understood understood = understandAndPlan(scene, instruction);
      const std::vector<Goal>& goals = understood.specification.goals;
      ASSERT_EQ(goals.size(), 2u) << test::summarize(understood.specification);
      const std::string first = goals[0].object, second = goals[1].object;
      expectAtPositionGoal(scene, goals[0], first, second);
      expectAtPositionGoal(scene, goals[1], second, first);
      // Set one aside, move the other, bring the first: three picks and three places.
      const std::vector<SymbolicAction>& actions = understood.plan.actions;
      ASSERT_EQ(actions.size(), 6u);
      EXPECT_EQ(test::checkPlan(understood.plan, observeSymbolicState(scene), understood.specification), "");
      const SymbolicAction& aside = actions[1];
      ASSERT_TRUE(aside.params.position.has_value());
      const AlignedBox3 spot = footprintAt(scene, aside.object, *aside.params.position);
      for (const std::string& other : {std::string("marker"), std::string("eraser"), std::string("holder")}) {
        if (other == aside.object) continue;
        EXPECT_FALSE(overlapInPlan(spot, footprintAt(scene, other, robotBaseFrame(scene, "").inverse() * scene.object(other).pose.translation())))
            << aside.object << " set aside onto " << other;
      }
      EXPECT_FALSE(overlapInPlan(spot, footprintAt(scene, aside.object, placeOf(scene, aside.object, aside.object))))
          << "set aside where it stood";
    }
  });
}

TEST_F(OnEveryDesk, PuttingAnObjectWhereAnotherStandsSetsThatOneAside) {
  const char* phrasings[] = {"put the marker where the eraser is", "move the marker to where the eraser stands",
                             "place the pen in the place of the rubber", "replace the eraser with the marker",
                             "could you put the marker at the position of the eraser"};
  forEachDesk([&](const Scene& scene) {
    for (const char* instruction : phrasings) {
      SCOPED_TRACE(instruction);
      const Understood understood = understandAndPlan(scene, instruction);
      ASSERT_EQ(understood.specification.goals.size(), 1u) << test::summarize(understood.specification);
      expectAtPositionGoal(scene, understood.specification.goals[0], "marker", "eraser");
      ASSERT_EQ(understood.plan.actions.size(), 4u);
      EXPECT_EQ(understood.plan.actions[0].object, "eraser");
      EXPECT_EQ(understood.plan.actions[3].object, "marker");
      EXPECT_EQ(test::checkPlan(understood.plan, observeSymbolicState(scene), understood.specification), "");
    }
  });
}

TEST_F(OnEveryDesk, TurnsByAnAngleAreReadWithTheirSense) {
  const std::pair<const char*, double> cases[] = {
      {"rotate the eraser by 90 degrees", 90.0},
      {"turn the eraser 90 degrees clockwise", -90.0},
      {"rotate the rubber a quarter turn to the right", -90.0},
      {"turn the marker 45\xc2\xb0", 45.0},
      {"spin the eraser ninety degrees counterclockwise", 90.0},
      {"please rotate the eraser anticlockwise by 30 deg", 30.0},
      {"twist the pen by forty five degrees to the left", 45.0},
      {"rotate the marker 0.5 radians", 0.5 * 180.0 / kPi},
      {"rotate the marker by 120 degrees", 120.0},
      {"turn the eraser sideways", 90.0},
  };
  forEachDesk([&](const Scene& scene) {
    for (const auto& [instruction, degrees] : cases) {
      SCOPED_TRACE(instruction);
      const Understood understood = understandAndPlan(scene, instruction);
      ASSERT_EQ(understood.specification.goals.size(), 1u);
      const Goal& goal = understood.specification.goals[0];
      EXPECT_EQ(goal.kind, GoalKind::kTurned);
      EXPECT_NEAR(goal.angle, degrees * kPi / 180.0, 1e-9);
      // A pick, and a place where it stood, turned.
      ASSERT_EQ(understood.plan.actions.size(), 2u);
      const SymbolicAction& place = understood.plan.actions[1];
      ASSERT_TRUE(place.params.position && place.params.orientation);
      const Pose toBase = robotBaseFrame(scene, "").inverse();
      const SceneObject& object = scene.object(goal.object);
      EXPECT_LT((*place.params.position - toBase * object.pose.translation()).norm(), 1e-9);
      const TurnBetween turn = turnBetween(toBase.linear() * object.pose.linear(), place.params.orientation->toRotationMatrix());
      EXPECT_NEAR(reducedAngle(turn.yaw - goal.angle, 2.0 * kPi), 0.0, 1e-6);
      EXPECT_NEAR(turn.tilt, 0.0, 1e-6);
    }
  });
}

TEST_F(OnEveryDesk, PointingTurnsTheLongSideTowardTheTarget) {
  const std::pair<const char*, const char*> cases[] = {
      {"point the marker at the holder", "holder"},     {"orient the pen toward the cup", "holder"},
      {"turn the marker to face the eraser", "eraser"}, {"aim the marker at the holder", "holder"},
      {"rotate the marker so that it points at the eraser", "eraser"}, {"point the eraser towards the marker", "marker"},
  };
  forEachDesk([&](const Scene& scene) {
    const SequencingOptions options = sequencingOptionsFor(scene);
    for (const auto& [instruction, target] : cases) {
      SCOPED_TRACE(instruction);
      const Understood understood = understandAndPlan(scene, instruction);
      ASSERT_EQ(understood.specification.goals.size(), 1u);
      const Goal& goal = understood.specification.goals[0];
      EXPECT_EQ(goal.kind, GoalKind::kFacing);
      EXPECT_EQ(goal.target, target);
      ASSERT_EQ(understood.plan.actions.size(), 2u);
      const SymbolicAction& place = understood.plan.actions[1];
      ASSERT_TRUE(place.params.orientation.has_value());
      // The long side after the turn points along the line between the centres.
      const ObjectLayout& mine = options.layout.at(goal.object);
      const TurnBetween turn = turnBetween(mine.orientation.toRotationMatrix(), place.params.orientation->toRotationMatrix());
      const Vector3 toward = options.layout.at(target).bounds.center() - mine.bounds.center();
      const double side = *mine.longSideYaw + turn.yaw;
      EXPECT_NEAR(reducedAngle(std::atan2(toward.y(), toward.x()) - side, kPi), 0.0, 1e-6);
      EXPECT_LE(std::abs(turn.yaw), kPi / 2.0 + 1e-9) << "the smaller turn";
    }
  });
}

TEST_F(OnEveryDesk, TurnsThatChangeNothingAndPointingWithoutALongSideAreRefusedWithTheReason) {
  const std::pair<const char*, const char*> cases[] = {
      {"turn the eraser around", "leaves it looking the same: its shape repeats every 180 deg"},
      {"rotate the eraser by 180 degrees", "repeats every 180 deg"},
      {"rotate the holder by 90 degrees", "repeats every 90 deg"},
      {"turn the marker", "say how far to turn it"},
      {"rotate the marker by 360 degrees", "a full turn"},
      {"rotate the eraser by 0 degrees", "a turn of zero"},
      {"point the holder at the marker", "holder has no long side to point with"},
      {"point the marker at the marker", "cannot"},
      {"swap the marker", "exactly two objects"},
      {"swap the marker and the eraser and the holder", "exactly two objects"},
      {"put the marker where the marker is", "itself"},
      {"put the marker and the eraser where the holder is", "only one object can stand where holder stands"},
      {"replace the eraser", "say what to replace it with"},
      {"point the marker", "say what to point it at"},
  };
  forEachDesk([&](const Scene& scene) {
    for (const auto& [instruction, reason] : cases) {
      SCOPED_TRACE(instruction);
      try {
        const Understood understood = understandAndPlan(scene, instruction);
        ADD_FAILURE() << "planned: " << test::summarize(understood.specification);
      } catch (const PlanningError& error) {
        EXPECT_NE(std::string(error.what()).find(reason), std::string::npos) << error.what();
      }
    }
  });
}

TEST(Rearrangement, AnObjectSetAsideLeavesTheSpotsOfEveryGoalFree) {
  // Three objects in a row: the marker goes where the eraser is; the eraser's free spot must not
  // be the marker's future place nor overlap the holder.
  for (const BuiltinProblem& problem : builtinProblems()) {
    SCOPED_TRACE(problem.shortName);
    const Scene scene = readKauthamProblem(problem.file).scene;
    SequencingOptions options = sequencingOptionsFor(scene);
    const TaskSpecification specification = understandInstruction("put the marker where the eraser is", describeObjects(scene));
    std::vector<Vector3> spots;
    for (int skipped = 0; skipped < 3; ++skipped) {
      options.skippedSpots["eraser"] = skipped;
      const Plan plan = sequenceGoals(specification, observeSymbolicState(scene), options);
      ASSERT_TRUE(plan.actions[1].params.position.has_value());
      const Vector3 spot = *plan.actions[1].params.position;
      for (const Vector3& earlier : spots) EXPECT_GE((spot - earlier).head<2>().norm(), 0.05) << "the next spot is another one";
      spots.push_back(spot);
      const AlignedBox3 aside = footprintAt(scene, "eraser", spot);
      const AlignedBox3 wanted = footprintAt(scene, "marker", *specification.goals[0].position);
      EXPECT_FALSE(overlapInPlan(aside, wanted));
    }
  }
}

TEST(Rearrangement, ATurnSplitIntoStepsRegraspsBetweenThem) {
  const Scene scene = test::deskScene();
  SequencingOptions options = sequencingOptionsFor(scene);
  options.turnSteps["eraser"] = 2;
  const TaskSpecification specification = understandInstruction("rotate the eraser by 90 degrees", describeObjects(scene));
  const Plan plan = sequenceGoals(specification, observeSymbolicState(scene), options);
  ASSERT_EQ(plan.actions.size(), 4u);
  const Matrix3 start = options.layout.at("eraser").orientation.toRotationMatrix();
  EXPECT_NEAR(turnBetween(start, plan.actions[1].params.orientation->toRotationMatrix()).yaw, kPi / 4.0, 1e-9);
  EXPECT_NEAR(turnBetween(start, plan.actions[3].params.orientation->toRotationMatrix()).yaw, kPi / 2.0, 1e-9);
}

}  // namespace
}  // namespace lang2manip
