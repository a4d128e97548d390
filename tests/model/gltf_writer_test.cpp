// Scenes as glTF binary: the file is read back and checked against the glTF 2.0 rules a viewer
// relies on (header, chunks, accessors inside their buffer views, indices inside their vertices,
// POSITION bounds), for primitives, meshes and the paper's scene.

#include "lang2manip/model/gltf_writer.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <tuple>
#include <nlohmann/json.hpp>

#include "lang2manip/core/error.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/model/mesh_loader.hpp"
#include "lang2manip/model/mesh_shading.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

using json = nlohmann::json;
using ::testing::HasSubstr;

std::uint32_t wordAt(const std::string& bytes, std::size_t offset) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + offset, 4);
  return value;
}

struct Glb {
  json document;
  std::string binary;
};

/// Parses `bytes` as GLB, failing the test on any structural error.
Glb parseGlb(const std::string& bytes) {
  Glb glb;
  EXPECT_GE(bytes.size(), 28U);
  if (bytes.size() < 28) return glb;
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_EQ(wordAt(bytes, 4), 2U);
  EXPECT_EQ(wordAt(bytes, 8), bytes.size());
  const std::uint32_t jsonLength = wordAt(bytes, 12);
  EXPECT_EQ(jsonLength % 4, 0U);
  EXPECT_EQ(bytes.substr(16, 4), "JSON");
  glb.document = json::parse(bytes.substr(20, jsonLength));
  const std::size_t binaryHeader = 20 + jsonLength;
  EXPECT_EQ(bytes.substr(binaryHeader + 4, 4), std::string("BIN\0", 4));
  glb.binary = bytes.substr(binaryHeader + 8, wordAt(bytes, binaryHeader));
  EXPECT_EQ(glb.binary.size() % 4, 0U);
  EXPECT_EQ(glb.document["buffers"][0]["byteLength"].get<std::size_t>(), glb.binary.size());
  return glb;
}

/// Checks every mesh primitive of `glb`: views inside the buffer, indices below the vertex
/// count, POSITION min/max equal to the data's. Returns the number of triangles.
std::size_t checkPrimitives(const Glb& glb) {
  const json& accessors = glb.document["accessors"];
  const json& views = glb.document["bufferViews"];
  std::size_t triangles = 0;
  for (const json& mesh : glb.document["meshes"]) {
    for (const json& primitive : mesh["primitives"]) {
      if (primitive.contains("mode")) continue;  // lines: checked by checkLines()
      const json& position = accessors[primitive["attributes"]["POSITION"].get<std::size_t>()];
      const json& index = accessors[primitive["indices"].get<std::size_t>()];
      const json& positionView = views[position["bufferView"].get<std::size_t>()];
      const json& indexView = views[index["bufferView"].get<std::size_t>()];
      const std::size_t vertices = position["count"];
      EXPECT_EQ(positionView["byteLength"].get<std::size_t>(), vertices * 12);
      EXPECT_LE(positionView["byteOffset"].get<std::size_t>() + vertices * 12, glb.binary.size());
      EXPECT_EQ(positionView["byteOffset"].get<std::size_t>() % 4, 0U);
      const std::size_t count = index["count"];
      EXPECT_EQ(count % 3, 0U);
      EXPECT_LE(indexView["byteOffset"].get<std::size_t>() + count * 4, glb.binary.size());
      std::vector<float> low(3, 1e30F);
      std::vector<float> high(3, -1e30F);
      for (std::size_t v = 0; v < vertices; ++v) {
        for (std::size_t k = 0; k < 3; ++k) {
          float x = 0;
          std::memcpy(&x, glb.binary.data() + positionView["byteOffset"].get<std::size_t>() + 12 * v + 4 * k, 4);
          low[k] = std::min(low[k], x);
          high[k] = std::max(high[k], x);
        }
      }
      for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_FLOAT_EQ(position["min"][k].get<float>(), low[k]);
        EXPECT_FLOAT_EQ(position["max"][k].get<float>(), high[k]);
      }
      for (std::size_t i = 0; i < count; ++i) {
        EXPECT_LT(wordAt(glb.binary, indexView["byteOffset"].get<std::size_t>() + 4 * i), vertices);
      }
      // One unit normal per vertex, for smooth shading.
      const json& normal = accessors[primitive["attributes"]["NORMAL"].get<std::size_t>()];
      EXPECT_EQ(normal["count"].get<std::size_t>(), vertices);
      const std::size_t normalOffset = views[normal["bufferView"].get<std::size_t>()]["byteOffset"].get<std::size_t>();
      for (std::size_t v = 0; v < vertices; v += 1 + vertices / 50) {
        float n[3];
        std::memcpy(n, glb.binary.data() + normalOffset + 12 * v, 12);
        EXPECT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0F, 1e-4F);
      }
      triangles += count / 3;
    }
  }
  return triangles;
}

