// checkGlb(): a GLB's chunks, and the indices and byte ranges of its glTF document, checked before
// a viewer is asked to draw it.

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/json_limits.hpp"
#include "lang2manip/model/viewer_document.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

constexpr std::uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kBinaryChunk = 0x004E4942;  // "BIN\0"
constexpr std::size_t kHeaderBytes = 12;
constexpr std::size_t kChunkHeaderBytes = 8;

std::uint32_t littleEndianWord(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (std::size_t k = 4; k-- > 0;) value = (value << 8) | static_cast<unsigned char>(bytes[at + k]);
  return value;
}

/// The glTF document of one GLB, with the file named in every error.
class GlbDocument {
 public:
  GlbDocument(const json& document, std::size_t binaryBytes, std::string file)
      : document_(document), binaryBytes_(binaryBytes), file_(std::move(file)) {}

  void check() const {
    checkBuffers();
    checkBufferViews();
    checkAccessors();
    checkMeshes();
    checkNodes();
    checkAnimations();
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const { throw InputError(file_ + ": " + where + ": " + what); }

  /// The array `name` of the document (empty when absent); fails when it is not an array of objects.
  const json& list(const json& parent, const std::string& name, const std::string& where) const {
    static const json kNone = json::array();
    const auto found = parent.find(name);
    if (found == parent.end()) return kNone;
    if (!found->is_array()) fail(where + name, "expected an array");
    for (std::size_t i = 0; i < found->size(); ++i) {
      if (!(*found)[i].is_object()) fail(where + name + "[" + std::to_string(i) + "]", "expected an object");
    }
    return *found;
  }
  const json& list(const std::string& name) const { return list(document_, name, ""); }

  /// An unsigned integer field (`fallback` when absent and optional).
  std::uint64_t natural(const json& object, const std::string& field, const std::string& where, bool required, std::uint64_t fallback = 0) const {
    const auto found = object.find(field);
    if (found == object.end()) {
      if (required) fail(where, "no \"" + field + "\"");
      return fallback;
    }
    if (!found->is_number_unsigned()) fail(where + "." + field, "expected an integer >= 0, got " + boundedJsonDump(*found));
    return found->get<std::uint64_t>();
  }

  /// Fails unless `object[field]`, when present (or `required`), indexes the array `target`.
  void index(const json& object, const std::string& field, const std::string& where, const std::string& target, bool required) const {
    if (!required && !object.contains(field)) return;
    const std::uint64_t value = natural(object, field, where, true);
    const std::size_t size = list(target).size();
    if (value >= size) fail(where + "." + field, std::to_string(value) + " is not one of the " + std::to_string(size) + " " + target);
  }

  void checkBuffers() const {
    const json& buffers = list("buffers");
    for (std::size_t i = 0; i < buffers.size(); ++i) {
      const std::string where = "buffers[" + std::to_string(i) + "]";
      const std::uint64_t bytes = natural(buffers[i], "byteLength", where, true);
      if (buffers[i].contains("uri")) fail(where, "refers to an outside file (a run's scene.glb holds all its data)");
      if (i > 0) fail(where, "a GLB has one buffer, its binary chunk");
      if (bytes > binaryBytes_) {
        fail(where + ".byteLength", std::to_string(bytes) + " bytes, but the binary chunk has " + std::to_string(binaryBytes_) + " (truncated?)");
      }
    }
  }

  void checkBufferViews() const {
    const json& views = list("bufferViews");
    for (std::size_t i = 0; i < views.size(); ++i) {
      const std::string where = "bufferViews[" + std::to_string(i) + "]";
      index(views[i], "buffer", where, "buffers", true);
      const std::uint64_t end = natural(views[i], "byteOffset", where, false) + natural(views[i], "byteLength", where, true);
      const std::uint64_t bytes = list("buffers")[natural(views[i], "buffer", where, true)]["byteLength"].get<std::uint64_t>();
      if (end > bytes) fail(where, "bytes up to " + std::to_string(end) + " of a buffer of " + std::to_string(bytes));
    }
  }

  static std::uint64_t componentBytes(std::uint64_t type) {
    switch (type) {
      case 5120: case 5121: return 1;  // (unsigned) byte
      case 5122: case 5123: return 2;  // (unsigned) short
      case 5125: case 5126: return 4;  // unsigned int, float
      default: return 0;
    }
  }

  static std::uint64_t componentCount(const std::string& type) {
    static constexpr std::pair<std::string_view, std::uint64_t> kTypes[] = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                                                                            {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
    for (const auto& [name, count] : kTypes) {
      if (type == name) return count;
    }
    return 0;
  }

  void checkAccessors() const {
    const json& accessors = list("accessors");
    for (std::size_t i = 0; i < accessors.size(); ++i) {
      const json& accessor = accessors[i];
      const std::string where = "accessors[" + std::to_string(i) + "]";
      const std::uint64_t component = componentBytes(natural(accessor, "componentType", where, true));
      const std::uint64_t components = componentCount(accessor.value("type", ""));
      if (component == 0) fail(where + ".componentType", "not a glTF component type");
      if (components == 0) fail(where + ".type", "expected SCALAR, VEC2 to VEC4 or MAT2 to MAT4");
      const std::uint64_t count = natural(accessor, "count", where, true);
      if (count == 0) fail(where + ".count", "must be at least 1");
      if (!accessor.contains("bufferView")) continue;  // all zeros
      index(accessor, "bufferView", where, "bufferViews", true);
      const json& view = list("bufferViews")[accessor["bufferView"].get<std::size_t>()];
      const std::uint64_t element = component * components;
      const std::uint64_t stride = natural(view, "byteStride", where, false, element);
      const std::uint64_t end = natural(accessor, "byteOffset", where, false) + (count - 1) * stride + element;
      if (end > view["byteLength"].get<std::uint64_t>()) {
        fail(where, std::to_string(count) + " elements need " + std::to_string(end) + " bytes of bufferView " +
                        std::to_string(accessor["bufferView"].get<std::size_t>()) + ", which has " + std::to_string(view["byteLength"].get<std::uint64_t>()));
      }
    }
  }

  void checkMeshes() const {
    const json& meshes = list("meshes");
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      const std::string mesh = "meshes[" + std::to_string(m) + "].";
      const json& primitives = list(meshes[m], "primitives", mesh);
      for (std::size_t p = 0; p < primitives.size(); ++p) {
        const std::string where = mesh + "primitives[" + std::to_string(p) + "]";
        index(primitives[p], "indices", where, "accessors", false);
        const auto attributes = primitives[p].find("attributes");
        if (attributes == primitives[p].end() || !attributes->is_object()) fail(where, "no \"attributes\" object");
        for (const auto& [name, value] : attributes->items()) index(*attributes, name, where + ".attributes", "accessors", true);
      }
    }
  }

  void checkNodes() const {
    const json& nodes = list("nodes");
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const std::string where = "nodes[" + std::to_string(i) + "]";
      index(nodes[i], "mesh", where, "meshes", false);
      const auto children = nodes[i].find("children");
      if (children == nodes[i].end()) continue;
      if (!children->is_array()) fail(where + ".children", "expected an array");
      for (std::size_t c = 0; c < children->size(); ++c) index(*children, c, where + ".children", "nodes");
    }
    const json& scenes = list("scenes");
    for (std::size_t s = 0; s < scenes.size(); ++s) {
      const auto roots = scenes[s].find("nodes");
      if (roots == scenes[s].end()) continue;
      if (!roots->is_array()) fail("scenes[" + std::to_string(s) + "].nodes", "expected an array");
      for (std::size_t r = 0; r < roots->size(); ++r) index(*roots, r, "scenes[" + std::to_string(s) + "].nodes", "nodes");
    }
  }

