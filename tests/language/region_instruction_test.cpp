// Regions of a support's top in instructions (issue 23): corners, edges and sides, the middle,
// halves and quadrants, "top/bottom" as far/near, a corner chosen by an object, a side of an object
// as a relation beside it, stacks in a region, and the refusals. On the built-in Panda desk
// (reachable part of the desk, base frame: x [0.22, 0.60], y [-0.40, 0.40]).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/symbolic/task_planner.hpp"
#include "language/language_test_scenes.hpp"
#include "language/language_test_support.hpp"
#include "language/plan_check.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;

const std::pair<const char*, const char*> kRegions[] = {
    {"put the eraser in the far left corner of the desk", "eraser on desk (far left corner)"},
    {"move the marker to the top right corner of the table", "marker on desk (far right corner)"},
    {"place the eraser at the bottom left corner", "eraser on desk (near left corner)"},
    {"put the marker in the lower right-hand corner", "marker on desk (near right corner)"},
    {"put the eraser in the upper right", "eraser on desk (far right corner)"},
    {"put the eraser on the bottom side of the table", "eraser on desk (near edge)"},
    {"move the marker along the right edge", "marker on desk (right edge)"},
    {"put the eraser at the far end of the desk", "eraser on desk (far edge)"},
    {"move the eraser to the middle of the desk", "eraser on desk (centre)"},
    {"put the marker in the centre", "marker on desk (centre)"},
    {"put the eraser in the left half of the table", "eraser on desk (left half)"},
    {"put the marker in the top right quadrant", "marker on desk (far right quadrant)"},
    {"put the eraser on the desk in its bottom right corner", "eraser on desk (near right corner)"},
    {"put the eraser in a corner", "eraser on desk (near left corner)"},
    {"put the eraser in the corner closest to the holder", "eraser on desk (far left corner)"},
    {"put the eraser in the closest corner to the marker", "eraser on desk (near right corner)"},
    {"put the marker in the corner farthest from the eraser", "marker on desk (far right corner)"},
    {"put the marker in the left corner closest to the robot", "marker on desk (near left corner)"},
    {"put the eraser on the left side of the holder", "eraser left of holder"},
    {"put the marker on the far side of the holder", "marker in front of holder"},
    {"put the eraser in the top left corner, then the marker in the bottom right corner",
     "eraser on desk (far left corner); marker on desk (near right corner)"},
    {"put the marker and the eraser in the bottom left corner", "marker on desk (near left corner); eraser on desk (near left corner)"},
};

TEST(RegionInstructions, CornersEdgesTheMiddleHalvesAndQuadrantsAreUnderstoodAndPlanned) {
  test::expectUnderstoodAndPlanned(test::deskScene(), kRegions);
}

TEST(RegionInstructions, TheRegionReachesThePlaceAction) {
  const TaskSpecification specification = understandInstruction("put the eraser in the top left corner", describeObjects(test::deskScene()));
  ASSERT_EQ(specification.goals.size(), 1u);
  ASSERT_TRUE(specification.goals.front().region);
  EXPECT_EQ(surfaceRegionName(*specification.goals.front().region), "far_left_corner");
}

TEST(RegionInstructions, StacksGoInARegionWithTheirLowestObject) {
  const TaskSpecification specification =
      understandInstruction("stack the red block and the blue block in the top left corner of the table", describeObjects(test::workbenchScene()));
  EXPECT_EQ(test::summarize(specification), "red_block on table (far left corner); blue_block on red_block");
}

std::string refusal(const std::string& instruction) {
  try {
    (void)understandInstruction(instruction, describeObjects(test::deskScene()));
  } catch (const PlanningError& error) {
    return error.what();
  }
  return "not refused";
}

TEST(RegionInstructions, RegionsOfWhatIsNoSupportAndContradictoryRegionsAreRefused) {
  EXPECT_THAT(refusal("put the eraser in the corner of the marker"), HasSubstr("marker is not a table or desk"));
  EXPECT_THAT(refusal("put the marker in the middle of the holder"), HasSubstr("holder is not a table or desk"));
  EXPECT_THAT(refusal("put the marker in the top left corner and in the bottom right corner"),
              HasSubstr("it contradicts itself: marker on desk (far left corner) and marker on desk (near right corner) cannot both hold"));
  EXPECT_THAT(refusal("put the eraser in the left half and in the right half of the desk"), HasSubstr("it contradicts itself"));
  EXPECT_THAT(refusal("put the eraser in the corner closest to"), HasSubstr("expected an object after"));
}

}  // namespace
}  // namespace lang2manip
