#include "lang2manip/model/collada_mesh_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/model/mesh_builder.hpp"
#include "lang2manip/model/xml_document.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;

/// The positions of one <source>: point i is values[offset + i * stride + 0..2].
struct PositionArray {
  std::vector<double> values;
  std::size_t offset = 0;
  std::size_t stride = 3;
  std::size_t count = 0;
};

/// How a primitive element's <p> lists are read: `stride` indices per vertex, the position index
/// at `vertexOffset`.
struct IndexLayout {
  std::size_t stride = 1;
  std::size_t vertexOffset = 0;
};

bool isNamed(const pugi::xml_node& node, const char* name) { return std::strcmp(node.name(), name) == 0; }

class ColladaReader {
 public:
  explicit ColladaReader(const fs::path& path)
      : path_(path), document_(XmlDocument::loadFile(path, "COLLADA file")) {
    indexIds();
  }

  TriangleMesh read() {
    const pugi::xml_node root = document_.root();
    const Eigen::Affine3d X_RS(Eigen::Scaling(unitInMetres(root)));
    const pugi::xml_node scene = visualScene(root);
    if (scene) {
      for (const pugi::xml_node& node : scene.children("node")) addNode(node, X_RS, 1);
    } else {
      for (const pugi::xml_node& library : root.children("library_geometries")) {
        for (const pugi::xml_node& geometry : library.children("geometry")) addGeometry(geometry, X_RS);
      }
    }
    return builder_.finish(path_);
  }

 private:
  // -------------------------------------------------------------------------------------------
  // Document structure

  void indexIds() {
    struct IdCollector final : pugi::xml_tree_walker {
      std::unordered_map<std::string, pugi::xml_node>* ids = nullptr;
      bool for_each(pugi::xml_node& node) override {
        const pugi::xml_attribute id = node.attribute("id");
        if (id) ids->emplace(id.value(), node);  // the first of duplicate ids wins
        return true;
      }
    } collector;
    collector.ids = &ids_;
    document_.root().traverse(collector);
  }

  [[noreturn]] void fail(const pugi::xml_node& node, const std::string& what) const {
    throw InputError(document_.where(node), "COLLADA " + what);
  }

  std::string elementName(const pugi::xml_node& node) const { return std::string("<") + node.name() + ">"; }

  /// The element a "#id" URL attribute of `node` names.
  pugi::xml_node target(const pugi::xml_node& node, const char* attribute) const {
    const std::string url = document_.requiredAttribute(node, attribute);
    if (url.empty() || url[0] != '#') {
      fail(node, elementName(node) + " " + attribute + " \"" + url.substr(0, 80) +
                     "\" is not a \"#id\" reference within the file (other files are not read)");
    }
    const auto found = ids_.find(url.substr(1));
    if (found == ids_.end()) {
      fail(node, elementName(node) + " " + attribute + " \"" + url.substr(0, 80) + "\" names no element");
    }
    return found->second;
  }

  /// Like target(), but an element of that id among the children and grandchildren of `scope`
  /// comes first: exporters repeat the ids of sources in each geometry (as Kautham's Robotiq
  /// meshes do), and a mesh means its own.
  pugi::xml_node targetWithin(const pugi::xml_node& node, const char* attribute, const pugi::xml_node& scope) const {
    const std::string url = node.attribute(attribute).value();
    if (!url.empty() && url[0] == '#') {
      const std::string_view id = std::string_view(url).substr(1);
      for (const pugi::xml_node& child : scope.children()) {
        if (child.attribute("id").value() == id) return child;
        for (const pugi::xml_node& grandchild : child.children()) {
          if (grandchild.attribute("id").value() == id) return grandchild;
        }
      }
    }
    return target(node, attribute);
  }

  pugi::xml_node requiredChild(const pugi::xml_node& node, const char* name) const {
    const pugi::xml_node child = node.child(name);
    if (!child) fail(node, elementName(node) + " has no <" + name + ">");
    return child;
  }

