// The tabletop benchmarks' language (issue 23) on the workbench scene (red_block, blue_block and
// green_block at y = 0.2, 0, -0.2; a white and a yellow cup; a box; two markers): ordinals, per-object
// assignments by colour and by corner, stacks "on top of each other", open dishes, and refusals.

#include <algorithm>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/symbolic/surface_region.hpp"
#include "lang2manip/symbolic/task_planner.hpp"
#include "language/language_test_scenes.hpp"
#include "language/language_test_support.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::string meaning(const std::string& instruction) {
  try {
    return test::summarize(understandInstruction(instruction, describeObjects(test::workbenchScene())));
  } catch (const PlanningError& error) {
    return std::string("refused: ") + error.what();
  }
}

TEST(TabletopLanguage, OrdinalsCountAlongTheBaseFrame) {
  EXPECT_EQ(meaning("put the second block from the left in the box"), "blue_block in box");
  EXPECT_EQ(meaning("put the first block from the right in the box"), "green_block in box");
  EXPECT_EQ(meaning("pick up the last block from the left and put it in the box"), "green_block in box");
  EXPECT_EQ(meaning("put the middle block in the box"), "blue_block in box");
  // "from the top" after an ordinal is where it counts from, not a top grasp.
  EXPECT_EQ(meaning("put the red block next to the first object from the top"), "red_block next to box");
  EXPECT_EQ(meaning("pick up the red block from the top and put it in the box"), "red_block in box | grasp red_block=top");
  EXPECT_EQ(meaning("put the third block counting from the right in the box"), "red_block in box");
  EXPECT_THAT(meaning("put the fourth block from the left in the box"), HasSubstr("there are only 3"));
  EXPECT_THAT(meaning("put the middle marker in the box"), HasSubstr("there is no middle one of 2"));
  EXPECT_THAT(meaning("put the second block in the box"), HasSubstr("counted from where? say \"from the left\""));
}

TEST(TabletopLanguage, AssignmentsByColourAreAMatchingOverTheObjects) {
  EXPECT_EQ(meaning("put the blocks in the cups with mismatched colours"),
            "red_block in white_cup; blue_block in yellow_cup; green_block in yellow_cup");
  EXPECT_EQ(meaning("put the red block in the cup of a different colour"), "red_block in white_cup");
  EXPECT_THAT(meaning("put the blocks in the cups with matching colours"),
              HasSubstr("no matching place for red_block (red) among white_cup, yellow_cup"));
  EXPECT_THAT(meaning("sort the blocks into the cups by colour"), HasSubstr("no matching place for red_block"));
}

TEST(TabletopLanguage, DifferentCornersGiveEachObjectACornerOfItsOwn) {
  EXPECT_EQ(meaning("put the markers in different corners of the table"),
            "marker_1 on table (far left corner); marker_2 on table (far right corner)");
  EXPECT_EQ(meaning("put the blocks in separate corners"),
            "red_block on table (far left corner); blue_block on table (near left corner); green_block on table (far right corner)");
  EXPECT_THAT(meaning("put all the movable objects in different corners"), HasSubstr("objects cannot each have a corner of their own: table has 4"));
}

TEST(TabletopLanguage, OneObjectInEachPlaceIsADistributiveAssignment) {
  // "one X in each Y": every Y gets an X of its own, the X chosen so that they move least.
  EXPECT_EQ(meaning("put one marker in each cup"), "marker_1 in white_cup; marker_2 in yellow_cup");
  EXPECT_EQ(meaning("put a marker in every cup"), "marker_1 in white_cup; marker_2 in yellow_cup");
  const std::string twoOfThree = meaning("put a block in each cup");
  EXPECT_THAT(twoOfThree, HasSubstr("white_cup"));
  EXPECT_THAT(twoOfThree, HasSubstr("yellow_cup"));
  EXPECT_EQ(std::count(twoOfThree.begin(), twoOfThree.end(), ';'), 1) << twoOfThree;
  EXPECT_THAT(meaning("put one block in each corner"), HasSubstr("3 objects for the 4 corners of table"));
  EXPECT_THAT(meaning("put a cup in each corner of the table"), HasSubstr("2 objects for the 4 corners of table"));
  const std::string fourOfMany = meaning("put a movable object in each corner");
  for (const char* corner : {"far left corner", "far right corner", "near left corner", "near right corner"}) {
    EXPECT_THAT(fourOfMany, HasSubstr(corner));
  }
  EXPECT_EQ(std::count(fourOfMany.begin(), fourOfMany.end(), ';'), 3) << fourOfMany;
  EXPECT_THAT(meaning("put one block per cup"), Not(HasSubstr("refused")));
  EXPECT_THAT(meaning("put one cup in each block"), HasSubstr("refused"));
  // A named object stays one object: "the block in each cup" is not distributive.
  EXPECT_THAT(meaning("put the red block in each cup"), HasSubstr("refused"));
}

