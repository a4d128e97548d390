// Objects named by quantity, property or place (issue 15, class 3): "both", "all the movable
// objects", superlatives of size, height and length, "on the left", "to the left of X",
// "closest to X", "farthest from you". The destination is never among the objects moved.
// Checked on the desk of every built-in robot; what names nothing is refused with the reason.

#include <gtest/gtest.h>

#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/language/sequencer.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"
#include "lang2manip/symbolic/task_planner.hpp"
#include "language/language_test_support.hpp"
#include "language/plan_check.hpp"

namespace lang2manip {
namespace {

// On every desk: the marker lies to the right of the holder and farther from it, the eraser to
// its left and nearer; the marker is the longest and largest movable object, the holder the
// tallest object.
const std::pair<const char*, const char*> kReferences[] = {
    {"put both objects in the holder", "marker in holder; eraser in holder"},
    {"put both in the holder", "marker in holder; eraser in holder"},
    {"put the two objects into the holder", "marker in holder; eraser in holder"},
    {"put all the movable objects in the holder", "marker in holder; eraser in holder"},
    {"put every object on the desk in the holder", "marker in holder; eraser in holder"},
    {"put everything that is on the desk into the holder", "marker in holder; eraser in holder"},
    {"put the largest object in the holder", "marker in holder"},
    {"put the biggest movable object in the holder", "marker in holder"},
    {"put the longest object in the holder", "marker in holder"},
    {"put the largest object on the desk in the holder", "marker in holder"},
    {"put the smallest object in the holder", "eraser in holder"},
    {"put the object on the left in the holder", "eraser in holder"},
    {"put the thing on the right into the holder", "marker in holder"},
    {"put the object to the left of the holder in the holder", "eraser in holder"},
    {"put the object that is right of the holder in the holder", "marker in holder"},
    {"put the item closest to the eraser into the holder", "marker in holder"},
    {"pick up the object that is left of the holder", "holding eraser"},
    {"place the object farthest away from the eraser next to the holder", "marker next to holder"},
    {"put the tallest object next to the marker", "holder next to marker"},
    {"put everything except the eraser in the holder", "marker in holder"},
    {"put all the objects but the marker into the holder", "eraser in holder"},
    {"put everything other than the holder in the holder", "marker in holder; eraser in holder"},
};

/// Of the marker and the eraser, the one whose box is nearer to (or farther from) the holder's.
std::string byGapToHolder(const Scene& scene, bool nearest) {
  const AlignedBox3 holder = scene.object("holder").worldBounds();
  const double marker = boxGap(scene.object("marker").worldBounds(), holder);
  const double eraser = boxGap(scene.object("eraser").worldBounds(), holder);
  return (marker < eraser) == nearest ? "marker" : "eraser";
}

TEST(ObjectReferences, QuantifiersSuperlativesAndPlacesOnEveryBuiltInDesk) {
  for (const BuiltinProblem& problem : builtinProblems()) {
    SCOPED_TRACE(problem.shortName);
    const Scene scene = readKauthamProblem(problem.file).scene;
    test::expectUnderstoodAndPlanned(scene, kReferences);
    // The desks differ in which object lies nearer to the holder.
    const std::pair<const char*, bool> byDistance[] = {{"put the object closest to the holder in the holder", true},
                                                      {"put the thing nearest to the holder into the holder", true},
                                                      {"put the object farthest from the holder in the holder", false},
                                                      {"drop the item that is furthest away from the holder into the holder", false}};
    for (const auto& [instruction, nearest] : byDistance) {
      SCOPED_TRACE(instruction);
      EXPECT_EQ(test::summarize(understandInstruction(instruction, describeObjects(scene))),
                byGapToHolder(scene, nearest) + " in holder");
    }
  }
}

TEST(HandingOver, EveryPhrasingHoldsTheObjectOutOnEveryBuiltInDesk) {
  const std::pair<const char*, const char*> handovers[] = {
      {"hand me the marker", "marker handed over"},
      {"give the eraser to me", "eraser handed over"},
      {"hand over the marker", "marker handed over"},
      {"pass me the eraser", "eraser handed over"},
      {"give me the longest object", "marker handed over"},
      {"hand the marker over to the user", "marker handed over"},
      {"please give the person the eraser", "eraser handed over"},
      {"put the eraser in the holder, then hand me the marker", "eraser in holder; marker handed over"},
      {"hand me the marker, then put it in the holder", "marker in holder"},
  };
  for (const BuiltinProblem& problem : builtinProblems()) {
    SCOPED_TRACE(problem.shortName);
    const Scene scene = readKauthamProblem(problem.file).scene;
    test::expectUnderstoodAndPlanned(scene, handovers);
  }
  const Scene scene = readKauthamProblem(resolveProblem("panda_desk")).scene;
  for (const auto& [instruction, fragment] : {std::pair{"give the marker to the holder", "a handover goes to a person"},
                                              std::pair{"hand me the marker and the eraser", "one object at a time"}}) {
    SCOPED_TRACE(instruction);
    try {
      (void)understandInstruction(instruction, describeObjects(scene));
      ADD_FAILURE() << "understood";
    } catch (const PlanningError& error) {
      EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
    }
  }
}

TEST(ObjectReferences, TheRobotIsAReferenceToo) {
  const Scene scene = readKauthamProblem(resolveProblem("panda_desk")).scene;
  // Panda desk, base frame: the eraser's nearest corner is 0.389 m from the base, the marker's 0.394 m.
  EXPECT_EQ(test::summarize(understandInstruction("put the object nearest to the robot in the holder", describeObjects(scene))),
            "eraser in holder");
  EXPECT_EQ(test::summarize(understandInstruction("put the object farthest from you in the holder", describeObjects(scene))),
            "marker in holder");
  EXPECT_EQ(test::summarize(understandInstruction("put the object to the left of the robot in the holder", describeObjects(scene))),
            "eraser in holder");
}

TEST(ObjectReferences, AReferenceToNothingIsRefusedWithTheReason) {
  const Scene scene = readKauthamProblem(resolveProblem("panda_desk")).scene;
  const std::pair<const char*, const char*> refusals[] = {
      {"put the object next to the marker in the holder", "no object is next to marker"},
      {"put the objects in front of the holder in the holder", "no object is in front of holder"},
      {"put the object closest to the cactus in the holder", "could not ground \"the cactus\""},
      {"put the object in the holder", "it is ambiguous: it could be marker or eraser"},
  };
  for (const auto& [instruction, fragment] : refusals) {
    SCOPED_TRACE(instruction);
    try {
      const TaskSpecification specification = understandInstruction(instruction, describeObjects(scene));
      ADD_FAILURE() << "understood as " << test::summarize(specification);
    } catch (const PlanningError& error) {
      EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
    }
  }
}

}  // namespace
}  // namespace lang2manip
