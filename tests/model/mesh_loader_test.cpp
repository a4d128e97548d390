#include "lang2manip/model/mesh_loader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/log.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

fs::path meshFile(const std::string& name) { return test::testDataDirectory() / "meshes" / name; }

TriangleMesh loadTestMesh(const std::string& name) { return loadTriangleMesh(meshFile(name).string()); }

void expectBounds(const AlignedBox3& box, const Vector3& min, const Vector3& max,
                  double tolerance = 1e-6) {
  ASSERT_FALSE(box.isEmpty());
  EXPECT_TRUE((box.min() - min).cwiseAbs().maxCoeff() <= tolerance)
      << "min " << box.min().transpose() << " expected " << min.transpose();
  EXPECT_TRUE((box.max() - max).cwiseAbs().maxCoeff() <= tolerance)
      << "max " << box.max().transpose() << " expected " << max.transpose();
}

/// The message of the InputError that loading `path` throws ("" and a failure when none).
std::string loadError(const std::string& path) {
  try {
    loadTriangleMesh(path);
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError for " << path;
  return {};
}

void expectValidIndices(const TriangleMesh& mesh) {
  const int count = static_cast<int>(mesh.vertices.size());
  for (const auto& triangle : mesh.triangles) {
    for (int index : triangle) {
      ASSERT_GE(index, 0);
      ASSERT_LT(index, count);
    }
  }
}

// ------------------------------------------------------------------------------ formats

TEST(MeshLoader, AsciiStl) {
  const TriangleMesh mesh = loadTestMesh("box_ascii.stl");
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_EQ(mesh.vertices.size(), 8u);
  expectValidIndices(mesh);
  expectBounds(mesh.bounds(), Vector3(0, 0, 0), Vector3(1, 2, 3));
  EXPECT_TRUE(fs::path(mesh.source).is_absolute());
  EXPECT_THAT(mesh.source, HasSubstr("box_ascii.stl"));
}

TEST(MeshLoader, BinaryStl) {
  const TriangleMesh mesh = loadTestMesh("tetrahedron_binary.stl");
  EXPECT_EQ(mesh.triangles.size(), 4u);
  EXPECT_EQ(mesh.vertices.size(), 4u);
  expectValidIndices(mesh);
  expectBounds(mesh.bounds(), Vector3(0, 0, 0), Vector3(1, 1, 1));
}

TEST(MeshLoader, ObjQuadsAreTriangulated) {
  const TriangleMesh mesh = loadTestMesh("cube_quads.obj");
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_EQ(mesh.vertices.size(), 8u);
  expectValidIndices(mesh);
  expectBounds(mesh.bounds(), Vector3::Constant(-0.5), Vector3::Constant(0.5));
}

TEST(MeshLoader, ColladaUnitAndNodeTransformsAppliedUpAxisIgnored) {
  // Millimetres, a translation of 2000 mm along z and a 90 degree turn about z; the Z_UP
  // up axis is not turned into assimp's Y up.
  const TriangleMesh mesh = loadTestMesh("tetrahedron_mm.dae");
  EXPECT_EQ(mesh.triangles.size(), 4u);
  EXPECT_EQ(mesh.vertices.size(), 4u);
  expectValidIndices(mesh);
  expectBounds(mesh.bounds(), Vector3(-1, 0, 2), Vector3(0, 1, 3));
}

// ------------------------------------------------------------------------------ colours

/// The mesh file's colour as a string ("none" without one), rounded to 1/255.
std::string colourOf(const std::string& name) {
  const TriangleMesh mesh = loadTestMesh(name);
  if (!mesh.colour) return "none";
  const Vector3 c = (*mesh.colour * 255.0).array().round();
  return std::to_string(static_cast<int>(c.x())) + " " + std::to_string(static_cast<int>(c.y())) + " " + std::to_string(static_cast<int>(c.z()));
}

TEST(MeshLoader, TheColourCoveringMostOfTheSurfaceIsTheMeshesOwn) {
  EXPECT_EQ(colourOf("white_piece.iv"), "242 240 229");  // ivory over a thin black base
  EXPECT_EQ(colourOf("two_colours.dae"), "204 26 26");   // red 4 m2 over blue 1 m2, bound by <bind_material>
  EXPECT_EQ(colourOf("green_cube.obj"), "26 178 51");    // from its .mtl
  EXPECT_EQ(colourOf("red_box_v2.wrl"), "229 26 26");     // a VRML 2 Appearance
  // Files that name no colour have none (not the reader's default grey).
  EXPECT_EQ(colourOf("box_ascii.stl"), "none");
  EXPECT_EQ(colourOf("cube_v1.wrl"), "none");
  EXPECT_EQ(colourOf("tetrahedron_mm.dae"), "none");
}

TEST(MeshLoader, InventorTransformsAndPrimitives) {
  const TriangleMesh mesh = loadTestMesh("scene.iv");
  expectValidIndices(mesh);
  // 12 for the cube, 2 for the quad, and the tessellated sphere and cylinder.
  EXPECT_GT(mesh.triangles.size(), 12u + 2u + 40u);
  // Extremes on every side come from the quad (x, y), the quad's plane (z min) and the cube
  // (z max), all exact.
  expectBounds(mesh.bounds(), Vector3(-2, -2, -10), Vector3(12, 12, 6), 1e-5);
}

TEST(MeshLoader, InventorPrimitivesAreTessellatedWhereTheyArePlaced) {
  const TriangleMesh mesh = loadTestMesh("scene.iv");
  // Vertices of each part, told apart by where they lie.
  AlignedBox3 cube, sphere, cylinder;
  for (const Vector3& v : mesh.vertices) {
    if (v.z() < -9) continue;  // the quad
    if (v.x() > 8) sphere.extend(v);
    else if (v.y() > 8) cylinder.extend(v);
    else cube.extend(v);
  }
  expectBounds(cube, Vector3(-1, 1, 0), Vector3(3, 3, 6), 1e-5);
  // Tessellated: vertices lie on the surface, so the bounds are within the exact ones.
  expectBounds(sphere, Vector3(9, -1, -1), Vector3(11, 1, 1), 0.05);
  expectBounds(cylinder, Vector3(-1, 9, -2), Vector3(1, 11, 2), 0.05);
}

TEST(MeshLoader, Vrml2TransformsApplied) {
  const TriangleMesh mesh = loadTestMesh("box_v2.wrl");
  EXPECT_EQ(mesh.triangles.size(), 13u);  // 12 for the box, 1 for the face set
  expectValidIndices(mesh);
  expectBounds(mesh.bounds(), Vector3(-1, -0.5, 8.5), Vector3(1, 2, 11.5), 1e-5);
}

TEST(MeshLoader, Vrml1TransformsApplied) {
  const TriangleMesh mesh = loadTestMesh("cube_v1.wrl");
  EXPECT_EQ(mesh.triangles.size(), 12u);
  expectBounds(mesh.bounds(), Vector3(4, -1, -1), Vector3(6, 1, 1), 1e-5);
}

TEST(MeshLoader, Ply) {
  const TriangleMesh mesh = loadTestMesh("tetrahedron.ply");
  EXPECT_EQ(mesh.triangles.size(), 4u);
  expectBounds(mesh.bounds(), Vector3(0, 0, 0), Vector3(1, 1, 1));
}

TEST(MeshLoader, NormalsAndTextureIndicesOutOfRangeAreIgnored) {
  const TriangleMesh mesh = loadTestMesh("bad_normal_index_v2.wrl");
  EXPECT_EQ(mesh.triangles.size(), 1u);
  expectBounds(mesh.bounds(), Vector3(0, 0, 0), Vector3(1, 1, 0));
}

TEST(MeshLoader, MissingTextureImageIsNotNeededButWarnedAbout) {
  std::vector<std::string> warnings;
  setLogSink([&warnings](LogLevel, std::string_view message) { warnings.emplace_back(message); });
  const TriangleMesh mesh = loadTestMesh("missing_texture.iv");
  setLogSink([](LogLevel level, std::string_view message) {
    std::cerr << "lang2manip " << logLevelName(level) << ": " << message << '\n';
  });
  EXPECT_EQ(mesh.triangles.size(), 12u);
  ASSERT_FALSE(warnings.empty());
  EXPECT_THAT(warnings.back(), HasSubstr("missing_texture.iv: "));
  EXPECT_THAT(warnings.back(), HasSubstr("no_such_image.png"));
}

TEST(MeshLoader, ExtensionIsCaseInsensitive) {
  const test::TempDirectory directory;
  const fs::path copy = directory.path() / "BOX.STL";
  fs::copy_file(meshFile("box_ascii.stl"), copy);
  EXPECT_EQ(loadTriangleMesh(copy.string()).triangles.size(), 12u);
}

TEST(MeshLoader, SupportedExtensionsAreLowerCaseWithDot) {
  const auto& extensions = supportedMeshExtensions();
  for (const char* expected : {".stl", ".dae", ".obj", ".iv", ".wrl"}) {
    EXPECT_NE(std::find(extensions.begin(), extensions.end(), expected), extensions.end())
        << expected;
  }
}

// ------------------------------------------------------------------------------ bad input

TEST(MeshLoaderErrors, MissingFile) {
  const std::string path = meshFile("no_such_mesh.stl").string();
  const std::string message = loadError(path);
  EXPECT_THAT(message, HasSubstr(path));
  EXPECT_THAT(message, HasSubstr("mesh file does not exist"));
}

TEST(MeshLoaderErrors, EmptyPath) { EXPECT_THAT(loadError(""), HasSubstr("mesh path is empty")); }

TEST(MeshLoaderErrors, DirectoryIsNotAMesh) {
  const test::TempDirectory directory;
  const fs::path path = directory.path() / "folder.stl";
  fs::create_directory(path);
  EXPECT_THAT(loadError(path.string()), HasSubstr("mesh file is a directory, not a file"));
}

TEST(MeshLoaderErrors, PlyHeaderIsCheckedLineByLineBeforeAssimpReadsIt) {
  const test::TempDirectory directory;
  const std::string good = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                           "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const auto write = [&](const std::string& name, const std::string& text) {
    const fs::path path = directory.path() / name;
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  };
  EXPECT_EQ(loadTriangleMesh(write("good.ply", good)).triangles.size(), 1U);
  const std::string extraWords = good.substr(0, good.find("element face 1")) + "element face 1 y\n" +
                                 good.substr(good.find("property list"));
  EXPECT_THAT(loadError(write("extra.ply", extraWords)),
              HasSubstr("extra.ply:7: malformed PLY header line \"element face 1 y\""));
  std::string huge = good;
  huge.replace(huge.find("element vertex 3"), 16, "element vertex 99999999999");
  EXPECT_THAT(loadError(write("huge.ply", huge)), HasSubstr("huge.ply:3: malformed PLY header line"));
  EXPECT_THAT(loadError(write("open.ply", "ply\nformat ascii 1.0\n")), HasSubstr("PLY header has no end_header line"));
  std::string longList = good;
  longList.replace(longList.find("3 0 1 2"), 7, "66666666 0 1 2");
  EXPECT_THAT(loadError(write("list.ply", longList)),
              HasSubstr("list.ply:13: PLY list count \"66666666\" does not match the values on its line"));
  EXPECT_THAT(loadError(write("short.ply", good.substr(0, good.find("3 0 1 2")))),
              HasSubstr("PLY body ends before the counts of its header"));
}

