#include "lang2manip/model/coin_mesh_reader.hpp"

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
#include <Inventor/nodes/SoMaterialBinding.h>
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

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <mutex>
#include <regex>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/model/mesh_builder.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Coin's global state and messages

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
  std::string text;
  for (const std::string& error : messages.errors) {
    text += (text.empty() ? "" : "; ") + oneLine(error);
  }
  return text;
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

// ---------------------------------------------------------------------------------------------
// Making the scene safe to tessellate

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
/// Coin compute its own, which is safe. Materials are bound OVERALL for the same reason: an
/// indexed material binding on a shape without materialIndex dereferences null in Coin's
/// SoIndexedFaceSet::generatePrimitives (tests/regression/mesh_wrl/).
void dropNormalsAndTextureCoordinates(SoNode* root) {
  const std::vector<SoNode*> nodes = reachableNodes(root);
  clearEach<SoNormal>(nodes, [](SoNormal* n) { n->vector.setNum(0); });
  clearEach<SoVRMLNormal>(nodes, [](SoVRMLNormal* n) { n->vector.setNum(0); });
  clearEach<SoTextureCoordinate2>(nodes, [](SoTextureCoordinate2* t) { t->point.setNum(0); });
  clearEach<SoTextureCoordinate3>(nodes, [](SoTextureCoordinate3* t) { t->point.setNum(0); });
  clearEach<SoVRMLTextureCoordinate>(nodes, [](SoVRMLTextureCoordinate* t) { t->point.setNum(0); });
  clearEach<SoMaterialBinding>(nodes, [](SoMaterialBinding* b) {
    b->value.setValue(SoMaterialBinding::OVERALL);
  });
  clearEach<SoVertexProperty>(nodes, [](SoVertexProperty* p) {
    p->materialBinding.setValue(SoVertexProperty::OVERALL);
    p->normal.setNum(0);
    p->texCoord.setNum(0);
    p->texCoord3.setNum(0);
  });
  clearEach<SoIndexedShape>(nodes, [](SoIndexedShape* s) {
    s->materialIndex.setNum(0);
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
  // A face or strip of fewer than 3 vertices makes Coin's generatePrimitives dereference null
  // (found by fuzz_mesh_iv; tests/regression/mesh_iv/).
  for (int i = 0; i < numVertices->getNum(); ++i) {
    const std::int32_t size = (*numVertices)[i];
    if (size != -1 && size < 3) {
      return "numVertices entry " + std::to_string(i) + " is " + std::to_string(size) +
             ": a face or strip needs at least 3 vertices";
    }
  }
  return checkCoordinateCount(start, usedCoordinates(*numVertices, start, count), count);
}

// ---------------------------------------------------------------------------------------------
// Collecting triangles

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

// ---------------------------------------------------------------------------------------------
// Reading

/// Reads the scene graph; throws with Coin's reason (and line) when it is malformed.
SoSeparator* readCoinScene(const fs::path& path, const CoinMessages& messages) {
  const std::string name = path.string();
  SoInput input;
  if (!input.openFile(name.c_str(), TRUE)) {
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

/// Collects the triangles of `scene`; throws on the first shape Coin cannot safely tessellate.
MeshBuilder collectTriangles(SoNode* scene, const std::string& name) {
  CoinTraversal traversal;
  SoCallbackAction action;
  action.addPreCallback(SoShape::getClassTypeId(), checkCoinShape, &traversal);
  action.addTriangleCallback(SoShape::getClassTypeId(), addCoinTriangle, &traversal);
  action.apply(scene);
  if (!traversal.problem.empty()) throw InputError(SourceLocation{name, 0}, traversal.problem);
  return std::move(traversal.builder);
}

/// Coin 4 formats the message about an include it cannot open with the file name as the format
/// string, so a '%' in `File { name "..." }` crashes it (found by fuzz_mesh_iv;
/// tests/regression/mesh_iv/). Such names are refused before Coin reads the file.
void checkIncludeNames(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const auto skipSpace = [&](std::size_t at) { return text.find_first_not_of(" \t\r\n", at); };
  for (auto at = text.find("File"); at != std::string::npos; at = text.find("File", at + 1)) {
    std::size_t next = skipSpace(at + 4);
    if (next == std::string::npos || text[next] != '{') continue;
    next = skipSpace(next + 1);
    if (next == std::string::npos || text.compare(next, 4, "name") != 0) continue;
    next = skipSpace(next + 4);
    if (next == std::string::npos || text[next] != '"') continue;
    const auto nameEnd = text.find('"', next + 1);
    if (text.find('%', next + 1) < nameEnd) {
      throw InputError(SourceLocation{path.string(), 0},
                       "File include name holds '%', which Coin cannot report safely");
    }
  }
}

}  // namespace

TriangleMesh readMeshWithCoin(const fs::path& path) {
  checkBraceNestingDepth(path);
  checkIncludeNames(path);
  initCoinOnce();
  const std::lock_guard lock(coinMutex());
  CoinMessages messages;
  const CoinMessageScope scope(messages);
  const CoinRef root(readCoinScene(path, messages));
  SoNode* const scene = root.get();
  dropNormalsAndTextureCoordinates(scene);
  MeshBuilder builder = collectTriangles(scene, path.string());
  for (const std::string& warning : messages.warnings) {
    logWarning(path.string() + ": " + oneLine(warning));
  }
  return builder.finish(path);
}

}  // namespace lang2manip