  double unitInMetres(const pugi::xml_node& root) const {
    const pugi::xml_node unit = root.child("asset").child("unit");
    if (!unit) return 1.0;
    const double metres = document_.numberAttribute(unit, "meter", 1.0);
    if (metres <= 0.0) fail(unit, "<unit> meter must be positive");
    return metres;
  }

  pugi::xml_node visualScene(const pugi::xml_node& root) const {
    const pugi::xml_node instance = root.child("scene").child("instance_visual_scene");
    if (instance) return target(instance, "url");
    return root.child("library_visual_scenes").child("visual_scene");
  }

  // -------------------------------------------------------------------------------------------
  // Numbers

  std::vector<double> numbers(const pugi::xml_node& node, std::size_t expected = 0) const {
    std::vector<double> values =
        parseNumberList(node.text().get(), "COLLADA " + elementName(node), document_.where(node));
    if (expected != 0 && values.size() != expected) {
      fail(node, elementName(node) + " needs " + std::to_string(expected) + " numbers, has " +
                     std::to_string(values.size()));
    }
    return values;
  }

  std::vector<std::size_t> indices(const pugi::xml_node& node) const {
    std::vector<std::size_t> values;
    const std::string_view text = node.text().get();
    std::size_t position = 0;
    while (position < text.size()) {
      position = text.find_first_not_of(" \t\r\n", position);
      if (position == std::string_view::npos) break;
      const std::size_t end = std::min(text.size(), text.find_first_of(" \t\r\n", position));
      std::uint32_t value = 0;
      const auto [stop, error] = std::from_chars(text.data() + position, text.data() + end, value);
      if (error != std::errc() || stop != text.data() + end) {
        fail(node, elementName(node) + " holds \"" + std::string(text.substr(position, std::min<std::size_t>(end - position, 20))) +
                       "\": index lists hold only unsigned integers below 2^32");
      }
      values.push_back(value);
      position = end;
    }
    return values;
  }

  std::size_t sizeAttribute(const pugi::xml_node& node, const char* name, std::size_t fallback) const {
    const double value = document_.numberAttribute(node, name, static_cast<double>(fallback));
    if (value < 0.0 || value > 1e9 || value != std::floor(value)) {
      fail(node, elementName(node) + " " + name + " must be a whole number in [0, 1e9]");
    }
    return static_cast<std::size_t>(value);
  }

  // -------------------------------------------------------------------------------------------
  // Nodes and instances

  Eigen::Affine3d localTransform(const pugi::xml_node& node) const {
    Eigen::Affine3d X = Eigen::Affine3d::Identity();
    for (const pugi::xml_node& child : node.children()) {
      if (isNamed(child, "matrix")) {
        const std::vector<double> m = numbers(child, 16);
        Eigen::Matrix4d matrix;
        for (int i = 0; i < 16; ++i) matrix(i / 4, i % 4) = m[static_cast<std::size_t>(i)];
        X = X * Eigen::Affine3d(matrix);
      } else if (isNamed(child, "translate")) {
        const std::vector<double> t = numbers(child, 3);
        X = X * Eigen::Translation3d(t[0], t[1], t[2]);
      } else if (isNamed(child, "rotate")) {
        const std::vector<double> r = numbers(child, 4);
        const Vector3 axis(r[0], r[1], r[2]);
        if (axis.norm() > 0.0) X = X * Eigen::AngleAxisd(r[3] * M_PI / 180.0, axis.normalized());
      } else if (isNamed(child, "scale")) {
        const std::vector<double> s = numbers(child, 3);
        X = X * Eigen::Scaling(s[0], s[1], s[2]);
      } else if (isNamed(child, "lookat") || isNamed(child, "skew")) {
        fail(child, elementName(child) + " transforms are not supported");
      }
    }
    return X;
  }