TEST(MeshLoaderErrors, DeviceIsNotAMesh) {
  const test::TempDirectory directory;
  std::filesystem::create_symlink("/dev/zero", directory.path() / "zero.stl");
  EXPECT_THAT(loadError((directory.path() / "zero.stl").string()), HasSubstr("zero.stl: mesh file is a character device"));
}

TEST(MeshLoaderErrors, UnreadableFile) {
  const test::TempDirectory directory;
  const fs::path path = directory.path() / "locked.stl";
  fs::copy_file(meshFile("box_ascii.stl"), path);
  fs::permissions(path, fs::perms::none);
  if (std::ifstream(path).is_open()) GTEST_SKIP() << "running with permission to read any file";
  const std::string message = loadError(path.string());
  EXPECT_THAT(message, HasSubstr("locked.stl"));
  EXPECT_THAT(message, HasSubstr("cannot be opened"));
}

TEST(MeshLoaderErrors, AFileLargerThanTheBoundIsRefusedBeforeItIsRead) {
  const test::TempDirectory directory;
  const fs::path path = directory.path() / "huge.stl";
  fs::copy_file(meshFile("tetrahedron_binary.stl"), path);
  fs::resize_file(path, kMaxMeshFileBytes + 1);  // sparse: no disk used
  EXPECT_THAT(loadError(path.string()), HasSubstr("huge.stl: mesh file is 256 MiB (at most 256 MiB: give a simplified mesh)"));
}

