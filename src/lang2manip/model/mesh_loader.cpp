#include "lang2manip/model/mesh_loader.hpp"

#include <Inventor/SbMatrix.h>
#include <Inventor/SoDB.h>
#include <Inventor/SoInput.h>
#include <Inventor/SoPrimitiveVertex.h>
#include <Inventor/VRMLnodes/SoVRMLCoordinate.h>
#include <Inventor/VRMLnodes/SoVRMLIndexedLine.h>
#include <Inventor/VRMLnodes/SoVRMLIndexedShape.h>
#include <Inventor/VRMLnodes/SoVRMLNormal.h>
#include <Inventor/VRMLnodes/SoVRMLTextureCoordinate.h>
#include <Inventor/VRMLnodes/SoVRMLVertexPoint.h>
#include <Inventor/actions/SoCallbackAction.h>
#include <Inventor/errors/SoDebugError.h>
#include <Inventor/errors/SoMemoryError.h>
#include <Inventor/errors/SoReadError.h>
#include <Inventor/fields/SoMFNode.h>
#include <Inventor/fields/SoSFNode.h>
#include <Inventor/lists/SoFieldList.h>
#include <Inventor/misc/SoChildList.h>
#include <Inventor/nodes/SoFaceSet.h>
#include <Inventor/nodes/SoIndexedLineSet.h>
#include <Inventor/nodes/SoIndexedNurbsCurve.h>
#include <Inventor/nodes/SoIndexedNurbsSurface.h>
#include <Inventor/nodes/SoIndexedPointSet.h>
#include <Inventor/nodes/SoIndexedShape.h>
#include <Inventor/nodes/SoLineSet.h>
#include <Inventor/nodes/SoNormal.h>
#include <Inventor/nodes/SoNurbsCurve.h>
#include <Inventor/nodes/SoNurbsSurface.h>
#include <Inventor/nodes/SoPointSet.h>
#include <Inventor/nodes/SoQuadMesh.h>
#include <Inventor/nodes/SoSeparator.h>
#include <Inventor/nodes/SoShape.h>
#include <Inventor/nodes/SoTextureCoordinate2.h>
#include <Inventor/nodes/SoTextureCoordinate3.h>
#include <Inventor/nodes/SoTriangleStripSet.h>
#include <Inventor/nodes/SoVertexProperty.h>

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <regex>
#include <sstream>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/log.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kAssimpExtensions = {".stl", ".dae", ".obj", ".ply"};
const std::vector<std::string> kCoinExtensions = {".iv", ".wrl", ".vrml"};

std::string lowerCaseExtension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : separator) + item;
  return text;
}

// ---------------------------------------------------------------------------------------------
// Collecting triangles

/// Collects root-frame triangles into an indexed mesh. Never throws while collecting (it is
/// called from inside Coin's traversal): invalid input is remembered; check problem() afterwards.
class MeshBuilder {
 public:
  static constexpr int kInvalid = -1;

  /// Appends a vertex; kInvalid when it is not finite or the mesh is full.
  int addVertex(const Vector3& point) {
    if (!point.allFinite()) {
      nonFinite_ = true;
      return kInvalid;
    }
    if (mesh_.vertices.size() >= static_cast<std::size_t>(INT_MAX)) {
      tooLarge_ = true;
      return kInvalid;
    }
    mesh_.vertices.push_back(point);
    return static_cast<int>(mesh_.vertices.size() - 1);
  }

  /// The index of a vertex with exactly these coordinates, appending one if there is none.
  int mergedVertex(const Vector3& point) {
    const std::array<double, 3> key = {point.x(), point.y(), point.z()};
    if (const auto found = merged_.find(key); found != merged_.end()) return found->second;
    const int index = addVertex(point);
    if (index != kInvalid) merged_.emplace(key, index);
    return index;
  }

