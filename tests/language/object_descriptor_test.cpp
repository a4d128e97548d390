#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lang2manip/planning/planner_catalog.hpp"

#include <algorithm>

#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/language/planner_names.hpp"
#include "lang2manip/language/words.hpp"
#include "language/language_test_scenes.hpp"
#include "test_paths.hpp"
#include "language/language_test_support.hpp"
#include "lang2manip/language/instruction.hpp"
#include "lang2manip/model/mesh_loader.hpp"

namespace lang2manip {
namespace {

const ObjectDescriptor& find(const std::vector<ObjectDescriptor>& all, const std::string& name) {
  const auto found = std::find_if(all.begin(), all.end(),
                                  [&name](const ObjectDescriptor& item) { return item.name == name; });
  if (found == all.end()) throw std::runtime_error("no descriptor " + name);
  return *found;
}

bool has(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

TEST(ObjectDescriptorTest, DeskSceneObjectsHaveTheirColoursAndSynonyms) {
  const std::vector<ObjectDescriptor> all = describeObjects(test::deskScene());
  ASSERT_EQ(all.size(), 4u);
  EXPECT_EQ(find(all, "marker").colours, std::vector<std::string>{"blue"});
  EXPECT_EQ(find(all, "eraser").colours, std::vector<std::string>{"pink"});
  EXPECT_EQ(find(all, "holder").colours, std::vector<std::string>{"grey"});
  EXPECT_EQ(find(all, "desk").colours, std::vector<std::string>{"brown"});
  EXPECT_TRUE(has(find(all, "marker").synonyms, "pen"));
  EXPECT_TRUE(has(find(all, "eraser").synonyms, "rubber"));
  EXPECT_TRUE(has(find(all, "holder").synonyms, "cup"));
  EXPECT_TRUE(has(find(all, "desk").synonyms, "table"));
  EXPECT_EQ(find(all, "holder").role, ObjectRole::kContainer);
  EXPECT_FALSE(find(all, "desk").movable);
  EXPECT_GT(find(all, "holder").volume, find(all, "eraser").volume);
}

TEST(ObjectDescriptorTest, PositionsAreInTheRobotBaseFrame) {
  const Scene scene = test::deskScene();
  const std::vector<ObjectDescriptor> all = describeObjects(scene);
  const Pose base = scene.robots().front().basePose;
  const Vector3 expected = base.inverse() * scene.object("eraser").worldBounds().center();
  EXPECT_TRUE(find(all, "eraser").position.isApprox(expected));
  EXPECT_GT(find(all, "eraser").position.y(), find(all, "marker").position.y());
  EXPECT_THROW((void)describeObjects(scene, "no_such_robot"), std::exception);
}

TEST(ObjectDescriptorTest, NearestColourNames) {
  EXPECT_EQ(nearestColourName(Vector3(1, 0, 0)), "red");
  EXPECT_EQ(nearestColourName(Vector3(0.1, 0.1, 0.6)), "blue");
  EXPECT_EQ(nearestColourName(Vector3(0, 0.5, 0)), "green");
  EXPECT_EQ(nearestColourName(Vector3(1, 1, 1)), "white");
  EXPECT_EQ(nearestColourName(Vector3(0, 0, 0)), "black");
  EXPECT_EQ(nearestColourName(Vector3(0.45, 0.45, 0.47)), "grey");
  EXPECT_EQ(nearestColourName(Vector3(1, 0.85, 0.1)), "yellow");
  EXPECT_EQ(nearestColourName(Vector3(1, 0.5, 0)), "orange");
}

TEST(ObjectDescriptorTest, SizeClassesRankVolumesAmongMovableObjects) {
  const std::vector<ObjectDescriptor> desk = describeObjects(test::deskScene());
  EXPECT_EQ(find(desk, "eraser").sizeClass, "small");
  EXPECT_EQ(find(desk, "marker").sizeClass, "medium");
  EXPECT_EQ(find(desk, "holder").sizeClass, "large");
  EXPECT_EQ(find(desk, "desk").sizeClass, "large");
  const std::vector<ObjectDescriptor> bench = describeObjects(test::workbenchScene());
  EXPECT_EQ(find(bench, "red_block").sizeClass, "small");
  EXPECT_EQ(find(bench, "box").sizeClass, "large");
}

TEST(ObjectDescriptorTest, AMeshWithoutAUrdfMaterialHasItsFilesColour) {
  // Two pieces whose meshes give their colours (no URDF material, no colour in the name):
  // "the white piece" finds the one whose Inventor material is ivory.
  Scene scene = test::deskScene();
  const auto addPiece = [&](const std::string& name, const std::string& file, double y) {
    SceneObject piece;
    piece.name = name;
    piece.kind = "piece";
    piece.movable = true;
    Shape shape;
    shape.geometry = MeshGeometry{MeshCache::global().get((test::testDataDirectory() / "meshes" / file).string()), Vector3::Ones(), file};
    piece.visuals.push_back(shape);
    piece.collisions.push_back(shape);
    piece.pose.translation() = Vector3(0.1, y, 0.75);
    scene.addObject(piece);
  };
  addPiece("piece_1", "tetrahedron_binary.stl", -0.3);
  addPiece("piece_2", "white_piece.iv", 0.3);
  const std::vector<ObjectDescriptor> all = describeObjects(scene);
  EXPECT_EQ(find(all, "piece_2").colours, std::vector<std::string>{"white"});
  EXPECT_TRUE(find(all, "piece_1").colours.empty());
  EXPECT_EQ(test::summarize(understandInstruction("put the white piece in the holder", all)), "piece_2 in holder");
}

TEST(ObjectDescriptorTest, NamesWrittenInCamelCaseAreReadAsTheirWords) {
  // Kautham's chess pieces: "queenW" and "queenB" are queens, told apart by their colours (from
  // their materials here); "pawnB1" is still found as it is written.
  EXPECT_EQ(nameWords("queenW"), (Words{"queen", "w"}));
  EXPECT_EQ(nameWords("pawnB1"), (Words{"pawn", "b", "1"}));
  EXPECT_EQ(nameWords("woodPiece"), (Words{"wood", "piece"}));
  EXPECT_EQ(nameWords("UR5"), (Words{"ur", "5"}));
  EXPECT_EQ(headNoun(Words{"pawn", "b", "1"}), "pawn");
  EXPECT_EQ(headNoun(Words{"1"}), "");
  Scene scene = test::deskScene();
  const auto addPiece = [&](const std::string& name, const Vector4& rgba, double y) {
    SceneObject piece;
    piece.name = name;
    piece.kind = name;
    piece.movable = true;
    Shape shape;
    shape.geometry = Box{Vector3(0.03, 0.03, 0.08)};
    shape.origin.translation().z() = 0.04;
    shape.material = Material{"", rgba, ""};
    piece.visuals.push_back(shape);
    piece.collisions.push_back(shape);
    piece.pose.translation() = Vector3(0.1, y, 0.75);
    scene.addObject(piece);
  };
  addPiece("queenW", Vector4(0.95, 0.93, 0.88, 1.0), -0.3);
  addPiece("queenB", Vector4(0.25, 0.16, 0.08, 1.0), 0.3);
  addPiece("pawnB1", Vector4(0.25, 0.16, 0.08, 1.0), 0.2);
  const std::vector<ObjectDescriptor> all = describeObjects(scene);
  EXPECT_EQ(test::summarize(understandInstruction("pick up the white queen", all)), "holding queenW");
  EXPECT_EQ(test::summarize(understandInstruction("put the brown queen in the holder", all)), "queenB in holder");
  EXPECT_EQ(test::summarize(understandInstruction("pick up pawnB1", all)), "holding pawnB1");
  EXPECT_EQ(test::summarize(understandInstruction("pick up the pawn", all)), "holding pawnB1");
  try {
    (void)understandInstruction("pick up the queen", all);
    ADD_FAILURE() << "two queens: ambiguous";
  } catch (const PlanningError& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("queenB"));
  }
}

TEST(ObjectDescriptorTest, ColourWordsInTheNameCount) {
  const std::vector<ObjectDescriptor> all = describeObjects(test::workbenchScene());
  EXPECT_TRUE(has(find(all, "yellow_cup").colours, "yellow"));
  EXPECT_EQ(find(all, "marker_2").colours, std::vector<std::string>{"black"});
}

TEST(PlannerNamesTest, OmplKauthamAndSpokenNames) {
  EXPECT_EQ(plannerNameFromWords("RRTConnect"), "RRTConnect");
  EXPECT_EQ(plannerNameFromWords("omplRRTConnect"), "RRTConnect");
  EXPECT_EQ(plannerNameFromWords("rrt connect"), "RRTConnect");
  EXPECT_EQ(plannerNameFromWords("RRT-Connect"), "RRTConnect");
  EXPECT_EQ(plannerNameFromWords("RRT*"), "RRTstar");
  EXPECT_EQ(plannerNameFromWords("omplRRTStar"), "RRTstar");
  EXPECT_EQ(plannerNameFromWords("RRT"), "RRT");
  EXPECT_EQ(plannerNameFromWords("prm star"), "PRMstar");
  EXPECT_EQ(plannerNameFromWords("omplPRM"), "PRM");
  EXPECT_EQ(plannerNameFromWords("KPIECE"), "KPIECE1");
  EXPECT_EQ(plannerNameFromWords("omplKPIECE"), "KPIECE1");
  EXPECT_EQ(plannerNameFromWords("omplTRRTConnect"), "BiTRRT");
  EXPECT_EQ(plannerNameFromWords("BIT*"), "BITstar");
  EXPECT_FALSE(plannerNameFromWords("FooPlanner"));
  EXPECT_FALSE(plannerNameFromWords("RRTConnect please"));
  EXPECT_FALSE(plannerNameFromWords(""));
  const std::vector<std::string> names = plannerNames();
  EXPECT_TRUE(has(names, "RRTConnect"));
  EXPECT_TRUE(has(names, "PRM"));
  for (const std::string& name : names) EXPECT_EQ(plannerNameFromWords(name), name);
}

}  // namespace
}  // namespace lang2manip