TEST(GltfWriter, PrimitivesAreClosedSurfacesOfTheirSize) {
  const TriangleMesh box = tessellated(Box{Vector3(0.2, 0.4, 0.6)});
  EXPECT_EQ(box.triangles.size(), 12U);
  EXPECT_TRUE(box.bounds().sizes().isApprox(Vector3(0.2, 0.4, 0.6)));
  const TriangleMesh cylinder = tessellated(Cylinder{0.1, 0.5}, 16);
  EXPECT_EQ(cylinder.triangles.size(), 64U);
  EXPECT_NEAR(cylinder.bounds().sizes().z(), 0.5, 1e-12);
  const TriangleMesh sphere = tessellated(Sphere{0.3}, 12);
  EXPECT_NEAR(sphere.bounds().sizes().z(), 0.6, 1e-12);
  // Closed: every edge is shared by exactly two triangles, in opposite directions.
  for (const TriangleMesh* mesh : {&box, &cylinder, &sphere}) {
    std::map<std::pair<int, int>, int> edges;
    for (const auto& t : mesh->triangles) {
      for (int e = 0; e < 3; ++e) ++edges[{t[e], t[(e + 1) % 3]}];
    }
    for (const auto& [edge, uses] : edges) {
      EXPECT_EQ(uses, 1);
      EXPECT_EQ(edges.count({edge.second, edge.first}), 1U);
    }
  }
  EXPECT_THROW((void)tessellated(Sphere{0.3}, 2), InputError);
}

TEST(MeshShading, EdgesStaySharpCurvesTurnSmoothAndRepeatedVerticesAreWelded) {
  const TriangleMesh box = tessellated(Box{Vector3(0.2, 0.4, 0.6)});
  const ShadedMesh shadedBox = shadedMesh(box);
  EXPECT_EQ(shadedBox.vertices.size(), 24U) << "each corner once per face it bounds";
  ASSERT_EQ(shadedBox.triangles.size(), 12U);
  for (const auto& triangle : shadedBox.triangles) {
    const Vector3& a = shadedBox.vertices[static_cast<std::size_t>(triangle[0])];
    const Vector3 face = (shadedBox.vertices[static_cast<std::size_t>(triangle[1])] - a)
                             .cross(shadedBox.vertices[static_cast<std::size_t>(triangle[2])] - a)
                             .normalized();
    for (const int corner : triangle) EXPECT_TRUE(shadedBox.normals[static_cast<std::size_t>(corner)].isApprox(face));
  }
  // The same box as a triangle soup (as STL stores it): welded to the same 24 vertices.
  TriangleMesh soup;
  for (const auto& triangle : box.triangles) {
    const int first = static_cast<int>(soup.vertices.size());
    for (const int corner : triangle) soup.vertices.push_back(box.vertices[static_cast<std::size_t>(corner)]);
    soup.triangles.push_back({first, first + 1, first + 2});
  }
  EXPECT_EQ(shadedMesh(soup).vertices.size(), 24U);

  // A sphere has no crease: one vertex per position, its normal pointing out from the centre.
  const ShadedMesh sphere = shadedMesh(tessellated(Sphere{0.3}, 24));
  std::set<std::tuple<double, double, double>> positions;
  for (std::size_t v = 0; v < sphere.vertices.size(); ++v) {
    positions.insert({sphere.vertices[v].x(), sphere.vertices[v].y(), sphere.vertices[v].z()});
    EXPECT_GT(sphere.normals[v].dot(sphere.vertices[v].normalized()), 0.98) << sphere.vertices[v].transpose();
  }
  EXPECT_EQ(positions.size(), sphere.vertices.size());
  // A cylinder: smooth sides, sharp rims.
  const ShadedMesh cylinder = shadedMesh(tessellated(Cylinder{0.1, 0.5}, 16));
  for (std::size_t v = 0; v < cylinder.vertices.size(); ++v) {
    const Vector3& n = cylinder.normals[v];
    EXPECT_TRUE(std::abs(n.z()) > 0.999 || std::abs(n.z()) < 1e-9) << n.transpose();
  }
  // Corrupt indices are dropped, not read.
  TriangleMesh corrupt = box;
  corrupt.triangles.push_back({0, 1, 99});
  EXPECT_EQ(shadedMesh(corrupt).triangles.size(), 12U);
}

