#include "lang2manip/model/glb_builder.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <tuple>

#include "lang2manip/core/error.hpp"
#include "lang2manip/model/gltf_writer.hpp"
#include "lang2manip/model/mesh_shading.hpp"

namespace lang2manip {
namespace {

using json = nlohmann::json;

constexpr std::uint32_t kGlbMagic = 0x46546C67;     // "glTF"
constexpr std::uint32_t kJsonChunk = 0x4E4F534A;    // "JSON"
constexpr std::uint32_t kBinaryChunk = 0x004E4942;  // "BIN\0"
constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kLines = 1;
constexpr int kLineStrip = 3;

json quaternionOf(const Matrix3& rotation) {
  const Eigen::Quaterniond q(rotation);
  return {q.x(), q.y(), q.z(), q.w()};
}

json transformOf(const Pose& pose) {
  return {{"translation", {pose.translation().x(), pose.translation().y(), pose.translation().z()}}, {"rotation", quaternionOf(pose.linear())}};
}

std::vector<float> floatsOf(const std::vector<Vector3>& points) {
  std::vector<float> values;
  for (const Vector3& p : points) {
    for (int k = 0; k < 3; ++k) values.push_back(static_cast<float>(p[k]));
  }
  return values;
}

}  // namespace

struct GlbBuilder::Impl {
  GltfGeometry geometry;
  int roundSegments;
  json document;
  std::string binary;
  GltfSummary summary;
  /// The POSITION, NORMAL and index accessors of a drawn geometry.
  struct DrawnGeometry {
    int positions = -1;
    int normals = -1;
    int indices = -1;
    /// For a mesh of several colours: each colour (RGB) and the indices of its triangles.
    std::vector<std::pair<Vector3, int>> colourGroups;
  };
  std::map<std::tuple<const TriangleMesh*, double, double, double, int>, DrawnGeometry> accessors;
  std::map<std::tuple<int, double, double, double, double>, int> meshes;
  std::map<std::string, int> groups;

  int view(const void* data, std::size_t size, int target) {
    while (binary.size() % 4 != 0) binary.push_back('\0');
    json view{{"buffer", 0}, {"byteOffset", binary.size()}, {"byteLength", size}};
    if (target != 0) view["target"] = target;
    binary.append(static_cast<const char*>(data), size);
    document["bufferViews"].push_back(std::move(view));
    return static_cast<int>(document["bufferViews"].size()) - 1;
  }

  int accessor(json value) {
    document["accessors"].push_back(std::move(value));
    return static_cast<int>(document["accessors"].size()) - 1;
  }

  /// A VEC3 float accessor of `values` (x y z ...), with its bounds (positions and normals).
  int positions(const std::vector<float>& values, int target) {
    Vector3 low = Vector3::Constant(std::numeric_limits<double>::infinity());
    Vector3 high = -low;
    for (std::size_t i = 0; i + 2 < values.size(); i += 3) {
      const Vector3 v(values[i], values[i + 1], values[i + 2]);
      low = low.cwiseMin(v);
      high = high.cwiseMax(v);
    }
    const int bufferView = view(values.data(), values.size() * sizeof(float), target);
    return accessor({{"bufferView", bufferView}, {"componentType", kFloat}, {"count", values.size() / 3}, {"type", "VEC3"},
                     {"min", {low.x(), low.y(), low.z()}}, {"max", {high.x(), high.y(), high.z()}}});
  }

  int node(json value, int parent) {
    document["nodes"].push_back(std::move(value));
    const int index = static_cast<int>(document["nodes"].size()) - 1;
    document["nodes"][static_cast<std::size_t>(parent)]["children"].push_back(index);
    return index;
  }

  int material(const Vector4& rgba) {
    json value{{"pbrMetallicRoughness", {{"baseColorFactor", {rgba.x(), rgba.y(), rgba.z(), rgba.w()}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.8}}},
               {"doubleSided", true}};
    if (rgba.w() < 1.0) value["alphaMode"] = "BLEND";
    document["materials"].push_back(std::move(value));
    return static_cast<int>(document["materials"].size()) - 1;
  }