  /// Adds a triangle unless an index is invalid or it has no area (nothing to collide with).
  void addTriangle(int a, int b, int c) {
    if (a == kInvalid || b == kInvalid || c == kInvalid || a == b || b == c || a == c) return;
    if (!hasArea(mesh_.vertices[a].data(), mesh_.vertices[b].data(), mesh_.vertices[c].data())) {
      return;
    }
    mesh_.triangles.push_back({a, b, c});
  }

  /// What makes the collected mesh unusable, or "" when it is fine.
  [[nodiscard]] std::string problem() const {
    if (nonFinite_) return "has a vertex with a non-finite coordinate (nan or inf)";
    if (tooLarge_) return "has too many vertices";
    if (mesh_.triangles.empty()) return "contains no triangles";
    return {};
  }

  TriangleMesh take(std::string source) {
    mesh_.source = std::move(source);
    return std::move(mesh_);
  }

 private:
  struct KeyHash {
    std::size_t operator()(const std::array<double, 3>& key) const noexcept {
      std::size_t seed = 0;
      for (double value : key) {
        seed ^= std::hash<double>{}(value) + 0x9e3779b97f4a7c15ULL + (seed << 6) + (seed >> 2);
      }
      return seed;
    }
  };

  // Plain arithmetic: this runs per triangle, and unoptimised Eigen makes debug builds crawl.
  static bool hasArea(const double* a, const double* b, const double* c) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    return u[1] * v[2] != u[2] * v[1] || u[2] * v[0] != u[0] * v[2] || u[0] * v[1] != u[1] * v[0];
  }

  TriangleMesh mesh_;
  std::unordered_map<std::array<double, 3>, int, KeyHash> merged_;
  bool nonFinite_ = false;
  bool tooLarge_ = false;
};

// ---------------------------------------------------------------------------------------------
// Nesting guard: Coin's and assimp's COLLADA parsers recurse once per nesting level and
// overflow the stack on files nested some 10,000 levels deep, so deeper files are refused first.

constexpr int kMaxNestingDepth = 1000;

std::size_t skipPast(const std::string& text, std::size_t from, const char* end) {
  const std::size_t found = text.find(end, from);
  return found == std::string::npos ? text.size() : found + std::strlen(end);
}

/// Deepest nesting of { } and [ ] in Inventor or VRML text, comments and strings skipped.
int braceDepth(const std::string& text) {
  int depth = 0;
  int deepest = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '#') {
      i = skipPast(text, i, "\n") - 1;
    } else if (c == '"') {
      while (++i < text.size() && text[i] != '"') i += text[i] == '\\' ? 1 : 0;
    } else if (c == '{' || c == '[') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == '}' || c == ']') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

/// Deepest nesting of XML elements; comments, CDATA and declarations skipped.
int elementDepth(const std::string& text) {
  int depth = 0;
  int deepest = 0;
  for (std::size_t i = text.find('<'); i < text.size(); i = text.find('<', i)) {
    if (text.compare(i, 4, "<!--") == 0) {
      i = skipPast(text, i, "-->");
    } else if (text.compare(i, 9, "<![CDATA[") == 0) {
      i = skipPast(text, i, "]]>");
    } else {
      const std::size_t end = skipPast(text, i, ">");
      const char kind = i + 1 < text.size() ? text[i + 1] : '?';
      if (kind == '/' && depth > 0) --depth;
      const bool opens = kind != '/' && kind != '?' && kind != '!' && text[end - 1] == '>' &&
                         text[end - 2] != '/';
      if (opens) deepest = std::max(deepest, ++depth);
      i = end;
    }
  }
  return deepest;
}

