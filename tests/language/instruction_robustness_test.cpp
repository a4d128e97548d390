// Word salads and odd inputs: the offline planner either understands them or refuses with a
// PlanningError -- never another exception, a crash or a hang.

#include <gtest/gtest.h>

#include "lang2manip/core/random.hpp"
#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "language/language_test_scenes.hpp"

namespace lang2manip {
namespace {

const std::vector<std::string> kWords{
    "put", "the", "marker", "eraser", "holder", "in", "on", "and", "then", ",", "it", "them",
    "all", "both", "other", "one", "5", "cm", "to", "left", "of", "right", "push", "nudge",
    "stack", "blocks", "red", "blue", "big", "smallest", "go", "home", "with", "a", "side",
    "grasp", "using", "RRT*", "planner", "pick", "up", "down", "back", "there", "from", "cup",
    "box", "every", "the other one", "next to", "in front of", "behind", "please", ".", "first",
    "by", "2.5", "three", "marker_1", "table", "desk", "into", "onto", "top", "forward", "away"};

std::string randomInstruction(Random& random) {
  const std::uint64_t length = 1 + random.index(12);
  std::string text;
  for (std::uint64_t i = 0; i < length; ++i) text += kWords[random.index(kWords.size())] + " ";
  return text;
}

TEST(InstructionRobustnessTest, WordSaladIsUnderstoodOrRefusedNeverAnythingElse) {
  const Scene desk = test::deskScene();
  const Scene workbench = test::workbenchScene();
  OfflineTaskPlanner planner;
  Random random(20261124);
  int understood = 0;
  int refused = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    PlanningRequest request;
    request.task = randomInstruction(random);
    request.scene = trial % 2 == 0 ? &desk : &workbench;
    SCOPED_TRACE(request.task);
    PlanningStatistics statistics;
    try {
      (void)planner.plan(request, StopCondition::never(), statistics);
      ++understood;
    } catch (const PlanningError& error) {
      EXPECT_GT(std::string(error.what()).size(), 10u);
      ++refused;
    } catch (const std::exception& error) {
      ADD_FAILURE() << "unexpected exception: " << error.what();
    }
  }
  EXPECT_GT(refused, 0);
  EXPECT_GT(understood, 0);
}

TEST(InstructionRobustnessTest, OddCharactersAndLongInputs) {
  const std::vector<ObjectDescriptor> objects = describeObjects(test::deskScene());
  const std::vector<std::string> inputs{
      "put the marker in the holder!!!", "PUT THE MARKER IN THE HOLDER",
      "put\tthe\nmarker in the holder", "put the marker in the holder ;;; ...",
      "put the \"marker\" in the (holder)"};
  for (const std::string& input : inputs) {
    SCOPED_TRACE(input);
    EXPECT_EQ(understandInstruction(input, objects).goals.size(), 1u);
  }
  EXPECT_THROW((void)understandInstruction("put the m\xc3\xa4rker in the holder", objects),
               PlanningError);
  EXPECT_THROW((void)understandInstruction(std::string(1, '\0'), objects), PlanningError);
  std::string longTask;
  for (int i = 0; i < 200; ++i) longTask += "put the marker in the holder, then ";
  longTask += "go home";
  // 200 placements of the same object are one final state, then home.
  EXPECT_EQ(understandInstruction(longTask, objects).goals.size(), 2u);
  EXPECT_THROW((void)understandInstruction("put the marker in the holder", {}), PlanningError);
}

}  // namespace
}  // namespace lang2manip