  /// Fails unless the `at`th entry of `array` indexes `target`.
  void index(const json& array, std::size_t at, const std::string& where, const std::string& target) const {
    const std::size_t size = list(target).size();
    if (!array[at].is_number_unsigned() || array[at].get<std::uint64_t>() >= size) {
      fail(where + "[" + std::to_string(at) + "]", boundedJsonDump(array[at]) + " is not one of the " + std::to_string(size) + " " + target);
    }
  }

  void checkAnimations() const {
    const json& animations = list("animations");
    for (std::size_t a = 0; a < animations.size(); ++a) {
      const std::string animation = "animations[" + std::to_string(a) + "].";
      const json& samplers = list(animations[a], "samplers", animation);
      for (std::size_t s = 0; s < samplers.size(); ++s) {
        const std::string where = animation + "samplers[" + std::to_string(s) + "]";
        index(samplers[s], "input", where, "accessors", true);
        index(samplers[s], "output", where, "accessors", true);
      }
      const json& channels = list(animations[a], "channels", animation);
      for (std::size_t c = 0; c < channels.size(); ++c) {
        const std::string where = animation + "channels[" + std::to_string(c) + "]";
        const std::uint64_t sampler = natural(channels[c], "sampler", where, true);
        if (sampler >= samplers.size()) fail(where + ".sampler", std::to_string(sampler) + " is not one of the " + std::to_string(samplers.size()) + " samplers");
        const auto target = channels[c].find("target");
        if (target == channels[c].end() || !target->is_object()) fail(where, "no \"target\" object");
        index(*target, "node", where + ".target", "nodes", false);
      }
    }
  }

  const json& document_;
  std::size_t binaryBytes_;
  std::string file_;
};

}  // namespace

void checkGlb(const std::string& bytes, const std::string& file) {
  checkGlbHeader(bytes, file);
  const std::uint32_t jsonBytes = littleEndianWord(bytes, kHeaderBytes);
  if (littleEndianWord(bytes, kHeaderBytes + 4) != kJsonChunk) throw InputError(file + ": the first chunk is not the JSON chunk");
  const std::size_t jsonStart = kHeaderBytes + kChunkHeaderBytes;
  if (jsonBytes > bytes.size() - jsonStart) {
    throw InputError(file + ": the JSON chunk says " + std::to_string(jsonBytes) + " bytes, the file has " + std::to_string(bytes.size() - jsonStart) + " after it");
  }
  std::size_t binaryBytes = 0;
  const std::size_t binaryChunk = jsonStart + jsonBytes;
  if (bytes.size() > binaryChunk) {
    if (bytes.size() - binaryChunk < kChunkHeaderBytes || littleEndianWord(bytes, binaryChunk + 4) != kBinaryChunk) {
      throw InputError(file + ": after the JSON chunk, no binary (BIN) chunk");
    }
    binaryBytes = littleEndianWord(bytes, binaryChunk);
    if (binaryBytes > bytes.size() - binaryChunk - kChunkHeaderBytes) {
      throw InputError(file + ": the binary chunk says " + std::to_string(binaryBytes) + " bytes, the file has " +
                       std::to_string(bytes.size() - binaryChunk - kChunkHeaderBytes) + " (truncated)");
    }
  }
  const json document = parseJsonWithinLimits(std::string_view(bytes).substr(jsonStart, jsonBytes), {}, file + ": the JSON chunk");
  if (!document.is_object() || !document.contains("asset")) throw InputError(file + ": the JSON chunk is not a glTF document (no \"asset\")");
  GlbDocument(document, binaryBytes, file).check();
}

}  // namespace lang2manip