/// Throws when a text file nests deeper than kMaxNestingDepth (binary files are not scanned).
void checkNestingDepth(const fs::path& path, const std::string& name, bool xml) {
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream contents;
  contents << stream.rdbuf();
  const std::string text = std::move(contents).str();
  if (!xml && text.substr(0, text.find('\n')).find("binary") != std::string::npos) return;
  if ((xml ? elementDepth(text) : braceDepth(text)) > kMaxNestingDepth) {
    throw InputError(SourceLocation{name, 0}, "nesting deeper than " +
                                                  std::to_string(kMaxNestingDepth) +
                                                  " levels: refused to protect the stack");
  }
}

// ---------------------------------------------------------------------------------------------
// assimp: STL, COLLADA, OBJ, PLY

Eigen::Affine3d toAffine(const aiMatrix4x4& m) {
  Eigen::Matrix4d matrix;
  matrix << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2,
      m.d3, m.d4;
  return Eigen::Affine3d(matrix);
}

/// X * v in plain arithmetic (this runs per vertex; see MeshBuilder::hasArea).
Vector3 transformed(const Eigen::Affine3d& X, const aiVector3D& v) {
  const double* m = X.data();  // column-major 4 x 4
  const double x = v.x;
  const double y = v.y;
  const double z = v.z;
  return {m[0] * x + m[4] * y + m[8] * z + m[12], m[1] * x + m[5] * y + m[9] * z + m[13],
          m[2] * x + m[6] * y + m[10] * z + m[14]};
}

/// Adds the triangles of `mesh` (points and lines are skipped), its vertices moved by X_RN into
/// the root frame. assimp has already merged identical vertices within the mesh; vertices are
/// added when a triangle first uses them, so unused ones do not widen the bounds.
void addAssimpMesh(const aiMesh& mesh, const Eigen::Affine3d& X_RN, MeshBuilder& builder) {
  if (mesh.mVertices == nullptr || mesh.mFaces == nullptr) return;
  constexpr int kNotAdded = -2;
  std::vector<int> added(mesh.mNumVertices, kNotAdded);
  const auto index = [&](unsigned i) {
    if (i >= mesh.mNumVertices) return MeshBuilder::kInvalid;
    if (added[i] == kNotAdded) {
      added[i] = builder.addVertex(transformed(X_RN, mesh.mVertices[i]));
    }
    return added[i];
  };
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3 || face.mIndices == nullptr) continue;
    builder.addTriangle(index(face.mIndices[0]), index(face.mIndices[1]), index(face.mIndices[2]));
  }
}

/// Adds the meshes of every node, each in the root frame R (node transforms applied), walking
/// the tree with an explicit stack so that a deep hierarchy cannot overflow the call stack.
void addAssimpScene(const aiScene& scene, MeshBuilder& builder) {
  std::vector<std::pair<const aiNode*, Eigen::Affine3d>> pending;
  pending.emplace_back(scene.mRootNode, toAffine(scene.mRootNode->mTransformation));
  while (!pending.empty()) {
    const auto [node, X_RN] = pending.back();
    pending.pop_back();
    for (unsigned m = 0; m < node->mNumMeshes; ++m) {
      const unsigned meshIndex = node->mMeshes[m];
      if (meshIndex < scene.mNumMeshes && scene.mMeshes[meshIndex] != nullptr) {
        addAssimpMesh(*scene.mMeshes[meshIndex], X_RN, builder);
      }
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) {
      const aiNode* child = node->mChildren[c];
      if (child != nullptr) pending.emplace_back(child, X_RN * toAffine(child->mTransformation));
    }
  }
}

