#include "lang2manip/model/assimp_mesh_reader.hpp"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <iterator>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "lang2manip/model/mesh_builder.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;

Eigen::Affine3d toAffine(const aiMatrix4x4& m) {
  Eigen::Matrix4d matrix;
  matrix << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2,
      m.d3, m.d4;
  return Eigen::Affine3d(matrix);
}

/// X * v in plain arithmetic (this runs per vertex; see hasArea() in mesh_builder.cpp).
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
    if (face.mNumIndices < 3 || face.mIndices == nullptr) continue;
    // A polygon (PLY faces are not triangulated by assimp, see readMeshWithAssimp) as a fan.
    for (unsigned i = 1; i + 1 < face.mNumIndices; ++i) {
      builder.addTriangle(index(face.mIndices[0]), index(face.mIndices[i]), index(face.mIndices[i + 1]));
    }
  }
}

/// The diffuse colour of `mesh`'s material; none for assimp's default material (a format
/// without materials, such as STL) or a material without one.
std::optional<Vector3> diffuseColour(const aiScene& scene, const aiMesh& mesh) {
  if (scene.mMaterials == nullptr || mesh.mMaterialIndex >= scene.mNumMaterials || scene.mMaterials[mesh.mMaterialIndex] == nullptr) {
    return std::nullopt;
  }
  const aiMaterial& material = *scene.mMaterials[mesh.mMaterialIndex];
  aiString name;
  if (material.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && std::string(name.C_Str()) == AI_DEFAULT_MATERIAL_NAME) return std::nullopt;
  aiColor4D colour;
  if (material.Get(AI_MATKEY_COLOR_DIFFUSE, colour) != AI_SUCCESS) return std::nullopt;
  return Vector3(colour.r, colour.g, colour.b);
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
        builder.setColour(diffuseColour(scene, *scene.mMeshes[meshIndex]));
        addAssimpMesh(*scene.mMeshes[meshIndex], X_RN, builder);
      }
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) {
      const aiNode* child = node->mChildren[c];
      if (child != nullptr) pending.emplace_back(child, X_RN * toAffine(child->mTransformation));
    }
  }
}

/// Drops all but positions.
void configure(Assimp::Importer& importer) {
  // Only positions are kept: dropping normals and the like first lets JoinIdenticalVertices
  // merge the corners that faces share (an STL repeats them with each face's normal).
  importer.SetPropertyInteger(
      AI_CONFIG_PP_RVC_FLAGS,
      aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_COLORS |
          aiComponent_TEXCOORDS | aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
          aiComponent_TEXTURES | aiComponent_LIGHTS | aiComponent_CAMERAS);
}

bool isPlyType(const std::string& word) {
  static const std::vector<std::string> kTypes = {
      "char", "uchar", "short", "ushort", "int", "uint", "float", "double", "int8", "uint8",
      "int16", "uint16", "int32", "uint32", "float32", "float64"};
  return std::find(kTypes.begin(), kTypes.end(), word) != kTypes.end();
}

/// A count of elements that the file can hold (each takes at least one byte).
bool isPlyCount(const std::string& word, std::uintmax_t fileSize) {
  if (word.empty() || word.size() > 19 ||
      word.find_first_not_of("0123456789") != std::string::npos) {
    return false;
  }
  return std::stoull(word) <= fileSize;
}

/// Whether one header line (split in words, after the first) is well formed.
bool isPlyHeaderLine(const std::vector<std::string>& w, std::uintmax_t fileSize) {
  if (w[0] == "comment" || w[0] == "obj_info") return true;
  if (w[0] == "end_header") return w.size() == 1;
  if (w[0] == "format") {
    return w.size() == 3 && w[2] == "1.0" &&
           (w[1] == "ascii" || w[1] == "binary_little_endian" || w[1] == "binary_big_endian");
  }
  if (w[0] == "element") return w.size() == 3 && isPlyCount(w[2], fileSize);
  if (w[0] == "property") {
    return (w.size() == 3 && isPlyType(w[1])) ||
           (w.size() == 5 && w[1] == "list" && isPlyType(w[2]) && isPlyType(w[3]));
  }
  return false;
}

