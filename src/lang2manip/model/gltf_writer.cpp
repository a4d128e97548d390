#include "lang2manip/model/gltf_writer.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <tuple>

#include "lang2manip/core/error.hpp"

namespace lang2manip {
namespace {

using json = nlohmann::json;

constexpr std::uint32_t kGlbMagic = 0x46546C67;       // "glTF"
constexpr std::uint32_t kJsonChunk = 0x4E4F534A;      // "JSON"
constexpr std::uint32_t kBinaryChunk = 0x004E4942;    // "BIN\0"
constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

void addTriangle(TriangleMesh& mesh, int a, int b, int c) { mesh.triangles.push_back({a, b, c}); }

TriangleMesh boxMesh(const Vector3& size) {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.emplace_back((i & 1 ? 0.5 : -0.5) * size.x(), (i & 2 ? 0.5 : -0.5) * size.y(), (i & 4 ? 0.5 : -0.5) * size.z());
  }
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    addTriangle(mesh, f[0], f[1], f[2]);
    addTriangle(mesh, f[0], f[2], f[3]);
  }
  return mesh;
}

TriangleMesh cylinderMesh(double radius, double length, int segments) {
  TriangleMesh mesh;
  for (int i = 0; i < segments; ++i) {
    const double angle = 2.0 * M_PI * i / segments;
    for (const double z : {-0.5 * length, 0.5 * length}) mesh.vertices.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
  }
  const int bottom = static_cast<int>(mesh.vertices.size());
  mesh.vertices.emplace_back(0.0, 0.0, -0.5 * length);
  mesh.vertices.emplace_back(0.0, 0.0, 0.5 * length);
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % segments;
    addTriangle(mesh, 2 * i, 2 * j, 2 * j + 1);
    addTriangle(mesh, 2 * i, 2 * j + 1, 2 * i + 1);
    addTriangle(mesh, bottom, 2 * j, 2 * i);
    addTriangle(mesh, bottom + 1, 2 * i + 1, 2 * j + 1);
  }
  return mesh;
}

TriangleMesh sphereMesh(double radius, int segments) {
  TriangleMesh mesh;
  const int rings = std::max(2, segments / 2);
  mesh.vertices.emplace_back(0.0, 0.0, -radius);
  for (int r = 1; r < rings; ++r) {
    const double polar = M_PI * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double azimuth = 2.0 * M_PI * s / segments;
      mesh.vertices.emplace_back(radius * std::sin(polar) * std::cos(azimuth), radius * std::sin(polar) * std::sin(azimuth),
                                 -radius * std::cos(polar));
    }
  }
  const int top = static_cast<int>(mesh.vertices.size());
  mesh.vertices.emplace_back(0.0, 0.0, radius);
  const auto at = [segments](int ring, int s) { return 1 + (ring - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) {
    addTriangle(mesh, 0, at(1, s + 1), at(1, s));
    addTriangle(mesh, top, at(rings - 1, s), at(rings - 1, s + 1));
    for (int r = 1; r + 1 < rings; ++r) {
      addTriangle(mesh, at(r, s), at(r, s + 1), at(r + 1, s + 1));
      addTriangle(mesh, at(r, s), at(r + 1, s + 1), at(r + 1, s));
    }
  }
  return mesh;
}

/// Appends `bytes` to the binary chunk, 4-byte aligned; returns the new buffer view's index.
class BinaryBuilder {
 public:
  int view(const void* data, std::size_t size, int target, json& views) {
    while (bytes_.size() % 4 != 0) bytes_.push_back('\0');
    const std::size_t offset = bytes_.size();
    bytes_.append(static_cast<const char*>(data), size);
    views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}, {"target", target}});
    return static_cast<int>(views.size()) - 1;
  }
  [[nodiscard]] std::string padded() const {
    std::string result = bytes_;
    while (result.size() % 4 != 0) result.push_back('\0');
    return result;
  }

 private:
  std::string bytes_;
};

json quaternionOf(const Matrix3& rotation) {
  const Eigen::Quaterniond q(rotation);
  return {q.x(), q.y(), q.z(), q.w()};
}

