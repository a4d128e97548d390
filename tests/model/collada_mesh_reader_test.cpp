// The COLLADA reader: every primitive and instance kind on small files written here, each class
// of malformed file refused with its line, and a cross-check against assimp (the reference) on
// every COLLADA file of ../shared/data.

#include "lang2manip/model/collada_mesh_reader.hpp"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "lang2manip/model/mesh_loader.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

/// A unit square's four corners (z = 0), as a <source> with id "points".
constexpr const char* kSquareSource = R"(
  <source id="points">
    <float_array id="points-array" count="12">0 0 0 1 0 0 1 1 0 0 1 0</float_array>
    <technique_common><accessor source="#points-array" count="4" stride="3"/></technique_common>
  </source>
  <vertices id="verts"><input semantic="POSITION" source="#points"/></vertices>)";

/// A COLLADA document with `geometries` in <library_geometries> and `scene` as the visual scene's
/// content (no <library_visual_scenes> when it is empty), plus `extra` libraries.
std::string collada(const std::string& geometries, const std::string& scene, const std::string& extra = "") {
  std::string text = R"(<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<library_geometries>)" + geometries + "</library_geometries>\n" + extra;
  if (!scene.empty()) {
    text += "<library_visual_scenes><visual_scene id=\"scene\">" + scene +
            "</visual_scene></library_visual_scenes>\n<scene><instance_visual_scene url=\"#scene\"/></scene>\n";
  }
  return text + "</COLLADA>\n";
}

/// A <geometry id="square"> holding `primitive` over the square's points.
std::string squareGeometry(const std::string& primitive) {
  return std::string("<geometry id=\"square\"><mesh>") + kSquareSource + primitive + "</mesh></geometry>";
}

const std::string kTwoTriangles =
    R"(<triangles count="2"><input semantic="VERTEX" source="#verts" offset="0"/><p>0 1 2 0 2 3</p></triangles>)";

class ColladaReaderTest : public ::testing::Test {
 protected:
  TriangleMesh load(const std::string& text) {
    const fs::path file = directory_.path() / "mesh.dae";
    std::ofstream(file) << text;
    return loadTriangleMesh(file.string());
  }

  std::string loadError(const std::string& text) {
    try {
      load(text);
    } catch (const InputError& error) {
      return error.what();
    }
    ADD_FAILURE() << "no InputError";
    return {};
  }

  test::TempDirectory directory_;
};

void expectBox(const TriangleMesh& mesh, const Vector3& min, const Vector3& max) {
  const AlignedBox3 box = mesh.bounds();
  EXPECT_TRUE(box.min().isApprox(min, 1e-9) || (box.min() - min).norm() < 1e-9) << box.min().transpose();
  EXPECT_TRUE(box.max().isApprox(max, 1e-9) || (box.max() - max).norm() < 1e-9) << box.max().transpose();
}

// ------------------------------------------------------------------------------ what is read

TEST_F(ColladaReaderTest, TrianglesUnderNodeTransformsInDocumentOrder) {
  // translate then scale: the square is scaled first, then moved.
  const TriangleMesh mesh = load(collada(squareGeometry(kTwoTriangles),
                                         R"(<node><translate>10 0 0</translate><scale>2 3 1</scale>
                                              <instance_geometry url="#square"/></node>)"));
  EXPECT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.vertices.size(), 4u);
  expectBox(mesh, Vector3(10, 0, 0), Vector3(12, 3, 0));
}

