// Instructions the offline planner must refuse, each with the words its message must name.

#include <gtest/gtest.h>

#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/symbolic/task_planner.hpp"
#include "language/language_test_scenes.hpp"

namespace lang2manip {
namespace {

using test::SceneId;
using test::descriptorsFor;
using test::D;
using test::W;

struct Refusal {
  SceneId scene;
  const char* instruction;
  const char* messageFragment;
};


const Refusal kRefusals[] = {
    // Contradictions: both requests named, nothing planned.
    {D, "put the marker in the holder and keep it on the desk",
     "it contradicts itself: it asks for marker in holder and to keep marker on desk"},
    {D, "put the marker in the holder and on the desk", "it contradicts itself: marker in holder and marker on desk cannot both hold"},
    {D, "put the eraser on the desk and into the holder", "it contradicts itself: eraser on desk and eraser in holder cannot both hold"},
    {D, "put the marker to the left of the holder and to the right of the holder",
     "marker left of holder and marker right of holder cannot both hold"},
    {D, "place the eraser in front of the holder and behind the holder", "eraser in front of holder and eraser behind holder cannot both hold"},
    {D, "put the eraser in the holder and leave the eraser where it is",
     "it asks for eraser in holder and to leave eraser where it is"},
    {D, "move the marker 5 cm to the left and leave it alone", "it asks for marker displaced by"},
    {D, "keep the marker on the desk", "it asks for nothing the robot could do"},
    {D, "put the bottle in the holder",
     "could not ground \"the bottle\": no object matches (objects: desk, marker, eraser, holder)"},
    {D, "put the marker in the box", "could not ground \"the box\": no object matches"},
    {D, "put the red marker in the holder",
     "could not ground \"the red marker\": no object matches; by its noun it could only be marker (blue)"},
    {D, "put the wooden cup on the desk", "could not ground \"the wooden cup\""},
    {D, "flip the marker over", "\"flip\" is not an action the offline planner knows"},
    {D, "don't move the marker", "could not ground \"don't\""},
    {D, "do not touch the eraser", "could not ground \"do\""},
    {D, "put everything in the holder except the eraser", "could not ground \"except the eraser\""},
    {D, "put the marker in the holder but not the eraser", "could not ground \"but\""},
    {D, "put the marker or the eraser in the holder", "could not ground \"or\""},
    {D, "if the holder is empty put the marker in it", "could not ground \"if\""},
    {D, "what is on the desk?", "it is a question, not an instruction"},
    {D, "where is the marker", "it is a question"},
    {D, "", "the task is empty"},
    {D, "  please  ", "it asks for nothing the robot could do"},
    {D, "put the marker", "could not ground \"put the marker\": say where to put it"},
    {D, "insert the eraser", "say where to insert it"},
    {D, "push the eraser to the left", "say how far (e.g. \"5 cm to the left\")"},
    {D, "put the marker in the eraser", "eraser is not a container"},
    {D, "put the holder in the holder", "cannot relate holder to itself"},
    {D, "put the marker in the holder using the FooBar planner",
     "unknown motion planner \"foobar\" (known: RRTConnect"},
    {D, "put the marker in the holder upside down", "could not ground \"upside down\""},
    {D, "put the marker in the holder quickly and upside down", "could not ground"},
    {D, "pick up the marker and the eraser", "cannot hold marker and eraser at once"},
    {D, "go to the window", "the only place to go is home"},
    {D, "stack the marker", "stacking needs at least two objects"},
    {D, "put it in the holder", "could not ground \"it\": nothing was mentioned before"},
    {D, "put the eraser 5 cm in the holder", "a distance cannot go with \"in\""},
    {D, "put the marker next to", "expected an object after \"next to\""},
    {D, "put in the holder", "expected the object(s) to put"},
    {D, "put the marker in the holder and the", "could not ground \"and the\""},
    {W, "put the marker in the box",
     "could not ground \"the marker\": it is ambiguous: it could be marker_1 or marker_2"},
    {W, "put the block in the box",
     "it is ambiguous: it could be red_block, blue_block or green_block"},
    {W, "put both blocks in the box", "2 objects were meant but 3 match"},
    {W, "put the purple block in the box", "could not ground \"the purple block\""},
    {W, "put the red block on the red block", "cannot relate red_block to itself"},
    {W, "put the cup in the box", "it is ambiguous: it could be white_cup or yellow_cup"},
    {W, "put the block in the white cup, then the other", "could not ground \"the block\""},
    {W, "put the small block in the box", "it is ambiguous: it could be red_block or blue_block"},
    {W, "put the blocks in the red block", "red_block is not a container"},
    {W, "put the blocks on the table and the cups next to", "expected an object after \"next to\""},
    {D, "put the eraser in", "expected an object after \"in\""},
    {W, "put the red block on the blue block, then put the green block on the other one",
     "could not ground \"the other one\": there is no other one: already mentioned"},
    {D, "pick up the marker and do the same with the eraser",
     "could not ground \"do the same with\": the previous step has no place to repeat"},
    {D, "put the marker in the holder and do the same with the holder",
     "cannot relate holder to itself"},
    {W, "put the marker_1 in the cups", "a relation needs one target object"},
};

TEST(InstructionRefusalTest, EveryRefusalNamesTheWordsItCouldNotGround) {
  for (const Refusal& refusal : kRefusals) {
    SCOPED_TRACE(refusal.instruction);
    try {
      const TaskSpecification specification =
          understandInstruction(refusal.instruction, descriptorsFor(refusal.scene));
      ADD_FAILURE() << "understood as " << specification.goals.size() << " goals";
    } catch (const PlanningError& error) {
      EXPECT_NE(std::string(error.what()).find(refusal.messageFragment), std::string::npos)
          << error.what();
    }
  }
}

TEST(InstructionRefusalTest, GroundingFailuresSuggestAnLlmBackend) {
  try {
    (void)understandInstruction("put the bottle in the holder", descriptorsFor(D));
    FAIL() << "expected PlanningError";
  } catch (const PlanningError& error) {
    EXPECT_NE(std::string(error.what()).find("try an LLM backend with --llm"), std::string::npos);
  }
}

}  // namespace
}  // namespace lang2manip