  void countInstance(const pugi::xml_node& node, int depth) {
    if (depth > kMaxXmlDepth) {
      fail(node, "instances nest more than " + std::to_string(kMaxXmlDepth) + " levels deep (a node that instances itself?)");
    }
    if (++instances_ > kMaxColladaInstances) {
      fail(node, "file expands to more than " + std::to_string(kMaxColladaInstances) + " node and geometry instances");
    }
  }

  void addNode(const pugi::xml_node& node, const Eigen::Affine3d& X_RP, int depth) {
    countInstance(node, depth);
    const Eigen::Affine3d X_RN = X_RP * localTransform(node);
    for (const pugi::xml_node& child : node.children()) {
      if (isNamed(child, "node")) {
        addNode(child, X_RN, depth + 1);
      } else if (isNamed(child, "instance_node")) {
        const pugi::xml_node instanced = target(child, "url");
        if (!isNamed(instanced, "node")) fail(child, "<instance_node> url names " + elementName(instanced) + ", not a <node>");
        addNode(instanced, X_RN, depth + 1);
      } else if (isNamed(child, "instance_geometry")) {
        countInstance(child, depth + 1);
        instance_ = child;
        addGeometry(target(child, "url"), X_RN);
      } else if (isNamed(child, "instance_controller")) {
        countInstance(child, depth + 1);
        instance_ = child;
        addController(target(child, "url"), X_RN);
      }
    }
  }

  void addController(const pugi::xml_node& controller, const Eigen::Affine3d& X_RN) {
    if (const pugi::xml_node skin = controller.child("skin")) {
      Eigen::Affine3d X_NB = Eigen::Affine3d::Identity();
      if (const pugi::xml_node bind = skin.child("bind_shape_matrix")) {
        const std::vector<double> m = numbers(bind, 16);
        for (int i = 0; i < 16; ++i) X_NB.matrix()(i / 4, i % 4) = m[static_cast<std::size_t>(i)];
      }
      addGeometry(target(skin, "source"), X_RN * X_NB);
    } else if (const pugi::xml_node morph = controller.child("morph")) {
      addGeometry(target(morph, "source"), X_RN);
    } else {
      fail(controller, elementName(controller) + " has neither <skin> nor <morph>");
    }
  }

  // -------------------------------------------------------------------------------------------
  // Geometry

  void addGeometry(const pugi::xml_node& geometry, const Eigen::Affine3d& X_RG) {
    if (!isNamed(geometry, "geometry")) fail(geometry, elementName(geometry) + " is referenced as a <geometry>");
    const pugi::xml_node mesh = geometry.child("mesh");
    if (!mesh) return;  // splines and convex hulls hold no triangles to read
    for (const pugi::xml_node& primitive : mesh.children()) {
      const std::string_view kind = primitive.name();
      if (kind == "triangles" || kind == "polylist" || kind == "polygons" || kind == "trifans" ||
          kind == "tristrips") {
        addPrimitive(primitive, X_RG);
      }
    }
  }