TEST_F(ColladaReaderTest, MatrixIsRowMajorAndRotateIsInDegrees) {
  const TriangleMesh moved = load(collada(squareGeometry(kTwoTriangles),
                                          R"(<node><matrix>1 0 0 5  0 1 0 6  0 0 1 7  0 0 0 1</matrix>
                                               <instance_geometry url="#square"/></node>)"));
  expectBox(moved, Vector3(5, 6, 7), Vector3(6, 7, 7));
  const TriangleMesh turned = load(collada(squareGeometry(kTwoTriangles),
                                           R"(<node><rotate>0 0 1 90</rotate><instance_geometry url="#square"/></node>)"));
  expectBox(turned, Vector3(-1, 0, 0), Vector3(0, 1, 0));
}

TEST_F(ColladaReaderTest, UnitAppliedUpAxisIgnored) {
  std::string text = collada(squareGeometry(kTwoTriangles), R"(<node><instance_geometry url="#square"/></node>)");
  text.insert(text.find("<library_geometries>"), R"(<asset><unit meter="0.001"/><up_axis>Y_UP</up_axis></asset>)");
  expectBox(load(text), Vector3(0, 0, 0), Vector3(0.001, 0.001, 0));
}

TEST_F(ColladaReaderTest, PolylistPolygonsFansAndStripsAreTriangulated) {
  const std::string input = R"(<input semantic="VERTEX" source="#verts" offset="0"/>)";
  const std::vector<std::string> primitives = {
      "<polylist count=\"1\">" + input + "<vcount>4</vcount><p>0 1 2 3</p></polylist>",
      "<polygons count=\"1\">" + input + "<p>0 1 2 3</p></polygons>",
      "<polygons count=\"1\">" + input + "<ph><p>0 1 2 3</p><h>0 1 2</h></ph></polygons>",
      "<trifans count=\"1\">" + input + "<p>0 1 2 3</p></trifans>",
      "<tristrips count=\"1\">" + input + "<p>1 2 0 3</p></tristrips>"};
  for (const std::string& primitive : primitives) {
    SCOPED_TRACE(primitive);
    const TriangleMesh mesh = load(collada(squareGeometry(primitive), R"(<node><instance_geometry url="#square"/></node>)"));
    EXPECT_EQ(mesh.triangles.size(), 2u);
    expectBox(mesh, Vector3(0, 0, 0), Vector3(1, 1, 0));
  }
}

TEST_F(ColladaReaderTest, InterleavedInputsAndAccessorOffsetAndStride) {
  // Positions stored as x y z w from the second value on; <p> interleaves a normal index.
  const std::string geometry = R"(<geometry id="square"><mesh>
    <source id="points"><float_array id="a" count="17">99 0 0 0 9 1 0 0 9 1 1 0 9 0 1 0 9</float_array>
      <technique_common><accessor source="#a" count="4" stride="4" offset="1"/></technique_common></source>
    <vertices id="verts"><input semantic="POSITION" source="#points"/></vertices>
    <triangles count="2"><input semantic="VERTEX" source="#verts" offset="0"/>
      <input semantic="NORMAL" source="#points" offset="1"/><p>0 7 1 7 2 7 0 7 2 7 3 7</p></triangles>
    <lines count="1"><input semantic="VERTEX" source="#verts" offset="0"/><p>0 1</p></lines>
  </mesh></geometry>)";
  const TriangleMesh mesh = load(collada(geometry, R"(<node><instance_geometry url="#square"/></node>)"));
  EXPECT_EQ(mesh.triangles.size(), 2u);
  expectBox(mesh, Vector3(0, 0, 0), Vector3(1, 1, 0));
}

TEST_F(ColladaReaderTest, InstancedNodesAndSkinnedControllers) {
  const std::string library = R"(<library_nodes><node id="part"><translate>0 0 1</translate>
      <instance_geometry url="#square"/></node></library_nodes>
    <library_controllers><controller id="skin"><skin source="#square">
      <bind_shape_matrix>1 0 0 0  0 1 0 0  0 0 1 -4  0 0 0 1</bind_shape_matrix></skin></controller></library_controllers>)";
  const TriangleMesh mesh = load(collada(squareGeometry(kTwoTriangles),
                                         R"(<node><instance_node url="#part"/><node><translate>0 0 2</translate>
                                              <instance_node url="#part"/></node></node>
                                            <node><instance_controller url="#skin"/></node>)",
                                         library));
  EXPECT_EQ(mesh.triangles.size(), 6u);
  expectBox(mesh, Vector3(0, 0, -4), Vector3(1, 1, 3));
}

TEST_F(ColladaReaderTest, EachMeshUsesItsOwnSourcesWhenIdsRepeat) {
  // Two geometries whose sources share ids (as some exporters write them): each mesh means its
  // own, so the second square is the one 5 m up.
  std::string second = squareGeometry(kTwoTriangles);
  second.replace(second.find("id=\"square\""), 11, "id=\"upper\"");
  second.replace(second.find("0 0 0 1 0 0 1 1 0 0 1 0"), 23, "0 0 5 1 0 5 1 1 5 0 1 5");
  const TriangleMesh mesh = load(collada(squareGeometry(kTwoTriangles) + second,
                                         R"(<node><instance_geometry url="#upper"/></node>)"));
  expectBox(mesh, Vector3(0, 0, 5), Vector3(1, 1, 5));
}

TEST_F(ColladaReaderTest, WithoutAVisualSceneEveryGeometryIsAtTheOrigin) {
  const TriangleMesh mesh = load(collada(squareGeometry(kTwoTriangles), ""));
  EXPECT_EQ(mesh.triangles.size(), 2u);
  expectBox(mesh, Vector3(0, 0, 0), Vector3(1, 1, 0));
}

// ------------------------------------------------------------------------------ bad input

struct BadCollada {
  std::string name;
  std::string text;
  std::string expected;
};

std::vector<BadCollada> badColladaFiles() {
  const std::string node = R"(<node><instance_geometry url="#square"/></node>)";
  const std::string vertex = R"(<input semantic="VERTEX" source="#verts" offset="0"/>)";
  return {
      {"index beyond the positions",
       collada(squareGeometry("<triangles count=\"1\">" + vertex + "<p>0 1 4</p></triangles>"), node),
       "vertex index 4 is beyond the 4 positions"},
      {"index that is not an unsigned integer",
       collada(squareGeometry("<triangles count=\"1\">" + vertex + "<p>0 1 -2</p></triangles>"), node),
       "index lists hold only unsigned integers"},
      {"index list not a multiple of the inputs",
       collada(squareGeometry("<triangles count=\"1\">" + vertex +
                              R"(<input semantic="NORMAL" source="#points" offset="1"/><p>0 0 1 1 2</p></triangles>)"),
               node),
       "not a multiple of the 2 inputs"},
      {"triangle list with a left-over vertex",
       collada(squareGeometry("<triangles count=\"1\">" + vertex + "<p>0 1 2 3</p></triangles>"), node),
       "more indices than its primitives use"},
      {"vcount beyond the index list",
       collada(squareGeometry("<polylist count=\"1\">" + vertex + "<vcount>3 4000000000</vcount><p>0 1 2 0 1</p></polylist>"), node),
       "ends before the polygons of <vcount>"},
      {"accessor beyond its array",
       collada("<geometry id=\"square\"><mesh><source id=\"points\"><float_array id=\"a\">0 0 0 1 0 0</float_array>"
               "<technique_common><accessor source=\"#a\" count=\"3\" stride=\"3\"/></technique_common></source>"
               "<vertices id=\"verts\"><input semantic=\"POSITION\" source=\"#points\"/></vertices>" +
                   kTwoTriangles + "</mesh></geometry>",
               node),
       "reads 3 points of stride 3 from a <float_array> of 6 numbers"},
      {"float_array count that is not a number",
       [] {
         std::string text = collada(squareGeometry(kTwoTriangles), R"(<node><instance_geometry url="#square"/></node>)");
         text.replace(text.find("count=\"12\""), 10, "count=\".42\"");
         return text;
       }(),
       "<float_array> count must be a whole number"},
      {"float_array count that disagrees with its numbers",
       [] {
         std::string text = collada(squareGeometry(kTwoTriangles), R"(<node><instance_geometry url="#square"/></node>)");
         text.replace(text.find("count=\"12\""), 10, "count=\"15\"");
         return text;
       }(),
       "<float_array> count 15 but it holds 12 numbers"},
      {"accessor stride below 3",
       collada("<geometry id=\"square\"><mesh><source id=\"points\"><float_array id=\"a\">0 0 0 1 0 0</float_array>"
               "<technique_common><accessor source=\"#a\" count=\"3\" stride=\"2\"/></technique_common></source>"
               "<vertices id=\"verts\"><input semantic=\"POSITION\" source=\"#points\"/></vertices>" +
                   kTwoTriangles + "</mesh></geometry>",
               node),
       "stride of at least 3"},
      {"non-finite coordinate",
       [] {
         std::string text = collada(squareGeometry(kTwoTriangles), R"(<node><instance_geometry url="#square"/></node>)");
         text.replace(text.find("1 1 0 0 1 0"), 5, "1 inf");
         return text;
       }(),
       "must be a finite number"},
      {"URL that names nothing", collada(squareGeometry(kTwoTriangles), R"(<node><instance_geometry url="#nothing"/></node>)"),
       "url \"#nothing\" names no element"},
      {"URL into another file", collada(squareGeometry(kTwoTriangles), R"(<node><instance_geometry url="other.dae#square"/></node>)"),
       "is not a \"#id\" reference within the file"},
      {"URL naming the wrong kind of element",
       collada(squareGeometry(kTwoTriangles), R"(<node id="n"><instance_geometry url="#n"/></node>)"),
       "<node> is referenced as a <geometry>"},
      {"primitive without a VERTEX input", collada(squareGeometry("<triangles count=\"1\"><p>0 1 2</p></triangles>"), node),
       "<triangles> has no VERTEX input"},
      {"node that instances itself", collada(squareGeometry(kTwoTriangles), R"(<node id="loop"><instance_node url="#loop"/></node>)"),
       "instances nest more than 100 levels deep"},
      {"instances that double at every level",
       [] {
         std::string nodes = "<library_nodes><node id=\"n0\"><instance_geometry url=\"#square\"/></node>";
         for (int level = 1; level <= 30; ++level) {
           const std::string below = "#n" + std::to_string(level - 1);
           nodes += "<node id=\"n" + std::to_string(level) + "\"><instance_node url=\"" + below +
                    "\"/><instance_node url=\"" + below + "\"/></node>";
         }
         return collada(squareGeometry(kTwoTriangles), R"(<node><instance_node url="#n30"/></node>)", nodes + "</library_nodes>");
       }(),
       "more than 100000 node and geometry instances"},
      {"lookat transform", collada(squareGeometry(kTwoTriangles), R"(<node><lookat>0 0 1 0 0 0 0 1 0</lookat><instance_geometry url="#square"/></node>)"),
       "<lookat> transforms are not supported"},
      {"matrix of 15 numbers", collada(squareGeometry(kTwoTriangles), R"(<node><matrix>1 0 0 0 0 1 0 0 0 0 1 0 0 0 0</matrix><instance_geometry url="#square"/></node>)"),
       "<matrix> needs 16 numbers, has 15"},
      {"unit of zero metres",
       [] {
         std::string text = collada(squareGeometry(kTwoTriangles), R"(<node><instance_geometry url="#square"/></node>)");
         text.insert(text.find("<library_geometries>"), R"(<asset><unit meter="0"/></asset>)");
         return text;
       }(),
       "<unit> meter must be positive"},
      {"no triangles at all", collada(squareGeometry(""), node), "mesh contains no triangles"},
      {"a small file instancing more than the triangle bound",
       [] {
         std::string thousand = R"(<triangles count="1000"><input semantic="VERTEX" source="#verts" offset="0"/><p>)";
         for (int i = 0; i < 1000; ++i) thousand += "0 1 2 ";
         std::string nodes = "<library_nodes><node id=\"n0\"><instance_geometry url=\"#square\"/></node>";
         for (int level = 1; level <= 11; ++level) {  // 2048 instances of 1000 triangles
           const std::string below = "#n" + std::to_string(level - 1);
           nodes += "<node id=\"n" + std::to_string(level) + "\"><instance_node url=\"" + below +
                    "\"/><instance_node url=\"" + below + "\"/></node>";
         }
         return collada(squareGeometry(thousand + "</p></triangles>"), R"(<node><instance_node url="#n11"/></node>)",
                        nodes + "</library_nodes>");
       }(),
       "mesh has more than 2000000 triangles"},
  };
}

TEST_F(ColladaReaderTest, EveryClassOfMalformedFileIsRefusedWithItsLine) {
  for (const BadCollada& bad : badColladaFiles()) {
    SCOPED_TRACE(bad.name);
    const std::string message = loadError(bad.text);
    EXPECT_THAT(message, HasSubstr("mesh.dae"));
    EXPECT_THAT(message, HasSubstr(bad.expected));
  }
}

// ------------------------------------------------------------------------------ reference

struct ReferenceMesh {
  std::size_t triangles = 0;
  AlignedBox3 bounds;
};

/// The triangles and bounds assimp reads, unit applied and up axis ignored (as our reader).
ReferenceMesh readWithAssimp(const fs::path& file) {
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene = importer.ReadFile(file.string(), aiProcess_Triangulate);
  ReferenceMesh reference;
  if (scene == nullptr || scene->mRootNode == nullptr) return reference;
  std::vector<std::pair<const aiNode*, aiMatrix4x4>> pending = {{scene->mRootNode, scene->mRootNode->mTransformation}};
  while (!pending.empty()) {
    const auto [node, X] = pending.back();
    pending.pop_back();
    for (unsigned m = 0; m < node->mNumMeshes; ++m) {
      const aiMesh& mesh = *scene->mMeshes[node->mMeshes[m]];
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        if (mesh.mFaces[f].mNumIndices != 3) continue;
        ++reference.triangles;
        for (unsigned i = 0; i < 3; ++i) {
          const aiVector3D p = X * mesh.mVertices[mesh.mFaces[f].mIndices[i]];
          reference.bounds.extend(Vector3(p.x, p.y, p.z));
        }
      }
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) {
      pending.emplace_back(node->mChildren[c], X * node->mChildren[c]->mTransformation);
    }
  }
  return reference;
}

TEST(ColladaReaderReference, AgreesWithAssimpOnEverySharedColladaFile) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  int compared = 0;
  for (const auto& entry : fs::recursive_directory_iterator(shared)) {
    if (entry.path().extension() != ".dae") continue;
    SCOPED_TRACE(entry.path().string());
    const ReferenceMesh reference = readWithAssimp(entry.path());
    TriangleMesh mesh;
    ASSERT_NO_THROW(mesh = readColladaMesh(entry.path()));
    // assimp keeps triangles without area, which the builder drops.
    EXPECT_LE(mesh.triangles.size(), reference.triangles);
    EXPECT_GE(mesh.triangles.size(), reference.triangles * 99 / 100);
    const double size = reference.bounds.diagonal().norm();
    EXPECT_LT((mesh.bounds().min() - reference.bounds.min()).norm(), 1e-5 * size);
    EXPECT_LT((mesh.bounds().max() - reference.bounds.max()).norm(), 1e-5 * size);
    ++compared;
  }
  EXPECT_GE(compared, 40);
}

}  // namespace
}  // namespace lang2manip