/// COLLADA: assimp 5.2 multiplies the root node's transform (the <visual_scene>'s) by the
/// <unit meter="..."> scale and by a rotation that turns <up_axis> Z_UP or X_UP into Y up. We
/// keep the unit and ignore the up axis, as RViz does (it skips the root transform and applies
/// the unit itself): URDF meshes are expressed in their link frame as written. MoveIt's
/// geometric_shapes clears the root transform, losing the unit too; we follow the spec there.
TriangleMesh loadWithAssimp(const fs::path& path, const std::string& name) {
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // Only positions are kept: dropping normals and the like first lets JoinIdenticalVertices
  // merge the corners that faces share (an STL repeats them with each face's normal).
  importer.SetPropertyInteger(
      AI_CONFIG_PP_RVC_FLAGS,
      aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_COLORS |
          aiComponent_TEXCOORDS | aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
          aiComponent_TEXTURES | aiComponent_LIGHTS | aiComponent_CAMERAS);
  const unsigned steps = aiProcess_RemoveComponent | aiProcess_Triangulate |
                         aiProcess_JoinIdenticalVertices | aiProcess_SortByPType;
  const aiScene* scene = importer.ReadFile(path.string(), steps);
  if (scene == nullptr) {
    throw InputError(SourceLocation{name, 0},
                     std::string("cannot read mesh: ") + importer.GetErrorString());
  }
  MeshBuilder builder;
  if (scene->mRootNode != nullptr) addAssimpScene(*scene, builder);
  if (const std::string problem = builder.problem(); !problem.empty()) {
    throw InputError(SourceLocation{name, 0}, "mesh " + problem);
  }
  return builder.take(fs::absolute(path).lexically_normal().string());
}

// ---------------------------------------------------------------------------------------------
// Coin3D: Inventor .iv and VRML 1 / 2 .wrl

/// Messages Coin posts while the current thread reads a file.
struct CoinMessages {
  std::vector<std::string> errors;
  std::vector<std::string> warnings;
};

thread_local CoinMessages* tCoinMessages = nullptr;

/// Whether Coin's error is about a texture image, which a collision mesh does not need.
bool isAboutTexture(const std::string& text) {
  return text.find("texture") != std::string::npos || text.find("SbImage") != std::string::npos;
}

/// Replaces Coin's default handler, which prints to stderr. Messages posted while this thread
/// reads a file are collected; others are dropped (only this loader uses Coin). Errors about
/// texture images (missing files) are only warnings here: the geometry is complete without them.
void collectCoinMessage(const SoError* error, void* /*data*/) {
  if (tCoinMessages == nullptr || error == nullptr) return;
  std::string text = error->getDebugString().getString();
  bool isWarning = isAboutTexture(text);
  if (error->isOfType(SoDebugError::getClassTypeId())) {
    isWarning |= static_cast<const SoDebugError*>(error)->getSeverity() != SoDebugError::ERROR;
  }
  (isWarning ? tCoinMessages->warnings : tCoinMessages->errors).push_back(std::move(text));
}

/// Coin keeps global state (type system, name dictionaries, error handlers): it is initialised
/// once and used by one thread at a time, under this mutex.
std::mutex& coinMutex() {
  static std::mutex mutex;
  return mutex;
}

void initCoinOnce() {
  static std::once_flag once;
  std::call_once(once, [] {
    SoDB::init();
    SoError::setHandlerCallback(collectCoinMessage, nullptr);
    SoDebugError::setHandlerCallback(collectCoinMessage, nullptr);
    SoReadError::setHandlerCallback(collectCoinMessage, nullptr);
    SoMemoryError::setHandlerCallback(collectCoinMessage, nullptr);
  });
}

/// Installs `messages` as the current thread's collector for its lifetime.
class CoinMessageScope {
 public:
  explicit CoinMessageScope(CoinMessages& messages) { tCoinMessages = &messages; }
  ~CoinMessageScope() { tCoinMessages = nullptr; }
  CoinMessageScope(const CoinMessageScope&) = delete;
  CoinMessageScope& operator=(const CoinMessageScope&) = delete;
};

/// Coin's messages span several lines ("Coin read error: what\n  Occurred at line 6 in path"):
/// keeps "what" on one line (the file and line go into the exception's location).
std::string oneLine(const std::string& text) {
  static const std::regex kPrefix(R"(^\s*Coin (read error: |(error|warning) in ))");
  static const std::regex kOccurred(R"(\s*Occurred at line\s+\d+\s+in\s[\s\S]*$)");
  static const std::regex kBreaks(R"(\s*\n\s*)");
  std::string line = std::regex_replace(text, kOccurred, "");
  line = std::regex_replace(line, kPrefix, "");
  line = std::regex_replace(line, kBreaks, " ");
  while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
  return line;
}

