#pragma once
/// @file An indexed triangle mesh, in the units of the file it came from (scale not applied).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"

namespace lang2manip {

/// Immutable after loading; shared between every model that uses the same file.
struct TriangleMesh {
  std::vector<Vector3> vertices;
  std::vector<std::array<int, 3>> triangles;
  /// The file it was read from (absolute path), for messages.
  std::string source;
  /// The diffuse colour (RGB, 0..1) that covers most of its surface, from the file's own
  /// materials (Inventor/VRML Material, COLLADA effects, OBJ/PLY materials); none when the file
  /// gives none.
  std::optional<Vector3> colour;
  /// Every colour the file gives its surfaces (diffuse RGB, 0..1), and for each triangle the index
  /// of its colour in `palette` (-1: none); both empty when the file gives no colour. Drawn as
  /// RViz draws a mesh's materials; collision ignores them.
  std::vector<Vector3> palette;
  std::vector<int> triangleColours;

  /// Axis-aligned bounds of the vertices (empty box when there are none).
  [[nodiscard]] AlignedBox3 bounds() const;
};

}  // namespace lang2manip