TEST(MeshLoaderErrors, UnsupportedExtensionListsSupported) {
  const std::string message = loadError(meshFile("mesh.xyz").string());
  EXPECT_THAT(message, HasSubstr("mesh.xyz"));
  EXPECT_THAT(message, HasSubstr("unsupported mesh format \".xyz\""));
  EXPECT_THAT(message, HasSubstr(".stl, .dae, .obj"));
  EXPECT_THAT(message, HasSubstr(".iv, .wrl"));
  EXPECT_THAT(loadError(meshFile("no_extension").string()), HasSubstr("unsupported mesh format"));
}

TEST(MeshLoaderErrors, EmptyStl) {
  const std::string message = loadError(meshFile("empty.stl").string());
  EXPECT_THAT(message, HasSubstr("empty.stl"));
  EXPECT_THAT(message, HasSubstr("cannot read mesh"));
}

TEST(MeshLoaderErrors, EmptyInventor) {
  const std::string message = loadError(meshFile("empty.iv").string());
  EXPECT_THAT(message, HasSubstr("empty.iv"));
}

TEST(MeshLoaderErrors, GarbageStl) {
  const std::string message = loadError(meshFile("garbage.stl").string());
  EXPECT_THAT(message, HasSubstr("garbage.stl"));
  EXPECT_THAT(message, HasSubstr("cannot read mesh"));
}