/// A byte below 0x20 but tab and CR, or DEL: never in a text PLY (assimp's reader stops at a NUL
/// in the middle of a line and reads past its buffer).
bool hasControlCharacter(const std::string& line) {
  return std::any_of(line.begin(), line.end(), [](char c) {
    return (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r') || c == 0x7f;
  });
}

std::vector<std::string> wordsOf(const std::string& line) {
  std::istringstream stream(line);
  return {std::istream_iterator<std::string>(stream), std::istream_iterator<std::string>()};
}

/// One PLY element of the header: how many, and which of its properties are lists.
struct PlyElement {
  std::uintmax_t count = 0;
  std::vector<bool> isList;
};

/// In an ASCII body, every element on its own line with as many values as its properties and
/// list counts say (assimp allocates a list's count before reading it).
void checkPlyAsciiBody(std::istream& in, const std::vector<PlyElement>& elements,
                       const fs::path& path, int number) {
  std::string line;
  for (const PlyElement& element : elements) {
    for (std::uintmax_t e = 0; e < element.count; ++e) {
      ++number;
      if (!std::getline(in, line)) {
        throw InputError(SourceLocation{path.string(), number}, "PLY body ends before the counts of its header");
      }
      if (hasControlCharacter(line)) {
        throw InputError(SourceLocation{path.string(), number}, "PLY text line holds a control character");
      }
      const std::vector<std::string> values = wordsOf(line);
      std::size_t next = 0;
      for (const bool list : element.isList) {
        std::size_t take = 1;
        if (list) {
          const std::string count = next < values.size() ? values[next] : "";
          if (count.empty() || count.size() > 9 || count.find_first_not_of("0123456789") != std::string::npos ||
              std::stoul(count) > values.size() - next - 1) {
            throw InputError(SourceLocation{path.string(), number}, "PLY list count \"" + count.substr(0, 20) +
                                                                        "\" does not match the values on its line");
          }
          take = 1 + std::stoul(count);
        }
        if (next + take > values.size()) {
          throw InputError(SourceLocation{path.string(), number}, "PLY line has fewer values than its properties");
        }
        next += take;
      }
    }
  }
}

/// assimp 5.2's PLY reader trusts its header: without end_header it never returns, and a
/// misread element or property line, or a list count beyond its line, makes it allocate without
/// bound (found by fuzz_mesh_ply; tests/regression/mesh_ply/). So the header is checked line by
/// line before assimp sees the file ("ply", "format ascii|binary_* 1.0", comments,
/// "element NAME COUNT" with COUNT at most the file's size, "property TYPE NAME",
/// "property list TYPE TYPE NAME", "end_header"), and so is an ASCII body's list counts.
void checkPlyHeader(const fs::path& path) {
  std::error_code error;
  const std::uintmax_t fileSize = fs::file_size(path, error);
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::vector<PlyElement> elements;
  bool ascii = false;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::vector<std::string> words = wordsOf(line);
    const bool good = number == 1 ? words.size() == 1 && words[0] == "ply"
                                  : words.empty() || isPlyHeaderLine(words, fileSize);
    if (!good || hasControlCharacter(line) || (!words.empty() && words[0] == "property" && elements.empty())) {
      throw InputError(SourceLocation{path.string(), number},
                       "malformed PLY header line \"" + line.substr(0, 60) + "\"");
    }
    if (words.empty() || number == 1) continue;
    if (words[0] == "format") ascii = words[1] == "ascii";
    if (words[0] == "element") elements.push_back({std::stoull(words[2]), {}});
    if (words[0] == "property") elements.back().isList.push_back(words[1] == "list");
    if (words[0] == "end_header") {
      if (ascii) checkPlyAsciiBody(in, elements, path, number);
      return;
    }
  }
  throw InputError(SourceLocation{path.string(), 0}, "PLY header has no end_header line");
}

}  // namespace

TriangleMesh readMeshWithAssimp(const fs::path& path) {
  if (lowerCaseExtension(path) == ".ply") checkPlyHeader(path);
  Assimp::Importer importer;
  configure(importer);
  // assimp's PLY reader can build faces with no or out-of-range indices and face counts that
  // disagree with the header, on which its post-processing steps abort (ai_asserts in
  // TriangulateProcess; tests/regression/mesh_ply/). A PLY is indexed already: it gets no step,
  // and addAssimpMesh triangulates its polygons and checks every index.
  const unsigned steps = lowerCaseExtension(path) == ".ply"
                             ? 0U
                             : aiProcess_RemoveComponent | aiProcess_Triangulate |
                                   aiProcess_JoinIdenticalVertices | aiProcess_SortByPType;
  const aiScene* scene = importer.ReadFile(path.string(), steps);
  if (scene == nullptr) {
    throw InputError(SourceLocation{path.string(), 0},
                     std::string("cannot read mesh: ") + importer.GetErrorString());
  }
  MeshBuilder builder;
  if (scene->mRootNode != nullptr) addAssimpScene(*scene, builder);
  return builder.finish(path);
}

}  // namespace lang2manip