  /// The accessors of a geometry, shaded (mesh_shading.hpp), written once per mesh and scale or
  /// primitive.
  DrawnGeometry geometryAccessors(const Geometry& shape) {
    using Key = std::tuple<const TriangleMesh*, double, double, double, int>;
    Key key{nullptr, 0.0, 0.0, 0.0, 0};
    if (const auto* mesh = std::get_if<MeshGeometry>(&shape)) key = Key{mesh->mesh.get(), mesh->scale.x(), mesh->scale.y(), mesh->scale.z(), 0};
    if (const auto* box = std::get_if<Box>(&shape)) key = Key{nullptr, box->size.x(), box->size.y(), box->size.z(), 1};
    if (const auto* sphere = std::get_if<Sphere>(&shape)) key = Key{nullptr, sphere->radius, 0.0, 0.0, 2};
    if (const auto* cylinder = std::get_if<Cylinder>(&shape)) key = Key{nullptr, cylinder->radius, cylinder->length, 0.0, 3};
    if (const auto found = accessors.find(key); found != accessors.end()) return found->second;
    const ShadedMesh shaded = shadedMesh(tessellated(shape, roundSegments));
    if (shaded.triangles.empty()) return accessors[key] = {};
    std::vector<std::uint32_t> indices;
    for (const auto& t : shaded.triangles) {
      for (const int i : t) indices.push_back(static_cast<std::uint32_t>(i));
    }
    DrawnGeometry drawn;
    drawn.positions = positions(floatsOf(shaded.vertices), kArrayBuffer);
    drawn.normals = positions(floatsOf(shaded.normals), kArrayBuffer);
    drawn.indices = indexAccessor(indices);
    drawn.colourGroups = colourGroups(std::get_if<MeshGeometry>(&shape), shaded);
    summary.triangles += static_cast<int>(shaded.triangles.size());
    return accessors[key] = drawn;
  }

  int indexAccessor(const std::vector<std::uint32_t>& indices) {
    const int indexView = view(indices.data(), indices.size() * sizeof(std::uint32_t), kElementArrayBuffer);
    return accessor({{"bufferView", indexView}, {"componentType", kUnsignedInt}, {"count", indices.size()}, {"type", "SCALAR"}});
  }

  /// The triangles of each colour of a mesh whose file gives several (none otherwise); triangles
  /// without a colour are drawn grey.
  std::vector<std::pair<Vector3, int>> colourGroups(const MeshGeometry* mesh, const ShadedMesh& shaded) {
    if (mesh == nullptr || !mesh->mesh || mesh->mesh->palette.size() < 2) return {};
    const TriangleMesh& source = *mesh->mesh;
    std::map<int, std::vector<std::uint32_t>> byColour;
    for (std::size_t t = 0; t < shaded.triangles.size(); ++t) {
      const auto from = static_cast<std::size_t>(shaded.sourceTriangles[t]);
      const int colour = from < source.triangleColours.size() ? source.triangleColours[from] : -1;
      for (const int i : shaded.triangles[t]) byColour[colour].push_back(static_cast<std::uint32_t>(i));
    }
    std::vector<std::pair<Vector3, int>> coloured;
    for (const auto& [colour, indices] : byColour) {
      const bool known = colour >= 0 && static_cast<std::size_t>(colour) < source.palette.size();
      coloured.emplace_back(known ? source.palette[static_cast<std::size_t>(colour)] : Vector3::Constant(0.7), indexAccessor(indices));
    }
    return coloured;
  }

  /// The glTF mesh of a shape's geometry and colour (built once per geometry and colour).
  int meshIndex(const Shape& shape) {
    Vector4 rgba(0.7, 0.7, 0.7, 1.0);
    if (shape.material) {
      rgba = shape.material->rgba;
    } else if (const auto* mesh = std::get_if<MeshGeometry>(&shape.geometry); mesh != nullptr && mesh->mesh && mesh->mesh->colour) {
      rgba.head<3>() = *mesh->mesh->colour;  // the mesh file's own colour
    }
    const DrawnGeometry drawn = geometryAccessors(shape.geometry);
    if (drawn.positions < 0) return -1;
    // A mesh file's own colours, unless the description gives the shape one (-1: that marker).
    const bool ownColours = !shape.material && !drawn.colourGroups.empty();
    const auto key = ownColours ? std::make_tuple(drawn.positions, -1.0, -1.0, -1.0, -1.0)
                                : std::make_tuple(drawn.positions, rgba.x(), rgba.y(), rgba.z(), rgba.w());
    if (const auto found = meshes.find(key); found != meshes.end()) return found->second;
    const json attributes{{"POSITION", drawn.positions}, {"NORMAL", drawn.normals}};
    json primitives = json::array();
    if (ownColours) {
      for (const auto& [rgb, indices] : drawn.colourGroups) {
        primitives.push_back({{"attributes", attributes}, {"indices", indices}, {"material", material(Vector4(rgb.x(), rgb.y(), rgb.z(), 1.0))}});
      }
    } else {
      primitives.push_back({{"attributes", attributes}, {"indices", drawn.indices}, {"material", material(rgba)}});
    }
    document["meshes"].push_back({{"primitives", std::move(primitives)}});
    return meshes[key] = static_cast<int>(document["meshes"].size()) - 1;
  }