TEST(MeshLoaderErrors, TruncatedBinaryStl) {
  const std::string message = loadError(meshFile("truncated_binary.stl").string());
  EXPECT_THAT(message, HasSubstr("truncated_binary.stl"));
  EXPECT_THAT(message, HasSubstr("cannot read mesh"));
}

TEST(MeshLoaderErrors, MalformedCollada) {
  const std::string message = loadError(meshFile("garbage.dae").string());
  EXPECT_THAT(message, HasSubstr("garbage.dae"));
  EXPECT_THAT(message, HasSubstr("malformed XML in COLLADA file"));
}

TEST(MeshLoaderErrors, GarbageInventor) {
  const std::string message = loadError(meshFile("garbage.iv").string());
  EXPECT_THAT(message, HasSubstr("garbage.iv"));
  EXPECT_THAT(message, HasSubstr("malformed Inventor/VRML file"));
}

TEST(MeshLoaderErrors, ObjWithVerticesOnly) {
  const std::string message = loadError(meshFile("vertices_only.obj").string());
  EXPECT_THAT(message, HasSubstr("vertices_only.obj"));
  EXPECT_THAT(message, HasSubstr("no triangles"));
}

TEST(MeshLoaderErrors, ObjWithLinesOnly) {
  const std::string message = loadError(meshFile("lines_only.obj").string());
  EXPECT_THAT(message, HasSubstr("lines_only.obj"));
  EXPECT_THAT(message, HasSubstr("no triangles"));
}

TEST(MeshLoaderErrors, NonFiniteVertex) {
  const std::string message = loadError(meshFile("nonfinite.stl").string());
  EXPECT_THAT(message, HasSubstr("nonfinite.stl"));
  EXPECT_THAT(message, HasSubstr("non-finite"));
}

TEST(MeshLoaderErrors, InventorSyntaxErrorGivesLine) {
  const std::string path = meshFile("syntax_error.iv").string();
  const std::string message = loadError(path);
  EXPECT_THAT(message, HasSubstr(path + ":6: malformed Inventor/VRML file"));
  EXPECT_THAT(message, HasSubstr("\"height\""));  // Coin names the field it could not read
  EXPECT_THAT(message, Not(HasSubstr("Occurred at")));  // Coin's own location is not repeated
  EXPECT_THAT(message, Not(HasSubstr("\n")));
}

TEST(MeshLoaderErrors, InventorMissingIncludedFile) {
  const std::string message = loadError(meshFile("missing_include.iv").string());
  EXPECT_THAT(message, HasSubstr("missing_include.iv:5: malformed Inventor/VRML file"));
  EXPECT_THAT(message, HasSubstr("no_such_part.iv"));
}

