#pragma once
/// @file Internal: pieces shared by the mesh readers (assimp_mesh_reader.cpp and
/// coin_mesh_reader.cpp): the builder that collects triangles into an indexed mesh, and the
/// nesting-depth pre-scan that protects the parsers' stacks.

#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <unordered_map>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/triangle_mesh.hpp"

namespace lang2manip {

/// Most triangles one mesh may have: ten times a detailed vendor visual mesh, and a bound on the
/// memory of the collision structures built from it.
inline constexpr std::size_t kMaxMeshTriangles = 2000000;

/// Collects root-frame triangles into an indexed mesh. Never throws while collecting (it is
/// called from inside Coin's traversal): invalid input is remembered; check problem() afterwards.
class MeshBuilder {
 public:
  static constexpr int kInvalid = -1;

  /// Appends a vertex; kInvalid when it is not finite or the mesh is full.
  int addVertex(const Vector3& point);

  /// The index of a vertex with exactly these coordinates, appending one if there is none.
  int mergedVertex(const Vector3& point);

  /// Adds a triangle unless an index is invalid, it has no area (nothing to collide with) or the
  /// mesh has kMaxMeshTriangles already (remembered as a problem); its area counts for the colour
  /// set last.
  void addTriangle(int a, int b, int c);

  /// The diffuse colour (RGB, 0..1) of the triangles added next; none: no colour of the file.
  void setColour(const std::optional<Vector3>& rgb) { colour_ = rgb; }
  /// Forgets the colours of the triangles added so far (they were no colour of the file).
  void forgetColours() {
    colour_.reset();
    colourAreas_.clear();
    paletteIndex_.clear();
    mesh_.palette.clear();
    mesh_.triangleColours.assign(mesh_.triangleColours.size(), -1);
  }

  /// What makes the collected mesh unusable, or "" when it is fine.
  [[nodiscard]] std::string problem() const;

  /// The collected mesh, its source set to `source`.
  TriangleMesh take(std::string source);

  /// The collected mesh read from `path`, its source the absolute path. Throws InputError
  /// "path: mesh <problem>" when problem() is not empty.
  TriangleMesh finish(const std::filesystem::path& path);

 private:
  struct KeyHash {
    std::size_t operator()(const std::array<double, 3>& key) const noexcept;
  };

  TriangleMesh mesh_;
  std::unordered_map<std::array<double, 3>, int, KeyHash> merged_;
  std::optional<Vector3> colour_;
  /// Surface area per colour (RGB rounded to 1/255).
  std::unordered_map<std::array<double, 3>, double, KeyHash> colourAreas_;
  /// Index in mesh_.palette per colour.
  std::unordered_map<std::array<double, 3>, int, KeyHash> paletteIndex_;
  bool nonFinite_ = false;
  bool tooLarge_ = false;
  bool tooManyTriangles_ = false;
};

/// The deepest nesting of { } and [ ] an Inventor or VRML file may have. Coin's parser recurses
/// once per nesting level and overflows the stack on files nested some 10,000 levels deep, so
/// deeper files are refused before they are parsed.
constexpr int kMaxMeshNestingDepth = 1000;

/// Throws InputError "path: nesting deeper than 1000 levels..." when the Inventor or VRML text
/// at `path` nests braces deeper than kMaxMeshNestingDepth (binary Inventor is not scanned).
void checkBraceNestingDepth(const std::filesystem::path& path);

/// The extension of `path` in lower case, with the dot ("" when there is none).
std::string lowerCaseExtension(const std::filesystem::path& path);

}  // namespace lang2manip