/// The line number Coin gives in a read error, or 0.
int coinErrorLine(const std::vector<std::string>& errors) {
  static const std::regex kLine(R"(Occurred at line\s+(\d{1,9}))");
  for (const std::string& error : errors) {
    std::smatch match;
    if (std::regex_search(error, match, kLine)) return std::stoi(match[1].str());
  }
  return 0;
}

std::string coinErrorText(const CoinMessages& messages) {
  if (messages.errors.empty()) return "no reason given";
  std::vector<std::string> lines;
  for (const std::string& error : messages.errors) lines.push_back(oneLine(error));
  return joined(lines, "; ");
}

/// Holds a reference on a Coin node for its lifetime (unref() deletes it when it is the last).
class CoinRef {
 public:
  explicit CoinRef(SoSeparator* node) : node_(node) { node_->ref(); }
  ~CoinRef() { node_->unref(); }
  CoinRef(const CoinRef&) = delete;
  CoinRef& operator=(const CoinRef&) = delete;
  [[nodiscard]] SoNode* get() const { return node_; }

 private:
  SoNode* node_;
};

/// Every node reachable from `root`, each once: group children and the values of node fields
/// (VRML keeps geometry, coordinates and normals in fields).
std::vector<SoNode*> reachableNodes(SoNode* root) {
  std::vector<SoNode*> nodes;
  std::unordered_set<SoNode*> seen;
  std::vector<SoNode*> pending = {root};
  while (!pending.empty()) {
    SoNode* node = pending.back();
    pending.pop_back();
    if (node == nullptr || !seen.insert(node).second) continue;
    nodes.push_back(node);
    if (const SoChildList* children = node->getChildren()) {
      for (int i = 0; i < children->getLength(); ++i) pending.push_back((*children)[i]);
    }
    SoFieldList fields;
    node->getFields(fields);
    for (int i = 0; i < fields.getLength(); ++i) {
      if (fields[i]->isOfType(SoSFNode::getClassTypeId())) {
        pending.push_back(static_cast<SoSFNode*>(fields[i])->getValue());
      } else if (fields[i]->isOfType(SoMFNode::getClassTypeId())) {
        const auto* values = static_cast<SoMFNode*>(fields[i]);
        for (int j = 0; j < values->getNum(); ++j) pending.push_back((*values)[j]);
      }
    }
  }
  return nodes;
}

/// Calls `clear` on each of `nodes` that is a T.
template <typename T, typename Clear>
void clearEach(const std::vector<SoNode*>& nodes, Clear clear) {
  for (SoNode* node : nodes) {
    if (node->isOfType(T::getClassTypeId())) clear(static_cast<T*>(node));
  }
}