class GlbBuilder {
 public:
  explicit GlbBuilder(const GltfOptions& options) : options_(options) {
    document_["asset"] = {{"version", "2.0"}, {"generator", "lang2manip"}};
    for (const char* key : {"nodes", "meshes", "materials", "accessors", "bufferViews"}) document_[key] = json::array();
    // World z up -> glTF y up: a quarter turn about x.
    document_["nodes"].push_back({{"name", "world (z up)"}, {"rotation", {-std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5)}},
                                  {"children", json::array()}});
  }

  void addShapes(const std::string& name, const std::vector<Shape>& visuals, const std::vector<Shape>& collisions, const Pose& X_WF) {
    const std::vector<Shape>& shapes = options_.collision || visuals.empty() ? collisions : visuals;
    for (std::size_t i = 0; i < shapes.size(); ++i) addShape(name + (shapes.size() > 1 ? "/" + std::to_string(i + 1) : ""), shapes[i], X_WF);
  }

  std::string finish(GltfSummary* summary) {
    document_["scenes"] = json::array({{{"nodes", {0}}}});
    document_["scene"] = 0;
    const std::string binary = binary_.padded();
    document_["buffers"] = json::array({{{"byteLength", binary.size()}}});
    std::string text = document_.dump();
    while (text.size() % 4 != 0) text.push_back(' ');
    std::string glb;
    const auto word = [&glb](std::uint32_t value) {
      char bytes[4];
      std::memcpy(bytes, &value, 4);
      glb.append(bytes, 4);
    };
    word(kGlbMagic);
    word(2);
    word(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + binary.size()));
    word(static_cast<std::uint32_t>(text.size()));
    word(kJsonChunk);
    glb += text;
    word(static_cast<std::uint32_t>(binary.size()));
    word(kBinaryChunk);
    glb += binary;
    if (summary) {
      summary_.nodes = static_cast<int>(document_["nodes"].size()) - 1;
      summary_.meshes = static_cast<int>(document_["meshes"].size());
      *summary = summary_;
    }
    return glb;
  }

 private:
  void addShape(const std::string& name, const Shape& shape, const Pose& X_WF) {
    const auto* mesh = std::get_if<MeshGeometry>(&shape.geometry);
    if (mesh && !mesh->mesh) {
      ++summary_.unloadedMeshes;
      return;
    }
    const int index = meshIndex(shape);
    if (index < 0) return;
    const Pose X_WG = X_WF * shape.origin;
    json node{{"name", name}, {"mesh", index}, {"translation", {X_WG.translation().x(), X_WG.translation().y(), X_WG.translation().z()}},
              {"rotation", quaternionOf(X_WG.linear())}};
    document_["nodes"].push_back(std::move(node));
    document_["nodes"][0]["children"].push_back(static_cast<int>(document_["nodes"].size()) - 1);
  }

  /// The glTF mesh of the shape's geometry and colour (built once per geometry and colour).
  int meshIndex(const Shape& shape) {
    const Vector4 rgba = shape.material ? shape.material->rgba : Vector4(0.7, 0.7, 0.7, 1.0);
    const auto [positions, indices] = geometryAccessors(shape.geometry);
    if (positions < 0) return -1;
    const auto key = std::make_tuple(positions, rgba.x(), rgba.y(), rgba.z(), rgba.w());
    if (const auto found = meshes_.find(key); found != meshes_.end()) return found->second;
    json material{{"pbrMetallicRoughness", {{"baseColorFactor", {rgba.x(), rgba.y(), rgba.z(), rgba.w()}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.8}}},
                  {"doubleSided", true}};
    if (rgba.w() < 1.0) material["alphaMode"] = "BLEND";
    document_["materials"].push_back(std::move(material));
    document_["meshes"].push_back({{"primitives", json::array({{{"attributes", {{"POSITION", positions}}}, {"indices", indices},
                                                                {"material", static_cast<int>(document_["materials"].size()) - 1}}})}});
    return meshes_[key] = static_cast<int>(document_["meshes"].size()) - 1;
  }

  /// (POSITION, indices) accessors of a geometry, written once per mesh and scale or primitive.
  std::pair<int, int> geometryAccessors(const Geometry& geometry) {
    using Key = std::tuple<const TriangleMesh*, double, double, double, int>;
    Key tuple{nullptr, 0.0, 0.0, 0.0, 0};
    if (const auto* mesh = std::get_if<MeshGeometry>(&geometry)) tuple = Key{mesh->mesh.get(), mesh->scale.x(), mesh->scale.y(), mesh->scale.z(), 0};
    if (const auto* box = std::get_if<Box>(&geometry)) tuple = Key{nullptr, box->size.x(), box->size.y(), box->size.z(), 1};
    if (const auto* sphere = std::get_if<Sphere>(&geometry)) tuple = Key{nullptr, sphere->radius, 0.0, 0.0, 2};
    if (const auto* cylinder = std::get_if<Cylinder>(&geometry)) tuple = Key{nullptr, cylinder->radius, cylinder->length, 0.0, 3};
    if (const auto found = accessors_.find(tuple); found != accessors_.end()) return found->second;
    const TriangleMesh triangles = tessellated(geometry, options_.roundSegments);
    if (triangles.triangles.empty()) return accessors_[tuple] = {-1, -1};
    std::vector<float> positions;
    Vector3 low = Vector3::Constant(std::numeric_limits<double>::infinity());
    Vector3 high = -low;
    for (const Vector3& v : triangles.vertices) {
      for (int k = 0; k < 3; ++k) positions.push_back(static_cast<float>(v[k]));
      low = low.cwiseMin(v.cast<float>().cast<double>());
      high = high.cwiseMax(v.cast<float>().cast<double>());
    }
    std::vector<std::uint32_t> indices;
    for (const auto& t : triangles.triangles) {
      for (const int i : t) indices.push_back(static_cast<std::uint32_t>(i));
    }
    json& views = document_["bufferViews"];
    const int positionView = binary_.view(positions.data(), positions.size() * sizeof(float), kArrayBuffer, views);
    const int indexView = binary_.view(indices.data(), indices.size() * sizeof(std::uint32_t), kElementArrayBuffer, views);
    json& accessors = document_["accessors"];
    accessors.push_back({{"bufferView", positionView}, {"componentType", kFloat}, {"count", triangles.vertices.size()}, {"type", "VEC3"},
                         {"min", {low.x(), low.y(), low.z()}}, {"max", {high.x(), high.y(), high.z()}}});
    accessors.push_back({{"bufferView", indexView}, {"componentType", kUnsignedInt}, {"count", indices.size()}, {"type", "SCALAR"}});
    summary_.triangles += static_cast<int>(triangles.triangles.size());
    const int count = static_cast<int>(accessors.size());
    return accessors_[tuple] = {count - 2, count - 1};
  }

  const GltfOptions& options_;
  json document_;
  BinaryBuilder binary_;
  GltfSummary summary_;
  std::map<std::tuple<const TriangleMesh*, double, double, double, int>, std::pair<int, int>> accessors_;
  std::map<std::tuple<int, double, double, double, double>, int> meshes_;
};

