#include "lang2manip/model/mesh_shading.hpp"

#include <cmath>
#include <map>
#include <utility>
#include <tuple>

namespace lang2manip {
namespace {

/// Vertex indices with coincident positions made one.
std::vector<int> weldedIndices(const std::vector<Vector3>& vertices) {
  std::map<std::tuple<double, double, double>, int> first;
  std::vector<int> welded(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Vector3& v = vertices[i];
    welded[i] = first.try_emplace({v.x(), v.y(), v.z()}, static_cast<int>(i)).first->second;
  }
  return welded;
}

bool inRange(const std::array<int, 3>& triangle, std::size_t count) {
  for (const int i : triangle) {
    if (i < 0 || static_cast<std::size_t>(i) >= count) return false;
  }
  return true;
}

}  // namespace

ShadedMesh shadedMesh(const TriangleMesh& mesh, double creaseRadians) {
  const std::vector<int> welded = weldedIndices(mesh.vertices);
  std::vector<std::array<int, 3>> faces;
  std::vector<int> sources;
  std::vector<Vector3> faceNormals;  // area-weighted (twice the area)
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& triangle = mesh.triangles[t];
    if (!inRange(triangle, mesh.vertices.size())) continue;
    sources.push_back(static_cast<int>(t));
    const std::array<int, 3> face{welded[static_cast<std::size_t>(triangle[0])], welded[static_cast<std::size_t>(triangle[1])],
                                  welded[static_cast<std::size_t>(triangle[2])]};
    const Vector3& a = mesh.vertices[static_cast<std::size_t>(face[0])];
    faces.push_back(face);
    faceNormals.push_back((mesh.vertices[static_cast<std::size_t>(face[1])] - a).cross(mesh.vertices[static_cast<std::size_t>(face[2])] - a));
  }
  std::vector<std::vector<int>> facesAt(mesh.vertices.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (const int v : faces[f]) facesAt[static_cast<std::size_t>(v)].push_back(static_cast<int>(f));
  }
  const double cosCrease = std::cos(creaseRadians);
  ShadedMesh shaded;
  // One output vertex per (position, normal) pair.
  std::map<std::tuple<int, double, double, double>, int> copies;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Vector3 own = faceNormals[f].normalized();
    std::array<int, 3> corners{};
    for (int c = 0; c < 3; ++c) {
      const int v = faces[f][static_cast<std::size_t>(c)];
      Vector3 sum = Vector3::Zero();
      for (const int g : facesAt[static_cast<std::size_t>(v)]) {
        const Vector3& other = faceNormals[static_cast<std::size_t>(g)];
        const double length = other.norm();
        if (length == 0.0) continue;
        if (own.isZero() || own.dot(other) >= cosCrease * length) sum += other;
      }
      const Vector3 normal = sum.norm() > 0.0 ? sum.normalized() : Vector3::UnitZ();
      const auto [entry, added] = copies.try_emplace({v, normal.x(), normal.y(), normal.z()}, static_cast<int>(shaded.vertices.size()));
      if (added) {
        shaded.vertices.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
        shaded.normals.push_back(normal);
      }
      corners[static_cast<std::size_t>(c)] = entry->second;
    }
    shaded.triangles.push_back(corners);
  }
  shaded.sourceTriangles = std::move(sources);
  return shaded;
}

}  // namespace lang2manip