  /// The points of the <source> that a VERTEX input names, directly or through <vertices>.
  PositionArray positions(const pugi::xml_node& vertexInput, const pugi::xml_node& mesh) const {
    pugi::xml_node source = targetWithin(vertexInput, "source", mesh);
    if (isNamed(source, "vertices")) {
      pugi::xml_node position;
      for (const pugi::xml_node& input : source.children("input")) {
        if (std::string_view(input.attribute("semantic").value()) == "POSITION") position = input;
      }
      if (!position) fail(source, "<vertices> has no POSITION input");
      source = targetWithin(position, "source", mesh);
    }
    if (!isNamed(source, "source")) fail(vertexInput, "VERTEX input names " + elementName(source) + ", not a <source> or <vertices>");
    const pugi::xml_node accessor = requiredChild(requiredChild(source, "technique_common"), "accessor");
    const pugi::xml_node array = targetWithin(accessor, "source", source);
    if (!isNamed(array, "float_array")) fail(accessor, "<accessor> source names " + elementName(array) + ", not a <float_array>");
    PositionArray points{numbers(array), sizeAttribute(accessor, "offset", 0), sizeAttribute(accessor, "stride", 1),
                         sizeAttribute(accessor, "count", 0)};
    if (array.attribute("count") && sizeAttribute(array, "count", 0) != points.values.size()) {
      fail(array, "<float_array> count " + std::string(array.attribute("count").value()) + " but it holds " +
                      std::to_string(points.values.size()) + " numbers");
    }
    if (points.stride < 3) fail(accessor, "<accessor> of positions needs a stride of at least 3");
    if (points.count > 0 && points.offset + (points.count - 1) * points.stride + 3 > points.values.size()) {
      fail(accessor, "<accessor> reads " + std::to_string(points.count) + " points of stride " +
                         std::to_string(points.stride) + " from a <float_array> of " +
                         std::to_string(points.values.size()) + " numbers");
    }
    return points;
  }

  /// The element `url` ("#id") names, or an empty node.
  pugi::xml_node named(const std::string& url) const {
    if (url.size() < 2 || url[0] != '#') return {};
    const auto found = ids_.find(url.substr(1));
    return found == ids_.end() ? pugi::xml_node() : found->second;
  }

  /// The diffuse colour of the material `primitive` names: the symbol bound by the instance's
  /// <bind_material> (else the symbol as the material's id), its <instance_effect>, the effect's
  /// <diffuse><color>. None when a link is missing or the diffuse is a texture.
  std::optional<Vector3> diffuseColour(const pugi::xml_node& primitive) const {
    const std::string symbol = primitive.attribute("material").value();
    if (symbol.empty()) return std::nullopt;
    std::string material = "#" + symbol;
    for (const pugi::xml_node& bound : instance_.child("bind_material").child("technique_common").children("instance_material")) {
      if (symbol == bound.attribute("symbol").value()) material = bound.attribute("target").value();
    }
    const pugi::xml_node effect = named(named(material).child("instance_effect").attribute("url").value());
    for (const pugi::xml_node& technique : effect.child("profile_COMMON").children("technique")) {
      for (const pugi::xml_node& model : technique.children()) {
        const pugi::xml_node colour = model.child("diffuse").child("color");
        if (!colour) continue;
        const std::vector<double> rgba = numbers(colour);
        if (rgba.size() < 3) fail(colour, "<color> needs 3 or 4 numbers, has " + std::to_string(rgba.size()));
        return Vector3(rgba[0], rgba[1], rgba[2]);
      }
    }
    return std::nullopt;
  }

  void addPrimitive(const pugi::xml_node& primitive, const Eigen::Affine3d& X_RG) {
    builder_.setColour(diffuseColour(primitive));
    IndexLayout layout;
    pugi::xml_node vertexInput;
    for (const pugi::xml_node& input : primitive.children("input")) {
      const std::size_t offset = sizeAttribute(input, "offset", 0);
      layout.stride = std::max(layout.stride, offset + 1);
      if (std::string_view(input.attribute("semantic").value()) == "VERTEX") {
        vertexInput = input;
        layout.vertexOffset = offset;
      }
    }
    if (!vertexInput) fail(primitive, elementName(primitive) + " has no VERTEX input");
    const PositionArray points = positions(vertexInput, primitive.parent());
    std::vector<int> added(points.count, MeshBuilder::kInvalid);
    const auto vertex = [&](const pugi::xml_node& list, std::size_t index) {
      if (index >= points.count) {
        fail(list, "vertex index " + std::to_string(index) + " is beyond the " + std::to_string(points.count) + " positions");
      }
      if (added[index] == MeshBuilder::kInvalid) {
        const double* p = points.values.data() + points.offset + index * points.stride;
        added[index] = builder_.mergedVertex(X_RG * Vector3(p[0], p[1], p[2]));
      }
      return added[index];
    };
    const std::string_view kind = primitive.name();
    if (kind == "triangles" || kind == "polylist") {
      addPolygons(primitive, layout, vertex);
    } else {
      for (const pugi::xml_node& child : primitive.children()) {
        const pugi::xml_node list = isNamed(child, "ph") ? child.child("p") : child;
        if (isNamed(list, "p")) addPolygon(list, layout, indices(list), kind == "tristrips", vertex);
      }
    }
  }