/// Only positions are kept, and Coin indexes normals and texture coordinates without checking
/// the indices (an out-of-range normalIndex crashes it). Emptying them and their indices makes
/// Coin compute its own, which is safe.
void dropNormalsAndTextureCoordinates(SoNode* root) {
  const std::vector<SoNode*> nodes = reachableNodes(root);
  clearEach<SoNormal>(nodes, [](SoNormal* n) { n->vector.setNum(0); });
  clearEach<SoVRMLNormal>(nodes, [](SoVRMLNormal* n) { n->vector.setNum(0); });
  clearEach<SoTextureCoordinate2>(nodes, [](SoTextureCoordinate2* t) { t->point.setNum(0); });
  clearEach<SoTextureCoordinate3>(nodes, [](SoTextureCoordinate3* t) { t->point.setNum(0); });
  clearEach<SoVRMLTextureCoordinate>(nodes, [](SoVRMLTextureCoordinate* t) { t->point.setNum(0); });
  clearEach<SoVertexProperty>(nodes, [](SoVertexProperty* p) {
    p->normal.setNum(0);
    p->texCoord.setNum(0);
    p->texCoord3.setNum(0);
  });
  clearEach<SoIndexedShape>(nodes, [](SoIndexedShape* s) {
    s->normalIndex.setNum(0);
    s->textureCoordIndex.setNum(0);
  });
  clearEach<SoVRMLIndexedShape>(nodes, [](SoVRMLIndexedShape* s) {
    s->normal.setValue(nullptr);
    s->texCoord.setValue(nullptr);
    s->color.setValue(nullptr);
    s->normalIndex.setNum(0);
    s->texCoordIndex.setNum(0);
    s->colorIndex.setNum(0);
  });
}

/// The first entry of `indices` outside [-1, count), as a problem, or "".
std::string checkCoordinateIndices(const SoMFInt32& indices, std::int64_t count) {
  for (int i = 0; i < indices.getNum(); ++i) {
    if (indices[i] < -1 || indices[i] >= count) {
      return "coordIndex " + std::to_string(indices[i]) + " is out of range (" +
             std::to_string(count) + " coordinates)";
    }
  }
  return {};
}

/// Whether `used` coordinates from `start` fit in `count`, as a problem, or "".
std::string checkCoordinateCount(std::int64_t start, std::int64_t used, std::int64_t count) {
  if (start < 0 || used < 0 || start + used > count) {
    return "needs coordinates " + std::to_string(start) + " to " +
           std::to_string(start + used - 1) + " but has " + std::to_string(count);
  }
  return {};
}

/// Coordinates a non-indexed set uses: the sum of numVertices, where -1 means "all the rest".
std::int64_t usedCoordinates(const SoMFInt32& numVertices, std::int64_t start, std::int64_t count) {
  std::int64_t used = 0;
  for (int i = 0; i < numVertices.getNum(); ++i) {
    if (numVertices[i] == -1) return std::max<std::int64_t>(count - start, used);
    if (numVertices[i] < 0) return -1;
    used += numVertices[i];
  }
  return used;
}

/// Coordinates an Inventor vertex shape reads: its own vertexProperty's, else the current ones.
std::int64_t availableCoordinates(const SoCallbackAction& action, const SoVertexShape& shape) {
  const SoNode* property = shape.vertexProperty.getValue();
  if (property != nullptr && property->isOfType(SoVertexProperty::getClassTypeId())) {
    const int own = static_cast<const SoVertexProperty*>(property)->vertex.getNum();
    if (own > 0) return own;
  }
  return action.getNumCoordinates();
}

std::int64_t vrmlCoordinates(const SoVRMLVertexShape& shape) {
  const SoNode* coord = shape.coord.getValue();
  if (coord == nullptr || !coord->isOfType(SoVRMLCoordinate::getClassTypeId())) return 0;
  return static_cast<const SoVRMLCoordinate*>(coord)->point.getNum();
}

bool isLineOrPointShape(const SoNode& shape) {
  for (const SoType type :
       {SoIndexedLineSet::getClassTypeId(), SoIndexedPointSet::getClassTypeId(),
        SoLineSet::getClassTypeId(), SoPointSet::getClassTypeId(),
        SoNurbsCurve::getClassTypeId(), SoIndexedNurbsCurve::getClassTypeId(),
        SoVRMLIndexedLine::getClassTypeId(), SoVRMLVertexPoint::getClassTypeId()}) {
    if (shape.isOfType(type)) return true;
  }
  return false;
}

