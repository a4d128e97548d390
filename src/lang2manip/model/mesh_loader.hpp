#pragma once
/// @file Loads triangle meshes from STL, DAE (COLLADA), OBJ, PLY (assimp) and Inventor .iv /
/// VRML .wrl (Coin3D), each file once.

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "lang2manip/model/triangle_mesh.hpp"

namespace lang2manip {

/// Largest mesh file read (a binary STL of five million triangles; vendors ship a few MB).
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t{256} << 20;

/// Reads one mesh file: STL, COLLADA, OBJ and PLY through assimp; Inventor .iv and VRML 1/2
/// .wrl/.vrml through Coin3D (chosen by the extension, in any case).
///
/// Transforms inside the file (COLLADA node transforms and <unit meter>, Inventor and VRML
/// transforms) are applied, so vertices are in the file's root frame. COLLADA <up_axis> is
/// ignored (a Z_UP file is not turned to Y up) and <unit> is applied, as RViz does; MoveIt's
/// geometric_shapes also ignores the up axis but drops the unit as well. Only triangles are kept
/// (points and lines are dropped); vertices shared by faces are merged, and triangles with no
/// area are dropped. Inventor/VRML primitives (Cube, Sphere, Cylinder, Cone, Box, ...)
/// are tessellated by Coin. A missing texture image only logs a warning.
///
/// Throws InputError "file[:line]: what" when the file is missing, not a regular file,
/// unreadable, of an unsupported format (the message lists the supported ones), malformed (with
/// the parser's reason, and Coin's line number), nested deeper than 1000 levels, indexes
/// coordinates that do not exist, has a non-finite vertex, has no triangles, is larger than
/// kMaxMeshFileBytes or has more than kMaxMeshTriangles triangles.
///
/// Thread-safe; Coin files are read one at a time (Coin's state is global). Prints nothing.
TriangleMesh loadTriangleMesh(const std::string& path);

/// File extensions loadTriangleMesh() accepts (lower case, with the dot).
const std::vector<std::string>& supportedMeshExtensions();

/// A cache of loaded meshes keyed by std::filesystem::weakly_canonical path, so that
/// "dir/./a.stl" and "dir/x/../a.stl" share one mesh: each file is read once. Thread-safe:
/// loads happen under the cache's lock, so threads asking for the same file get one mesh.
class MeshCache {
 public:
  /// The mesh of `path`, loading it on first use. Throws as loadTriangleMesh(); a failed load
  /// is not cached.
  std::shared_ptr<const TriangleMesh> get(const std::string& path);

  /// Number of distinct files loaded so far.
  [[nodiscard]] std::size_t size() const;

  /// The process-wide cache used by the model readers.
  static MeshCache& global();

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::shared_ptr<const TriangleMesh>> meshes_;
};

}  // namespace lang2manip