  /// <triangles> (one <p>, three vertices a triangle) and <polylist> (one <p>, <vcount> vertices
  /// per polygon).
  template <typename Vertex>
  void addPolygons(const pugi::xml_node& primitive, const IndexLayout& layout, const Vertex& vertex) {
    const pugi::xml_node list = primitive.child("p");
    if (!list) return;  // a <triangles count="0">
    const std::vector<std::size_t> all = indices(list);
    if (all.size() % layout.stride != 0) {
      fail(list, "<p> holds " + std::to_string(all.size()) + " indices, not a multiple of the " +
                     std::to_string(layout.stride) + " inputs");
    }
    std::vector<std::size_t> sizes;
    if (isNamed(primitive, "polylist")) {
      sizes = indices(requiredChild(primitive, "vcount"));
    } else {
      sizes.assign(all.size() / layout.stride / 3, 3);
    }
    std::size_t next = 0;
    for (const std::size_t size : sizes) {
      if (size > (all.size() - next) / layout.stride) fail(list, "<p> ends before the polygons of <vcount>");
      const std::vector<std::size_t> polygon(all.begin() + static_cast<std::ptrdiff_t>(next),
                                             all.begin() + static_cast<std::ptrdiff_t>(next + size * layout.stride));
      addPolygon(list, layout, polygon, false, vertex);
      next += size * layout.stride;
    }
    if (next != all.size()) fail(list, "<p> holds more indices than its primitives use");
  }

  /// One polygon or fan (as a fan) or strip, from its interleaved indices.
  template <typename Vertex>
  void addPolygon(const pugi::xml_node& list, const IndexLayout& layout, const std::vector<std::size_t>& interleaved,
                  bool strip, const Vertex& vertex) {
    if (interleaved.size() % layout.stride != 0) {
      fail(list, "<p> holds " + std::to_string(interleaved.size()) + " indices, not a multiple of the " +
                     std::to_string(layout.stride) + " inputs");
    }
    corners_ += static_cast<long>(interleaved.size() / layout.stride);
    if (corners_ > kMaxColladaCorners) {
      fail(list, "file expands to more than " + std::to_string(kMaxColladaCorners) + " triangle corners");
    }
    std::vector<int> corners;
    corners.reserve(interleaved.size() / layout.stride);
    for (std::size_t i = layout.vertexOffset; i < interleaved.size(); i += layout.stride) {
      corners.push_back(vertex(list, interleaved[i]));
    }
    for (std::size_t i = 2; i < corners.size(); ++i) {
      if (!strip) {
        builder_.addTriangle(corners[0], corners[i - 1], corners[i]);
      } else if (i % 2 == 0) {
        builder_.addTriangle(corners[i - 2], corners[i - 1], corners[i]);
      } else {
        builder_.addTriangle(corners[i - 1], corners[i - 2], corners[i]);
      }
    }
  }

  fs::path path_;
  XmlDocument document_;
  std::unordered_map<std::string, pugi::xml_node> ids_;
  MeshBuilder builder_;
  /// The <instance_geometry> or <instance_controller> being read (its <bind_material>).
  pugi::xml_node instance_;
  int instances_ = 0;
  long corners_ = 0;
};

}  // namespace

TriangleMesh readColladaMesh(const fs::path& path) { return ColladaReader(path).read(); }

}  // namespace lang2manip
