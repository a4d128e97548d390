// Scenes as glTF binary: the file is read back and checked against the glTF 2.0 rules a viewer
// relies on (header, chunks, accessors inside their buffer views, indices inside their vertices,
// POSITION bounds), for primitives, meshes and the paper's scene.

#include "lang2manip/model/gltf_writer.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>

#include "lang2manip/core/error.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"

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

TEST(GltfWriter, ThePaperSceneIsAValidGlbWithEveryShape) {
  const Scene scene = readKauthamProblem(resolveProblem("panda_desk")).scene;
  GltfSummary summary;
  const Glb glb = parseGlb(sceneToGlb(scene, {}, &summary));
  EXPECT_EQ(glb.document["asset"]["version"], "2.0");
  EXPECT_EQ(checkPrimitives(glb), static_cast<std::size_t>(summary.triangles));
  const json& nodes = glb.document["nodes"];
  EXPECT_EQ(nodes.size(), static_cast<std::size_t>(summary.nodes) + 1);
  EXPECT_EQ(nodes[0]["children"].size(), static_cast<std::size_t>(summary.nodes));
  std::vector<std::string> names;
  for (const json& node : nodes) names.push_back(node["name"]);
  for (const char* expected : {"marker", "holder", "desk", "panda/panda_hand"}) {
    EXPECT_TRUE(std::any_of(names.begin(), names.end(), [&](const std::string& n) { return n.rfind(expected, 0) == 0; })) << expected;
  }
  // Every shape's node carries its world pose: the marker lies on the desk at (0.02, -0.18).
  for (const json& node : nodes) {
    if (node["name"] == "marker") {
      EXPECT_NEAR(node["translation"][1].get<double>(), -0.18, 0.01);
    }
  }
  // Collision geometry instead of visuals: a different, still valid file.
  GltfOptions collision;
  collision.collision = true;
  GltfSummary collisionSummary;
  const Glb collisionGlb = parseGlb(sceneToGlb(scene, collision, &collisionSummary));
  EXPECT_EQ(checkPrimitives(collisionGlb), static_cast<std::size_t>(collisionSummary.triangles));
  GltfOptions bad;
  bad.roundSegments = 0;
  EXPECT_THROW((void)sceneToGlb(scene, bad), InputError);
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
  EXPECT_EQ(glb.document["accessors"].size(), 4U);
  EXPECT_EQ(summary.nodes, 3);
  EXPECT_EQ(summary.unloadedMeshes, 1);
  EXPECT_EQ(glb.document["meshes"].size(), 2U);
  EXPECT_EQ(checkPrimitives(glb), 2U * 12U);
}

}  // namespace
}  // namespace lang2manip