TEST(GltfWriter, AMeshOfSeveralColoursIsDrawnInEach) {
  for (const char* file : {"two_colours.dae", "white_piece.iv"}) {
    SCOPED_TRACE(file);
    auto mesh = std::make_shared<TriangleMesh>(loadTriangleMesh((test::testDataDirectory() / "meshes" / file).string()));
    ASSERT_EQ(mesh->palette.size(), 2U);
    ASSERT_EQ(mesh->triangleColours.size(), mesh->triangles.size());
    Scene scene;
    SceneObject object;
    object.name = "piece";
    object.kind = "piece";
    object.visuals.push_back(Shape{MeshGeometry{mesh, Vector3::Ones(), file}, Pose::Identity(), std::nullopt, ""});
    object.collisions = object.visuals;
    scene.addObject(object);
    const Glb glb = parseGlb(sceneToGlb(scene));
    EXPECT_EQ(checkPrimitives(glb), mesh->triangles.size());
    ASSERT_EQ(glb.document["meshes"].size(), 1U);
    const json& primitives = glb.document["meshes"][0]["primitives"];
    ASSERT_EQ(primitives.size(), 2U);
    std::set<std::vector<int>> colours;
    for (const json& primitive : primitives) {
      const json factor = glb.document["materials"][primitive["material"].get<std::size_t>()]["pbrMetallicRoughness"]["baseColorFactor"];
      colours.insert({static_cast<int>(std::lround(factor[0].get<double>() * 255)), static_cast<int>(std::lround(factor[1].get<double>() * 255)),
                      static_cast<int>(std::lround(factor[2].get<double>() * 255))});
    }
    std::set<std::vector<int>> expected;
    for (const Vector3& rgb : mesh->palette) {
      expected.insert({static_cast<int>(std::lround(rgb.x() * 255)), static_cast<int>(std::lround(rgb.y() * 255)), static_cast<int>(std::lround(rgb.z() * 255))});
    }
    EXPECT_EQ(colours, expected);
  }
}

/// The body nodes (children of the root) by name.
std::map<std::string, json> bodiesOf(const Glb& glb);
/// Names of the children of `node`.
std::vector<std::string> childNames(const Glb& glb, const json& node);

TEST(GltfWriter, ALinkWithoutVisualIsNotDrawnButAnObjectWithoutOneIs) {
  Scene scene;
  SceneRobot robot;
  robot.name = "arm";
  robot.model = readUrdfString(R"(<robot name="arm">
  <link name="base"><visual><geometry><box size="0.2 0.2 0.2"/></geometry></visual>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="padding"><collision><geometry><sphere radius="0.3"/></geometry></collision></link>
  <joint name="fix" type="fixed"><parent link="base"/><child link="padding"/></joint>
</robot>)", "arm.urdf", ".");
  robot.configuration = VectorX::Zero(0);
  scene.addRobot(robot);
  SceneObject obstacle;
  obstacle.name = "obstacle";
  obstacle.kind = "obstacle";
  obstacle.collisions.push_back(Shape{Box{Vector3::Ones()}, Pose::Identity(), std::nullopt, ""});
  scene.addObject(obstacle);
  const Glb glb = parseGlb(sceneToGlb(scene));
  const std::map<std::string, json> bodies = bodiesOf(glb);
  const auto visualChildren = [&](const std::string& body) {
    const json& visual = glb.document["nodes"][bodies.at(body)["children"][0].get<std::size_t>()];
    return visual.value("children", json::array()).size();
  };
  EXPECT_EQ(visualChildren("arm/base"), 1U);
  EXPECT_EQ(visualChildren("arm/padding"), 0U) << "a self-collision padding is not what the robot looks like";
  EXPECT_EQ(visualChildren("obstacle"), 1U);
  GltfOptions both;
  both.geometry = GltfGeometry::kBoth;
  const Glb withCollision = parseGlb(sceneToGlb(scene, both));
  EXPECT_EQ(childNames(withCollision, bodiesOf(withCollision).at("arm/padding")), (std::vector<std::string>{"visual", "collision"}));
}

