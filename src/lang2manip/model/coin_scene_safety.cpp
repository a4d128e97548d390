#include "lang2manip/model/coin_scene_safety.hpp"

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
#include <Inventor/nodes/SoArray.h>
#include <Inventor/nodes/SoFaceSet.h>
#include <Inventor/nodes/SoIndexedLineSet.h>
#include <Inventor/nodes/SoIndexedNurbsCurve.h>
#include <Inventor/nodes/SoIndexedNurbsSurface.h>
#include <Inventor/nodes/SoIndexedPointSet.h>
#include <Inventor/nodes/SoIndexedShape.h>
#include <Inventor/nodes/SoLineSet.h>
#include <Inventor/nodes/SoMaterialBinding.h>
#include <Inventor/nodes/SoMultipleCopy.h>
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
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "lang2manip/core/error.hpp"

namespace lang2manip::coin {
namespace {

namespace fs = std::filesystem;

/// Array and MultipleCopy nodes replicate their children and USE repeats a node, so a small file
/// can ask for billions of node visits; Coin's Array loop does not stop when a callback aborts,
/// so the count is computed before traversing.
constexpr double kMaxNodeVisits = 1e6;

/// The nodes a traversal visits below `node` (children, and node fields as reachableNodes()).
std::vector<SoNode*> traversedChildren(SoNode* node) {
  std::vector<SoNode*> children;
  if (const SoChildList* list = node->getChildren()) {
    for (int i = 0; i < list->getLength(); ++i) children.push_back((*list)[i]);
  }
  SoFieldList fields;
  node->getFields(fields);
  for (int i = 0; i < fields.getLength(); ++i) {
    if (fields[i]->isOfType(SoSFNode::getClassTypeId())) {
      children.push_back(static_cast<SoSFNode*>(fields[i])->getValue());
    } else if (fields[i]->isOfType(SoMFNode::getClassTypeId())) {
      const auto* values = static_cast<SoMFNode*>(fields[i]);
      for (int j = 0; j < values->getNum(); ++j) children.push_back((*values)[j]);
    }
  }
  std::erase(children, nullptr);
  return children;
}

/// Every node reachable from `root`, each once.
std::vector<SoNode*> reachableNodes(SoNode* root) {
  std::vector<SoNode*> nodes;
  std::unordered_set<SoNode*> seen;
  std::vector<SoNode*> pending = {root};
  while (!pending.empty()) {
    SoNode* node = pending.back();
    pending.pop_back();
    if (!seen.insert(node).second) continue;
    nodes.push_back(node);
    const std::vector<SoNode*> children = traversedChildren(node);
    pending.insert(pending.end(), children.begin(), children.end());
  }
  return nodes;
}

/// How many times a traversal goes through the children of `node`.
double replication(const SoNode& node) {
  if (node.isOfType(SoArray::getClassTypeId())) {
    const auto& array = static_cast<const SoArray&>(node);
    const auto count = [](const SoSFShort& field) { return std::max(0.0, static_cast<double>(field.getValue())); };
    return count(array.numElements1) * count(array.numElements2) * count(array.numElements3);
  }
  if (node.isOfType(SoMultipleCopy::getClassTypeId())) {
    return static_cast<double>(static_cast<const SoMultipleCopy&>(node).matrix.getNum());
  }
  return 1.0;
}

/// Counts the node visits of a traversal from a root, each shared node's count computed once
/// (saturating above kMaxNodeVisits); a node that contains itself is an error.
class VisitCounter {
 public:
  double visits(SoNode* node) {
    if (const auto known = counted_.find(node); known != counted_.end()) return known->second;
    if (!open_.insert(node).second) throw InputError("a node contains itself (" + typeName(*node) + ")");
    double total = 0.0;
    for (SoNode* child : traversedChildren(node)) total = std::min(total + visits(child), 2.0 * kMaxNodeVisits);
    total = std::min(1.0 + replication(*node) * total, 2.0 * kMaxNodeVisits);
    open_.erase(node);
    counted_.emplace(node, total);
    return total;
  }

 private:
  static std::string typeName(const SoNode& node) { return node.getTypeId().getName().getString(); }

  std::unordered_map<SoNode*, double> counted_;
  std::unordered_set<SoNode*> open_;
};

}  // namespace

/// Refuses scenes whose traversal would visit more than kMaxNodeVisits nodes.
void checkTraversalSize(SoNode* root, const std::string& name) {
  double visits = 0.0;
  try {
    visits = VisitCounter().visits(root);
  } catch (const InputError& error) {
    throw InputError(SourceLocation{name, 0}, error.what());
  }
  if (visits > kMaxNodeVisits) {
    throw InputError(SourceLocation{name, 0}, "the scene is too large: its traversal visits more than " +
                                                  std::to_string(static_cast<long>(kMaxNodeVisits)) +
                                                  " nodes (Array, MultipleCopy and USE repeat their children)");
  }
}

namespace {

/// Calls `clear` on each of `nodes` that is a T.
template <typename T, typename Clear>
void clearEach(const std::vector<SoNode*>& nodes, Clear clear) {
  for (SoNode* node : nodes) {
    if (node->isOfType(T::getClassTypeId())) clear(static_cast<T*>(node));
  }
}

}  // namespace

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

namespace {

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

}  // namespace

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


namespace {

/// Whether `text` holds the word `word` (not part of a longer identifier).
bool holdsWord(const std::string& text, const std::string& word) {
  const auto identifier = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; };
  for (auto at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) {
    const bool startsWord = at == 0 || !identifier(text[at - 1]);
    const bool endsWord = at + word.size() == text.size() || !identifier(text[at + word.size()]);
    if (startsWord && endsWord) return true;
  }
  return false;
}

}  // namespace

/// Coin 4 formats the message about an include it cannot open with the file name as the format
/// string, so a '%' in the name of a `File` node crashes it (found by fuzz_mesh_iv, quoted and
/// unquoted; tests/regression/mesh_iv/). Names can be written in many ways (quoted or not, after
/// comments, other fields first), so a file with a File node may hold no '%' at all.
void checkIncludeNames(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (text.find('%') != std::string::npos && holdsWord(text, "File")) {
    throw InputError(SourceLocation{path.string(), 0},
                     "a file that includes others (a File node) must not contain '%', which Coin cannot report safely");
  }
}


}  // namespace lang2manip::coin