TEST(TabletopLanguage, ACornerLeftOpenIsOneWithRoomForTheObject) {
  // The holder stands in the desk's far left corner and fills it.
  std::vector<ObjectDescriptor> objects = describeObjects(test::deskScene());
  const auto named = [&](const std::string& name) -> ObjectDescriptor& {
    return *std::find_if(objects.begin(), objects.end(), [&](const ObjectDescriptor& o) { return o.name == name; });
  };
  const AlignedBox3 corner = regionBox(*named("desk").reachableTop, {SurfaceRegion::Kind::kCorner, 1, 1});
  ObjectDescriptor& holder = named("holder");
  const Vector3 shift(corner.center().x() - holder.position.x(), corner.center().y() - holder.position.y(), 0.0);
  holder.position += shift;
  holder.origin += shift;
  holder.bounds = AlignedBox3(holder.bounds.min() + shift, holder.bounds.max() + shift);
  holder.bounds.extend(Vector3(corner.min().x(), corner.min().y(), holder.bounds.min().z()));
  holder.bounds.extend(Vector3(corner.max().x(), corner.max().y(), holder.bounds.max().z()));
  const auto summary = [&](const std::string& instruction) { return test::summarize(understandInstruction(instruction, objects)); };
  EXPECT_THAT(summary("put the eraser in the corner closest to the holder"), Not(HasSubstr("far_left_corner")));
  EXPECT_THAT(summary("put the eraser in a corner"), Not(HasSubstr("far_left_corner")));
  EXPECT_THAT(summary("put the marker and the eraser in different corners"), Not(HasSubstr("far_left_corner")));
  // Asked for by name, it is that corner (grounding then says it is taken).
  EXPECT_EQ(summary("put the eraser in the far left corner"), "eraser on desk (far left corner)");
}

TEST(TabletopLanguage, HalfwayToAnObjectIsTheMiddleOfWhereItStandsAndTheObject) {
  const std::vector<ObjectDescriptor> objects = describeObjects(test::deskScene());
  const TaskSpecification halfway = understandInstruction("move the eraser halfway to the holder", objects);
  ASSERT_EQ(halfway.goals.size(), 1u);
  ASSERT_EQ(halfway.goals.front().kind, GoalKind::kAtPosition);
  const auto centre = [&](const std::string& name) {
    return std::find_if(objects.begin(), objects.end(), [&](const ObjectDescriptor& o) { return o.name == name; })->position;
  };
  const Vector3 middle = (centre("eraser") + centre("holder")) / 2.0;
  EXPECT_NEAR(halfway.goals.front().position->x(), middle.x(), 1e-6);
  EXPECT_NEAR(halfway.goals.front().position->y(), middle.y(), 1e-6);
  EXPECT_THROW((void)understandInstruction("move the eraser and the marker halfway to the holder", objects), PlanningError);
}

TEST(TabletopLanguage, StacksOnTopOfEachOtherAndOpenDishes) {
  EXPECT_EQ(meaning("stack the red block and the blue block on top of each other"), "blue_block on red_block");
  EXPECT_EQ(meaning("make a tower of the red and the blue block"), "blue_block on red_block");
  EXPECT_EQ(meaning("put the red block on the box"), "red_block in box");  // an open dish: what is on it is in it
  EXPECT_THAT(meaning("put the red block on top of the white cup"), HasSubstr("red_block on white_cup"));
}

TEST(TabletopLanguage, VagueAmountsAreGapsBetweenTheBoxes) {
  // 2 cm (half the block) + 4.5 cm (half the cup) + 4 cm for "a little".
  EXPECT_EQ(meaning("place the red block a little to the left of the white cup"), "red_block left of white_cup at 0.105 m");
  // 2 cm + 10 cm (half the box) + 18 cm for "a lot"; "the top of" is the far side.
  EXPECT_EQ(meaning("place the blue block a lot to the top of the box"), "blue_block in front of box at 0.3 m");
  // 3 cm (half the 6 cm block) + 3 cm (half the small cup) + 4 cm; "the bottom of" is the near side.
  EXPECT_EQ(meaning("put the green block slightly to the bottom of the yellow cup"), "green_block behind yellow_cup at 0.1 m");
}