void requireRoundSegments(int roundSegments) {
  if (roundSegments < 3) throw InputError("glTF: a round shape needs at least 3 segments, got " + std::to_string(roundSegments));
}

}  // namespace

TriangleMesh tessellated(const Geometry& geometry, int roundSegments) {
  requireRoundSegments(roundSegments);
  if (const auto* box = std::get_if<Box>(&geometry)) return boxMesh(box->size);
  if (const auto* sphere = std::get_if<Sphere>(&geometry)) return sphereMesh(sphere->radius, roundSegments);
  if (const auto* cylinder = std::get_if<Cylinder>(&geometry)) return cylinderMesh(cylinder->radius, cylinder->length, roundSegments);
  const auto& mesh = std::get<MeshGeometry>(geometry);
  TriangleMesh scaled;
  if (!mesh.mesh) return scaled;
  scaled.source = mesh.mesh->source;
  scaled.triangles = mesh.mesh->triangles;
  for (const Vector3& v : mesh.mesh->vertices) scaled.vertices.push_back(v.cwiseProduct(mesh.scale));
  return scaled;
}

std::string sceneToGlb(const Scene& scene, const GltfOptions& options, GltfSummary* summary) {
  requireRoundSegments(options.roundSegments);
  GlbBuilder builder(options);
  for (const SceneRobot& robot : scene.robots()) {
    const std::vector<Pose> X_BL = robot.model->linkPoses(robot.configuration);
    for (std::size_t l = 0; l < robot.model->links().size(); ++l) {
      const Link& link = robot.model->links()[l];
      builder.addShapes(robot.name + "/" + link.name, link.visuals, link.collisions, robot.basePose * X_BL[l]);
    }
  }
  for (const SceneObject& object : scene.objects()) {
    Pose X_WO = object.pose;
    if (const Attachment* held = scene.findAttachment(object.name)) {
      const SceneRobot& robot = scene.robot(held->robot);
      X_WO = robot.basePose * robot.model->linkPoses(robot.configuration)[static_cast<std::size_t>(robot.model->linkIndex(held->link))] *
             held->linkToObject;
    }
    builder.addShapes(object.name, object.visuals, object.collisions, X_WO);
  }
  return builder.finish(summary);
}

}  // namespace lang2manip