  void addShapes(const std::string& name, const std::vector<Shape>& shapes, int parent) {
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      const Shape& shape = shapes[i];
      const auto* mesh = std::get_if<MeshGeometry>(&shape.geometry);
      if (mesh && !mesh->mesh) {
        ++summary.unloadedMeshes;
        continue;
      }
      const int mesh_ = meshIndex(shape);
      if (mesh_ < 0) continue;
      json value = transformOf(shape.origin);
      value["name"] = name + (shapes.size() > 1 ? "/" + std::to_string(i + 1) : "");
      value["mesh"] = mesh_;
      node(std::move(value), parent);
    }
  }

  int group(const std::string& name) {
    if (const auto found = groups.find(name); found != groups.end()) return found->second;
    return groups[name] = node({{"name", name}, {"children", json::array()}}, 0);
  }

  void addLineMesh(const std::string& groupName, const std::string& name, const std::vector<Vector3>& points, int mode, const Vector4& rgba) {
    if (points.size() < 2) return;
    const int position = positions(floatsOf(points), kArrayBuffer);
    document["meshes"].push_back({{"primitives", json::array({{{"attributes", {{"POSITION", position}}}, {"mode", mode}, {"material", material(rgba)}}})}});
    node({{"name", name}, {"mesh", static_cast<int>(document["meshes"].size()) - 1}}, group(groupName));
  }
};

GlbBuilder::GlbBuilder(GltfGeometry geometry, int roundSegments) : impl_(std::make_unique<Impl>()) {
  if (roundSegments < 3) throw InputError("glTF: a round shape needs at least 3 segments, got " + std::to_string(roundSegments));
  impl_->geometry = geometry;
  impl_->roundSegments = roundSegments;
  json& document = impl_->document;
  document["asset"] = {{"version", "2.0"}, {"generator", "lang2manip"}};
  for (const char* key : {"nodes", "meshes", "materials", "accessors", "bufferViews"}) document[key] = json::array();
  // World z up -> glTF y up: a quarter turn about x.
  document["nodes"].push_back({{"name", "world (z up)"}, {"rotation", {-std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5)}}, {"children", json::array()}});
}

GlbBuilder::~GlbBuilder() = default;

int GlbBuilder::addBody(const std::string& name, const std::string& kind, const std::vector<Shape>& visuals,
                        const std::vector<Shape>& collisions, const Pose& X_WB) {
  json value = transformOf(X_WB);
  value["name"] = name;
  value["extras"] = {{"kind", kind}};
  value["children"] = json::array();
  const int body = impl_->node(std::move(value), 0);
  const GltfGeometry geometry = impl_->geometry;
  if (geometry != GltfGeometry::kCollision) {
    const bool drawnByCollision = visuals.empty() && kind != "link";
    impl_->addShapes(name, drawnByCollision ? collisions : visuals, impl_->node({{"name", "visual"}, {"children", json::array()}}, body));
  }
  if (geometry != GltfGeometry::kVisual) {
    impl_->addShapes(name, collisions, impl_->node({{"name", "collision"}, {"children", json::array()}}, body));
  }
  return body;
}

void GlbBuilder::addPolyline(const std::string& group, const std::string& name, const std::vector<Vector3>& points, const Vector4& rgba) {
  impl_->addLineMesh(group, name, points, kLineStrip, rgba);
}

void GlbBuilder::addLines(const std::string& group, const std::string& name, const std::vector<std::pair<Vector3, Vector3>>& lines,
                          const Vector4& rgba) {
  std::vector<Vector3> points;
  for (const auto& [a, b] : lines) {
    points.push_back(a);
    points.push_back(b);
  }
  impl_->addLineMesh(group, name, points, kLines, rgba);
}