/// Why Coin cannot safely tessellate `shape` (it reads coordinates by index and count without
/// checking them, and out-of-range values crash it), or "".
std::string shapeProblem(const SoCallbackAction& action, const SoNode& shape) {
  if (shape.isOfType(SoNurbsSurface::getClassTypeId()) ||
      shape.isOfType(SoIndexedNurbsSurface::getClassTypeId())) {
    return "NURBS surfaces are not supported";
  }
  if (shape.isOfType(SoIndexedShape::getClassTypeId())) {
    const auto& indexed = static_cast<const SoIndexedShape&>(shape);
    return checkCoordinateIndices(indexed.coordIndex, availableCoordinates(action, indexed));
  }
  if (shape.isOfType(SoVRMLIndexedShape::getClassTypeId())) {
    const auto& indexed = static_cast<const SoVRMLIndexedShape&>(shape);
    return checkCoordinateIndices(indexed.coordIndex, vrmlCoordinates(indexed));
  }
  if (!shape.isOfType(SoNonIndexedShape::getClassTypeId())) return {};
  const auto& set = static_cast<const SoNonIndexedShape&>(shape);
  const std::int64_t count = availableCoordinates(action, set);
  const std::int64_t start = set.startIndex.getValue();
  if (shape.isOfType(SoQuadMesh::getClassTypeId())) {
    const auto& mesh = static_cast<const SoQuadMesh&>(shape);
    const std::int64_t rows = mesh.verticesPerColumn.getValue();
    const std::int64_t columns = mesh.verticesPerRow.getValue();
    return checkCoordinateCount(start, rows < 0 || columns < 0 ? -1 : rows * columns, count);
  }
  const SoMFInt32* numVertices = nullptr;
  if (shape.isOfType(SoFaceSet::getClassTypeId())) {
    numVertices = &static_cast<const SoFaceSet&>(shape).numVertices;
  } else if (shape.isOfType(SoTriangleStripSet::getClassTypeId())) {
    numVertices = &static_cast<const SoTriangleStripSet&>(shape).numVertices;
  }
  if (numVertices == nullptr) return {};
  return checkCoordinateCount(start, usedCoordinates(*numVertices, start, count), count);
}

/// What the traversal found: triangles, or the first shape it could not use.
struct CoinTraversal {
  MeshBuilder builder;
  std::string problem;
};

SoCallbackAction::Response checkCoinShape(void* data, SoCallbackAction* action,
                                          const SoNode* node) {
  if (isLineOrPointShape(*node)) return SoCallbackAction::PRUNE;  // no triangles to give
  std::string problem = shapeProblem(*action, *node);
  if (problem.empty()) return SoCallbackAction::CONTINUE;
  static_cast<CoinTraversal*>(data)->problem =
      std::string(node->getTypeId().getName().getString()) + " " + problem;
  return SoCallbackAction::ABORT;
}

void addCoinTriangle(void* data, SoCallbackAction* action, const SoPrimitiveVertex* v1,
                     const SoPrimitiveVertex* v2, const SoPrimitiveVertex* v3) {
  const SbMatrix& X_RS = action->getModelMatrix();
  const auto rootPoint = [&X_RS](const SoPrimitiveVertex* vertex) {
    SbVec3f point;
    X_RS.multVecMatrix(vertex->getPoint(), point);
    return Vector3(point[0], point[1], point[2]);
  };
  MeshBuilder& builder = static_cast<CoinTraversal*>(data)->builder;
  builder.addTriangle(builder.mergedVertex(rootPoint(v1)), builder.mergedVertex(rootPoint(v2)),
                      builder.mergedVertex(rootPoint(v3)));
}

/// Reads the scene graph; throws with Coin's reason (and line) when it is malformed.
SoSeparator* readCoinScene(const fs::path& path, const std::string& name,
                           const CoinMessages& messages) {
  SoInput input;
  if (!input.openFile(path.string().c_str(), TRUE)) {
    throw InputError(SourceLocation{name, 0}, "cannot open file: " + coinErrorText(messages));
  }
  SoSeparator* root = SoDB::readAll(&input);
  if (root != nullptr && messages.errors.empty()) return root;
  if (root != nullptr) {
    root->ref();  // Frees the partial scene.
    root->unref();
  }
  throw InputError(SourceLocation{name, coinErrorLine(messages.errors)},
                   "malformed Inventor/VRML file: " + coinErrorText(messages));
}