std::map<std::string, json> bodiesOf(const Glb& glb) {
  std::map<std::string, json> bodies;
  for (const json& child : glb.document["nodes"][0]["children"]) {
    const json& node = glb.document["nodes"][child.get<std::size_t>()];
    if (node.contains("extras")) bodies[node["name"]] = node;
  }
  return bodies;
}

/// Names of the children of `node`.
std::vector<std::string> childNames(const Glb& glb, const json& node) {
  std::vector<std::string> names;
  for (const json& child : node.value("children", json::array())) names.push_back(glb.document["nodes"][child.get<std::size_t>()]["name"]);
  return names;
}

TEST(GltfWriter, ThePaperSceneIsAValidGlbWithEveryBody) {
  const Scene scene = readKauthamProblem(resolveProblem("panda_desk")).scene;
  GltfSummary summary;
  const Glb glb = parseGlb(sceneToGlb(scene, {}, &summary));
  EXPECT_EQ(glb.document["asset"]["version"], "2.0");
  EXPECT_EQ(checkPrimitives(glb), static_cast<std::size_t>(summary.triangles));
  EXPECT_EQ(glb.document["nodes"].size(), static_cast<std::size_t>(summary.nodes) + 1);
  const std::map<std::string, json> bodies = bodiesOf(glb);
  std::size_t links = 0;
  for (const SceneRobot& robot : scene.robots()) links += robot.model->links().size();
  EXPECT_EQ(bodies.size(), links + scene.objects().size());
  for (const char* expected : {"marker", "holder", "desk", "panda/panda_hand"}) EXPECT_EQ(bodies.count(expected), 1U) << expected;
  EXPECT_EQ(bodies.at("marker")["extras"]["kind"], "object");
  EXPECT_EQ(bodies.at("panda/panda_hand")["extras"]["kind"], "link");
  // Every body node carries its world pose: the marker lies on the desk at (0.02, -0.18).
  EXPECT_NEAR(bodies.at("marker")["translation"][1].get<double>(), -0.18, 0.01);
  EXPECT_EQ(childNames(glb, bodies.at("marker")), std::vector<std::string>{"visual"});

  // Collision geometry instead of visuals, and both for the viewer: different, still valid files.
  for (const GltfGeometry geometry : {GltfGeometry::kCollision, GltfGeometry::kBoth}) {
    GltfOptions options;
    options.geometry = geometry;
    GltfSummary other;
    const Glb otherGlb = parseGlb(sceneToGlb(scene, options, &other));
    // Triangles are written once per geometry; meshes of two colours may share them.
    EXPECT_GE(checkPrimitives(otherGlb), static_cast<std::size_t>(other.triangles));
    const std::vector<std::string> groups = childNames(otherGlb, bodiesOf(otherGlb).at("panda/panda_hand"));
    const std::vector<std::string> expected =
        geometry == GltfGeometry::kBoth ? std::vector<std::string>{"visual", "collision"} : std::vector<std::string>{"collision"};
    EXPECT_EQ(groups, expected);
  }
  GltfOptions bad;
  bad.roundSegments = 0;
  EXPECT_THROW((void)sceneToGlb(scene, bad), InputError);
}