void GlbBuilder::addAnimation(const std::string& name, const std::vector<double>& times,
                              const std::vector<std::pair<int, std::vector<Pose>>>& tracks) {
  if (times.empty() || tracks.empty()) return;
  for (std::size_t i = 1; i < times.size(); ++i) {
    if (!(times[i] > times[i - 1])) throw InputError("glTF animation " + name + ": times must increase (sample " + std::to_string(i) + ")");
  }
  std::vector<float> seconds(times.begin(), times.end());
  const int timeView = impl_->view(seconds.data(), seconds.size() * sizeof(float), 0);
  const int input = impl_->accessor({{"bufferView", timeView}, {"componentType", kFloat}, {"count", seconds.size()}, {"type", "SCALAR"},
                                     {"min", {seconds.front()}}, {"max", {seconds.back()}}});
  json samplers = json::array();
  json channels = json::array();
  for (const auto& [node, poses] : tracks) {
    if (poses.size() != times.size()) throw InputError("glTF animation " + name + ": a track has " + std::to_string(poses.size()) + " poses for " + std::to_string(times.size()) + " times");
    std::vector<float> translations;
    std::vector<float> rotations;
    Eigen::Quaterniond previous = Eigen::Quaterniond::Identity();
    for (const Pose& pose : poses) {
      for (int k = 0; k < 3; ++k) translations.push_back(static_cast<float>(pose.translation()[k]));
      Eigen::Quaterniond q(pose.linear());
      // Consecutive quaternions on the same side, so that interpolation takes the short way.
      if (!rotations.empty() && q.dot(previous) < 0.0) q.coeffs() *= -1.0;
      previous = q;
      for (const double c : {q.x(), q.y(), q.z(), q.w()}) rotations.push_back(static_cast<float>(c));
    }
    const int translation = impl_->accessor({{"bufferView", impl_->view(translations.data(), translations.size() * sizeof(float), 0)},
                                             {"componentType", kFloat}, {"count", poses.size()}, {"type", "VEC3"}});
    const int rotation = impl_->accessor({{"bufferView", impl_->view(rotations.data(), rotations.size() * sizeof(float), 0)},
                                          {"componentType", kFloat}, {"count", poses.size()}, {"type", "VEC4"}});
    for (const auto& [output, path] : {std::pair{translation, "translation"}, std::pair{rotation, "rotation"}}) {
      samplers.push_back({{"input", input}, {"output", output}, {"interpolation", "LINEAR"}});
      channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", node}, {"path", path}}}});
    }
  }
  impl_->document["animations"].push_back({{"name", name}, {"samplers", samplers}, {"channels", channels}});
}

std::string GlbBuilder::finish(GltfSummary* summary) {
  json& document = impl_->document;
  document["scenes"] = json::array({{{"nodes", {0}}}});
  document["scene"] = 0;
  const int nodes = static_cast<int>(document["nodes"].size()) - 1;
  const int meshes = static_cast<int>(document["meshes"].size());
  // glTF allows no empty arrays: groups left without shapes lose "children", unused kinds vanish.
  for (json& node : document["nodes"]) {
    if (node.contains("children") && node["children"].empty()) node.erase("children");
  }
  for (const char* key : {"meshes", "materials", "accessors", "bufferViews"}) {
    if (document[key].empty()) document.erase(key);
  }
  std::string binary = impl_->binary;
  while (binary.size() % 4 != 0) binary.push_back('\0');
  if (!binary.empty()) document["buffers"] = json::array({{{"byteLength", binary.size()}}});
  std::string text = document.dump(-1, ' ', false, json::error_handler_t::replace);
  while (text.size() % 4 != 0) text.push_back(' ');
  std::string glb;
  const auto word = [&glb](std::uint32_t value) {
    char bytes[4];
    std::memcpy(bytes, &value, 4);
    glb.append(bytes, 4);
  };
  word(kGlbMagic);
  word(2);
  word(static_cast<std::uint32_t>(12 + 8 + text.size() + (binary.empty() ? 0 : 8 + binary.size())));
  word(static_cast<std::uint32_t>(text.size()));
  word(kJsonChunk);
  glb += text;
  if (!binary.empty()) {
    word(static_cast<std::uint32_t>(binary.size()));
    word(kBinaryChunk);
    glb += binary;
  }
  if (summary) {
    impl_->summary.nodes = nodes;
    impl_->summary.meshes = meshes;
    *summary = impl_->summary;
  }
  return glb;
}

}  // namespace lang2manip
