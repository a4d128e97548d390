#include "lang2manip/model/coin_mesh_reader.hpp"

#include <Inventor/SbMatrix.h>
#include <Inventor/SoDB.h>
#include <Inventor/SoInput.h>
#include <Inventor/SoPrimitiveVertex.h>
#include <Inventor/actions/SoCallbackAction.h>
#include <Inventor/actions/SoSearchAction.h>
#include <Inventor/errors/SoDebugError.h>
#include <Inventor/errors/SoMemoryError.h>
#include <Inventor/errors/SoReadError.h>
#include <Inventor/VRMLnodes/SoVRMLMaterial.h>
#include <Inventor/nodes/SoBaseColor.h>
#include <Inventor/nodes/SoMaterial.h>
#include <Inventor/nodes/SoPackedColor.h>
#include <Inventor/nodes/SoSeparator.h>
#include <Inventor/nodes/SoShape.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <mutex>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/model/coin_scene_safety.hpp"
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
// Collecting triangles

/// Bound on the triangles of one scene (coin::checkTraversalSize bounds the node visits).
constexpr std::int64_t kMaxTriangles = 5'000'000;

/// What the traversal found: triangles, or the first shape it could not use.
struct CoinTraversal {
  MeshBuilder builder;
  std::string problem;
  std::int64_t triangles = 0;
};

SoCallbackAction::Response checkCoinShape(void* data, SoCallbackAction* action,
                                          const SoNode* node) {
  if (coin::isLineOrPointShape(*node)) return SoCallbackAction::PRUNE;  // no triangles to give
  std::string problem = coin::shapeProblem(*action, *node);
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
  auto& traversal = *static_cast<CoinTraversal*>(data);
  if (++traversal.triangles > kMaxTriangles) return;  // refused after the traversal
  MeshBuilder& builder = traversal.builder;
  SbColor ambient, diffuse, specular, emission;
  float shininess = 0.0F, transparency = 0.0F;
  action->getMaterial(ambient, diffuse, specular, emission, shininess, transparency, 0);  // materials are bound OVERALL (coin_scene_safety)
  builder.setColour(Vector3(diffuse[0], diffuse[1], diffuse[2]));
  builder.addTriangle(builder.mergedVertex(rootPoint(v1)), builder.mergedVertex(rootPoint(v2)),
                      builder.mergedVertex(rootPoint(v3)));
}

// ---------------------------------------------------------------------------------------------
// Reading

/// True when the scene gives a colour of its own (without one, Coin's default grey is no colour
/// of the file).
bool declaresMaterial(SoNode* scene) {
  for (const SoType type : {SoMaterial::getClassTypeId(), SoBaseColor::getClassTypeId(), SoPackedColor::getClassTypeId(),
                            SoVRMLMaterial::getClassTypeId()}) {
    SoSearchAction search;
    search.setType(type);
    search.setInterest(SoSearchAction::FIRST);
    search.setSearchingAll(TRUE);
    search.apply(scene);
    if (search.getPath() != nullptr) return true;
  }
  return false;
}

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
  if (traversal.triangles > kMaxTriangles) {
    throw InputError(SourceLocation{name, 0}, "the scene has more than " + std::to_string(kMaxTriangles) + " triangles");
  }
  return std::move(traversal.builder);
}

}  // namespace

TriangleMesh readMeshWithCoin(const fs::path& path) {
  checkBraceNestingDepth(path);
  coin::checkIncludeNames(path);
  initCoinOnce();
  const std::lock_guard lock(coinMutex());
  CoinMessages messages;
  const CoinMessageScope scope(messages);
  const CoinRef root(readCoinScene(path, messages));
  SoNode* const scene = root.get();
  coin::checkTraversalSize(scene, path.string());
  coin::dropNormalsAndTextureCoordinates(scene);
  MeshBuilder builder = collectTriangles(scene, path.string());
  if (!declaresMaterial(scene)) builder.forgetColours();
  for (const std::string& warning : messages.warnings) {
    logWarning(path.string() + ": " + oneLine(warning));
  }
  return builder.finish(path);
}

}  // namespace lang2manip