TriangleMesh loadWithCoin(const fs::path& path, const std::string& name) {
  initCoinOnce();
  const std::lock_guard lock(coinMutex());
  CoinMessages messages;
  const CoinMessageScope scope(messages);
  const CoinRef root(readCoinScene(path, name, messages));
  SoNode* const scene = root.get();
  dropNormalsAndTextureCoordinates(scene);
  CoinTraversal traversal;
  SoCallbackAction action;
  action.addPreCallback(SoShape::getClassTypeId(), checkCoinShape, &traversal);
  action.addTriangleCallback(SoShape::getClassTypeId(), addCoinTriangle, &traversal);
  action.apply(scene);
  if (!traversal.problem.empty()) throw InputError(SourceLocation{name, 0}, traversal.problem);
  for (const std::string& warning : messages.warnings) logWarning(name + ": " + oneLine(warning));
  if (const std::string problem = traversal.builder.problem(); !problem.empty()) {
    throw InputError(SourceLocation{name, 0}, "mesh " + problem);
  }
  return traversal.builder.take(fs::absolute(path).lexically_normal().string());
}

// ---------------------------------------------------------------------------------------------

void checkReadableFile(const fs::path& path, const std::string& name) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (error || !fs::exists(status)) throw InputError(SourceLocation{name, 0}, "mesh file not found");
  if (!fs::is_regular_file(status)) {
    throw InputError(SourceLocation{name, 0}, "mesh path is not a regular file");
  }
  if (!std::ifstream(path, std::ios::binary).is_open()) {
    throw InputError(SourceLocation{name, 0}, "mesh file cannot be opened for reading");
  }
}

}  // namespace

const std::vector<std::string>& supportedMeshExtensions() {
  static const std::vector<std::string> extensions = [] {
    std::vector<std::string> all = kAssimpExtensions;
    all.insert(all.end(), kCoinExtensions.begin(), kCoinExtensions.end());
    return all;
  }();
  return extensions;
}

TriangleMesh loadTriangleMesh(const std::string& path) {
  if (path.empty()) throw InputError("mesh path is empty");
  const fs::path file(path);
  const std::string extension = lowerCaseExtension(file);
  if (!contains(supportedMeshExtensions(), extension)) {
    throw InputError(SourceLocation{path, 0},
                     "unsupported mesh format \"" + extension + "\" (supported: " +
                         joined(supportedMeshExtensions(), ", ") + ")");
  }
  checkReadableFile(file, path);
  const bool coin = contains(kCoinExtensions, extension);
  if (coin || extension == ".dae") checkNestingDepth(file, path, !coin);
  return coin ? loadWithCoin(file, path) : loadWithAssimp(file, path);
}

std::shared_ptr<const TriangleMesh> MeshCache::get(const std::string& path) {
  std::error_code error;
  const std::string key = fs::weakly_canonical(fs::path(path), error).string();
  if (error) throw InputError(SourceLocation{path, 0}, "bad mesh path: " + error.message());
  // Loading under the lock reads each file exactly once even when threads ask for it together.
  const std::lock_guard lock(mutex_);
  if (const auto found = meshes_.find(key); found != meshes_.end()) return found->second;
  auto mesh = std::make_shared<const TriangleMesh>(loadTriangleMesh(path));
  meshes_.emplace(key, mesh);
  return mesh;
}

std::size_t MeshCache::size() const {
  const std::lock_guard lock(mutex_);
  return meshes_.size();
}

MeshCache& MeshCache::global() {
  static MeshCache cache;
  return cache;
}

}  // namespace lang2manip