TEST(MeshLoaderErrors, ErrorCarriesLocation) {
  const std::string path = meshFile("syntax_error.iv").string();
  try {
    loadTriangleMesh(path);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.where().file, path);
    EXPECT_EQ(error.where().line, 6);
  }
}

TEST(MeshLoaderErrors, InventorIndexOutOfRange) {
  const std::string message = loadError(meshFile("index_out_of_range.iv").string());
  EXPECT_THAT(message, HasSubstr("index_out_of_range.iv: IndexedFaceSet coordIndex 7 is out of range"));
}

TEST(MeshLoaderErrors, InventorFaceSetWithTooFewPoints) {
  const std::string message = loadError(meshFile("too_few_points.iv").string());
  EXPECT_THAT(message, HasSubstr("too_few_points.iv: FaceSet needs coordinates 0 to 6 but has 3"));
}

TEST(MeshLoaderErrors, VrmlIndexOutOfRange) {
  const std::string message = loadError(meshFile("index_out_of_range_v2.wrl").string());
  EXPECT_THAT(message, HasSubstr("VRMLIndexedFaceSet coordIndex 99 is out of range"));
}

TEST(MeshLoaderErrors, InventorWithLinesOnly) {
  EXPECT_THAT(loadError(meshFile("lines_only.iv").string()), HasSubstr("no triangles"));
}

std::string repeated(const std::string& text, int times) {
  std::string all;
  for (int i = 0; i < times; ++i) all += text;
  return all;
}