TEST(TabletopLanguage, LinesAreEvenlySpacedPlacesInTheOrderTheObjectsStand) {
  // The blocks stand in a horizontal line already (y 0.2, 0, -0.2 at x 0.3): they stay.
  const TaskSpecification line = understandInstruction("put the blocks in a horizontal line", describeObjects(test::workbenchScene()));
  EXPECT_EQ(test::summarize(line), "red_block, blue_block, green_block in a line along yaw 90 deg on table");
  ASSERT_EQ(line.steps.size(), 3u) << test::summarize(line);
  EXPECT_NEAR(line.steps[0].position->y(), 0.2, 1e-9);
  EXPECT_NEAR(line.steps[2].position->y(), -0.2, 1e-9);
  // Along x: spaced by the widest (6 cm) + 4 cm, in the order they stand (ties: as named).
  const TaskSpecification vertical = understandInstruction("put the blocks in a vertical line", describeObjects(test::workbenchScene()));
  ASSERT_EQ(vertical.steps.size(), 3u) << test::summarize(vertical);
  for (std::size_t i = 0; i < 3; ++i) {
    ASSERT_EQ(vertical.steps[i].kind, GoalKind::kAtPosition);
    EXPECT_NEAR(vertical.steps[i].position->y(), vertical.steps[0].position->y(), 1e-9);
  }
  EXPECT_NEAR(vertical.steps[1].position->x() - vertical.steps[0].position->x(), 0.10, 1e-9);
  EXPECT_NEAR(vertical.steps[2].position->x() - vertical.steps[1].position->x(), 0.10, 1e-9);
  const TaskSpecification column = understandInstruction("put the markers in a column", describeObjects(test::workbenchScene()));
  ASSERT_EQ(column.steps.size(), 2u);
  EXPECT_NEAR(column.steps[0].position->y(), column.steps[1].position->y(), 1e-9);
  EXPECT_NEAR(*column.goals.at(0).heading, 0.0, 1e-9);
  // On a desk whose reachable part is 30 cm deep, three objects spaced by the 13 cm marker do not fit.
  std::vector<ObjectDescriptor> objects = describeObjects(test::deskScene());
  for (ObjectDescriptor& object : objects) {
    if (object.name != "desk") continue;
    ASSERT_TRUE(object.reachableTop);
    object.reachableTop->max().x() = object.reachableTop->min().x() + 0.30;
  }
  try {
    (void)understandInstruction("put the marker, the eraser and the holder in a vertical line", objects);
    ADD_FAILURE() << "not refused";
  } catch (const PlanningError& error) {
    EXPECT_THAT(error.what(), HasSubstr("3 objects in a line need 47 cm clear, and the reachable top has no such line free on desk"));
  }
}

TEST(TabletopLanguage, TyposAreReadAsTheOneWordTheyAreNearAndSaid) {
  const TaskSpecification specification = understandInstruction("put the markr in the holdr", describeObjects(test::deskScene()));
  EXPECT_EQ(test::summarize(specification), "marker in holder");
  EXPECT_EQ(specification.corrections, "read \"markr\" as \"marker\"; read \"holdr\" as \"holder\"");
  EXPECT_EQ(meaning("plase the bleu blokc on the red block"), "blue_block on red_block");
  EXPECT_EQ(meaning("put the red block in the top lefft cornr"), "red_block on table (far left corner)");
  EXPECT_EQ(meaning("put the second block from the rihgt in the box"), "blue_block in box");
  // As close to two words: refused, naming both.
  try {
    (void)understandInstruction("put the gree marker in the holder", describeObjects(test::deskScene()));
    ADD_FAILURE() << "not refused";
  } catch (const PlanningError& error) {
    EXPECT_THAT(error.what(), HasSubstr("\"gree\": it is a typo of green or grey? say which"));
  }
  // An object's own words come first: "gren" is the green block's, not grey.
  EXPECT_EQ(meaning("pls put the gren block in the box, thx"), "green_block in box");
  // Between words as near of different sorts, an object's noun comes before a colour, a colour before a verb.
  EXPECT_THAT(meaning("put the red block in the bown"), HasSubstr("put the red block in the brown"));
  // Words far from every word stay as they are, and the reader says what it could not ground.
  EXPECT_THAT(meaning("put the bottle in the box"), HasSubstr("could not ground \"the bottle\""));
  EXPECT_EQ(understandInstruction("put the marker in the holder", describeObjects(test::deskScene())).corrections, "");
}

}  // namespace
}  // namespace lang2manip
