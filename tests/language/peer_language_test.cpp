// The language of VIMA-Bench and LIBERO (issue 23, classes 4 and 6) on the workbench scene
// (red_block, blue_block and green_block at x = 0.3, y = 0.2, 0, -0.2; a white and a yellow cup;
// a box; a red and a black marker): objects between two others, objects with the same property
// as another and "into it", "the same bowl", where an object stood before ("the block that was to
// its left"), and towers in a given order; with the refusals of each.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/symbolic/task_planner.hpp"
#include "language/language_test_scenes.hpp"
#include "language/language_test_support.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;

std::string peerMeaningIn(const Scene& scene, const std::string& instruction) {
  try {
    return test::summarize(understandInstruction(instruction, describeObjects(scene)));
  } catch (const PlanningError& error) {
    return std::string("refused: ") + error.what();
  }
}
std::string peerMeaning(const std::string& instruction) { return peerMeaningIn(test::workbenchScene(), instruction); }

TEST(PeerLanguage, AnObjectBetweenTwoOthersIsTheOneOnTheSegmentJoiningThem) {
  EXPECT_EQ(peerMeaning("put the block between the red block and the green block in the box"), "blue_block in box");
  EXPECT_EQ(peerMeaning("pick up the block in between the green block and the red block and place it in the white cup"), "blue_block in white_cup");
  EXPECT_THAT(peerMeaning("put the marker between the red block and the green block in the box"), HasSubstr("nothing of that kind stands between them"));
  Scene crowded = test::workbenchScene();
  crowded.object("marker_1").pose.translation().head<2>() = Eigen::Vector2d(0.3, 0.1);
  EXPECT_THAT(peerMeaningIn(crowded, "put the object between the red block and the green block in the box"), HasSubstr("it is ambiguous"));
  // With one object of its kind, "between" is where it goes, not which one it is.
  EXPECT_THAT(peerMeaning("put the white cup between the red block and the box"), ::testing::StartsWith("white_cup at ("));
}

TEST(PeerLanguage, ObjectsWithTheSamePropertyAsAnotherAndIntoIt) {
  EXPECT_EQ(peerMeaning("put all objects with the same colour as the red block into the box"), "marker_1 in box");
  EXPECT_EQ(peerMeaning("put every object that has the same color as the red block in the white cup"), "marker_1 in white_cup");
  EXPECT_EQ(peerMeaning("put all objects of the same kind as the white cup into it"), "yellow_cup in white_cup");
  EXPECT_THAT(peerMeaning("put all objects with the same colour as the yellow cup into the box"), HasSubstr("nothing else has the same colour as yellow_cup"));
}

TEST(PeerLanguage, WhereAnObjectStoodBeforeAndTheSameContainer) {
  EXPECT_EQ(peerMeaning("first put the blue block into the box, then put the block that was previously to its left into the same box"),
            "blue_block in box; red_block in box");
  EXPECT_EQ(peerMeaning("put the blue block in the white cup and then put the block that was to its right before in the same cup"),
            "blue_block in white_cup; green_block in white_cup");
  EXPECT_THAT(peerMeaning("put the red block in the box, then put the block that was to its left into the same box"), HasSubstr("no object is left of red_block"));
  EXPECT_THAT(peerMeaning("put the blue block in the box, then put the object that was to its left into the same box"), HasSubstr("it is ambiguous"));
  EXPECT_THAT(peerMeaning("put the same cup in the box"), HasSubstr("nothing of that kind was named before"));
}

TEST(PeerLanguage, TowersInAGivenOrder) {
  EXPECT_EQ(peerMeaning("stack the blocks in this order from the bottom: green, red, blue"), "red_block on green_block; blue_block on red_block");
  EXPECT_EQ(peerMeaning("stack the blocks in the following order from the top: green, red, blue"), "red_block on blue_block; green_block on red_block");
  EXPECT_EQ(peerMeaning("build a tower with the green block at the bottom, then the blue block, then the red block on top"),
            "blue_block on green_block; red_block on blue_block");
  EXPECT_EQ(peerMeaning("build a tower with the red block on top, then the blue block, then the green block"),
            "blue_block on green_block; red_block on blue_block");
  EXPECT_THAT(peerMeaning("stack the blocks in this order: green, purple, blue"), HasSubstr("refused"));
}

}  // namespace
}  // namespace lang2manip
