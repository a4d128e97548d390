#pragma once
/// @file Vertex normals for drawing a triangle mesh smoothly where it is curved and sharply where
/// it has edges: coincident vertices are welded (STL files repeat each vertex per triangle), and a
/// vertex is split where the faces around it meet at more than a crease angle, each copy taking
/// the area-weighted normal of the faces on its side (as CAD exporters and three.js's
/// toCreasedNormals shade).

#include <array>
#include <vector>

#include "lang2manip/model/triangle_mesh.hpp"

namespace lang2manip {

/// A mesh with one unit normal per vertex.
struct ShadedMesh {
  std::vector<Vector3> vertices;
  std::vector<Vector3> normals;
  std::vector<std::array<int, 3>> triangles;
  /// For each triangle, the index of the input triangle it came from.
  std::vector<int> sourceTriangles;
};

/// Faces meeting at more than this angle (rad) keep a sharp edge: 40 degrees.
inline constexpr double kDefaultCreaseRadians = 0.698;

/// `mesh` with normals as described above. Degenerate triangles are kept (their corners take their
/// neighbours' normals); triangles naming a vertex out of range are dropped.
ShadedMesh shadedMesh(const TriangleMesh& mesh, double creaseRadians = kDefaultCreaseRadians);

}  // namespace lang2manip