TEST(GlbBuilder, AnimationsAndLinesAreValid) {
  GlbBuilder builder(GltfGeometry::kVisual, 12);
  const Shape box{Box{Vector3(0.1, 0.1, 0.1)}, Pose::Identity(), std::nullopt, ""};
  const int body = builder.addBody("cube", "object", {box}, {}, Pose::Identity());
  std::vector<Pose> poses(3, Pose::Identity());
  poses[1].translation() = Vector3(0.5, 0.0, 0.0);
  poses[2].linear() = Eigen::AngleAxisd(3.0, Vector3::UnitZ()).toRotationMatrix();
  builder.addAnimation("trajectory", {0.0, 0.5, 1.25}, {{body, poses}});
  builder.addPolyline("tool_paths", "tool_path/0", {Vector3::Zero(), Vector3::UnitX(), Vector3::UnitY()}, Vector4(1, 0, 0, 1));
  builder.addLines("exploration_tree", "exploration_tree/edges", {{Vector3::Zero(), Vector3::UnitZ()}}, Vector4(0, 1, 0, 1));
  EXPECT_THROW(builder.addAnimation("bad", {0.0, 0.0}, {{body, {Pose::Identity(), Pose::Identity()}}}), InputError);
  EXPECT_THROW(builder.addAnimation("bad", {0.0, 1.0}, {{body, {Pose::Identity()}}}), InputError);
  const Glb glb = parseGlb(builder.finish());
  const json& animation = glb.document["animations"][0];
  EXPECT_EQ(animation["name"], "trajectory");
  ASSERT_EQ(animation["channels"].size(), 2U);
  const json& accessors = glb.document["accessors"];
  for (const json& sampler : animation["samplers"]) {
    const json& input = accessors[sampler["input"].get<std::size_t>()];
    EXPECT_EQ(input["count"], 3);
    EXPECT_FLOAT_EQ(input["max"][0].get<float>(), 1.25F);
    const json& output = accessors[sampler["output"].get<std::size_t>()];
    EXPECT_EQ(output["count"], 3);
    const json& view = glb.document["bufferViews"][output["bufferView"].get<std::size_t>()];
    EXPECT_EQ(view["byteLength"].get<std::size_t>(), 3U * (output["type"] == "VEC3" ? 12U : 16U));
  }
  for (const json& channel : animation["channels"]) EXPECT_EQ(channel["target"]["node"], body);
  std::map<std::string, int> modes;
  for (const json& node : glb.document["nodes"]) {
    if (!node.contains("mesh")) continue;
    const json& primitive = glb.document["meshes"][node["mesh"].get<std::size_t>()]["primitives"][0];
    modes[node["name"]] = primitive.value("mode", 4);
  }
  EXPECT_EQ(modes.at("tool_path/0"), 3);
  EXPECT_EQ(modes.at("exploration_tree/edges"), 1);
  EXPECT_EQ(modes.at("cube"), 4);
  for (const json& node : glb.document["nodes"]) {
    if (node.contains("children")) {
      EXPECT_FALSE(node["children"].empty()) << node["name"];
    }
  }
}

TEST(GltfWriter, MeshesAreWrittenOncePerMeshAndScale) {
  auto mesh = std::make_shared<TriangleMesh>(tessellated(Box{Vector3::Ones()}));
  Scene scene;
  for (int i = 0; i < 3; ++i) {
    SceneObject object;
    object.name = "block" + std::to_string(i);
    object.kind = "block";
    object.pose.translation() = Vector3(i, 0, 0);
    object.collisions.push_back(Shape{MeshGeometry{mesh, Vector3::Constant(i == 2 ? 2.0 : 1.0), "block.stl"}, Pose::Identity(), std::nullopt, ""});
    scene.addObject(object);
  }
  SceneObject unloaded;
  unloaded.name = "ghost";
  unloaded.collisions.push_back(Shape{MeshGeometry{nullptr, Vector3::Ones(), "ghost.stl"}, Pose::Identity(), std::nullopt, ""});
  scene.addObject(unloaded);
  GltfSummary summary;
  const Glb glb = parseGlb(sceneToGlb(scene, {}, &summary));
  EXPECT_EQ(glb.document["accessors"].size(), 6U) << "positions, normals and indices of two scales";
  EXPECT_EQ(bodiesOf(glb).size(), 4U);
  EXPECT_EQ(std::count_if(glb.document["nodes"].begin(), glb.document["nodes"].end(), [](const json& node) { return node.contains("mesh"); }), 3);
  EXPECT_EQ(summary.unloadedMeshes, 1);
  EXPECT_EQ(glb.document["meshes"].size(), 2U);
  EXPECT_EQ(checkPrimitives(glb), 2U * 12U);
}

}  // namespace
}  // namespace lang2manip