std::string fileText(const fs::path& path) {
  std::ifstream stream(path);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

TEST(MeshLoaderErrors, DeepNestingIsRefusedBeforeParsing) {
  // Coin recurses per level and overflows the stack some 10,000 levels down; the COLLADA reader
  // refuses XML nested deeper than kMaxXmlDepth.
  const test::TempDirectory directory;
  const int levels = 20000;
  const fs::path inventor = directory.path() / "deep.iv";
  std::ofstream(inventor) << "#Inventor V2.1 ascii\n"
                          << repeated("Separator {\n", levels) << "Cube {}\n"
                          << repeated("}\n", levels);
  EXPECT_THAT(loadError(inventor.string()), HasSubstr("nesting deeper than 1000 levels"));

  std::string collada = fileText(meshFile("tetrahedron_mm.dae"));
  collada.insert(collada.find("</visual_scene>"), repeated("</node>", levels));
  collada.insert(collada.find("<node id=\"lifted\""), repeated("<node>", levels));
  const fs::path dae = directory.path() / "deep.dae";
  std::ofstream(dae) << collada;
  EXPECT_THAT(loadError(dae.string()), HasSubstr("nests elements more than 100 levels deep"));
}

TEST(MeshLoaderErrors, ReplicationBeyondTheWorkBoundIsRefused) {
  // Array nodes multiply their children: nested ones ask for 10^18 cubes, and an Array of empty
  // groups for 2.7 * 10^13 visits without a triangle; both stop at the bound instead of hanging.
  const test::TempDirectory directory;
  const fs::path cubes = directory.path() / "cubes.iv";
  std::ofstream(cubes) << "#Inventor V2.1 ascii\nSeparator {\n"
                       << "Array { numElements1 1000 numElements2 1000 numElements3 1000\n"
                       << "Array { numElements1 1000 numElements2 1000 numElements3 1000 Cube {} } } }\n";
  EXPECT_THAT(loadError(cubes.string()), HasSubstr("cubes.iv: the scene is too large"));
  const fs::path groups = directory.path() / "groups.iv";
  std::ofstream(groups) << "#Inventor V2.1 ascii\n"
                        << "Array { numElements1 30000 numElements2 30000 numElements3 30000 Group {} }\n";
  EXPECT_THAT(loadError(groups.string()), HasSubstr("groups.iv: the scene is too large"));
  // Each group uses the previous one twice: 2^30 cubes from 30 lines.
  const fs::path shared = directory.path() / "shared.iv";
  std::ofstream file(shared);
  file << "#Inventor V2.1 ascii\nSeparator {\nDEF G0 Group { Cube {} }\n";
  for (int level = 1; level <= 30; ++level) {
    file << "DEF G" << level << " Group { USE G" << level - 1 << " USE G" << level - 1 << " }\n";
  }
  file << "}\n";
  file.close();
  EXPECT_THAT(loadError(shared.string()), HasSubstr("shared.iv: the scene is too large"));
}

TEST(MeshLoaderErrors, PercentInAFileWithAnIncludeIsRefused) {
  const test::TempDirectory directory;
  for (const std::string name : {"\"50%.iv\"", "50%.iv", "# comment 100%\n \"part.iv\""}) {
    const fs::path inventor = directory.path() / "include.iv";
    std::ofstream(inventor) << "#Inventor V2.1 ascii\nSeparator { File { name " << name << " } }\n";
    EXPECT_THAT(loadError(inventor.string()), HasSubstr("must not contain '%'")) << name;
  }
}

TEST(MeshLoader, ModerateNestingLoads) {
  const test::TempDirectory directory;
  const fs::path inventor = directory.path() / "nested.iv";
  std::ofstream(inventor) << "#Inventor V2.1 ascii\n"
                          << repeated("Separator { Translation { translation 1 0 0 }\n", 900)
                          << "Cube {}\n" << repeated("}\n", 900);
  const TriangleMesh mesh = loadTriangleMesh(inventor.string());
  expectBounds(mesh.bounds(), Vector3(899, -1, -1), Vector3(901, 1, 1), 1e-3);
}

// ------------------------------------------------------------------------------ cache

TEST(MeshCache, SameFileThroughDifferentSpellingsIsLoadedOnce) {
  MeshCache cache;
  const fs::path directory = test::testDataDirectory() / "meshes";
  const auto first = cache.get((directory / "box_ascii.stl").string());
  const auto second = cache.get((directory / "." / "box_ascii.stl").string());
  const auto third = cache.get((directory / ".." / "meshes" / "box_ascii.stl").string());
  EXPECT_EQ(first.get(), second.get());
  EXPECT_EQ(first.get(), third.get());
  EXPECT_EQ(cache.size(), 1u);
  const auto other = cache.get((directory / "cube_quads.obj").string());
  EXPECT_NE(other.get(), first.get());
  EXPECT_EQ(cache.size(), 2u);
}

TEST(MeshCache, FailuresThrowAndAreNotCached) {
  MeshCache cache;
  EXPECT_THROW(cache.get(meshFile("garbage.stl").string()), InputError);
  EXPECT_THROW(cache.get(meshFile("no_such_mesh.stl").string()), InputError);
  EXPECT_EQ(cache.size(), 0u);
}

TEST(MeshCache, ConcurrentRequestsShareOneMesh) {
  MeshCache cache;
  const std::vector<std::string> files = {"scene.iv", "box_v2.wrl", "tetrahedron_mm.dae",
                                          "box_ascii.stl"};
  std::vector<std::vector<const TriangleMesh*>> seen(4);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < seen.size(); ++t) {
    threads.emplace_back([&, t] {
      for (const std::string& name : files) seen[t].push_back(cache.get(meshFile(name).string()).get());
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (std::size_t t = 1; t < seen.size(); ++t) EXPECT_EQ(seen[t], seen[0]);
  EXPECT_EQ(cache.size(), files.size());
}

TEST(MeshCache, GlobalIsOneInstance) { EXPECT_EQ(&MeshCache::global(), &MeshCache::global()); }

// ------------------------------------------------------------------------------ shared data

TEST(MeshSharedData, EveryKauthamMeshLoads) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const fs::path models = shared / "kautham" / "models";
  if (!fs::is_directory(models)) GTEST_SKIP() << models << " is absent: skipped";
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(models)) {
    const std::string extension = entry.path().extension().string();
    if (extension == ".stl" || extension == ".dae" || extension == ".iv" || extension == ".wrl") {
      files.push_back(entry.path());
    }
  }
  EXPECT_GE(files.size(), 70u);
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    TriangleMesh mesh;
    ASSERT_NO_THROW(mesh = loadTriangleMesh(file.string()));
    EXPECT_GT(mesh.triangles.size(), 0u);
    expectValidIndices(mesh);
    const AlignedBox3 box = mesh.bounds();
    EXPECT_FALSE(box.isEmpty());
    EXPECT_TRUE(box.min().allFinite() && box.max().allFinite());
  }
}

}  // namespace
}  // namespace lang2manip
