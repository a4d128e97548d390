#include "lang2manip/model/gltf_writer.hpp"

#include <cmath>

#include "lang2manip/core/error.hpp"

namespace lang2manip {
namespace {

void addTriangle(TriangleMesh& mesh, int a, int b, int c) { mesh.triangles.push_back({a, b, c}); }

TriangleMesh boxMesh(const Vector3& size) {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.emplace_back((i & 1 ? 0.5 : -0.5) * size.x(), (i & 2 ? 0.5 : -0.5) * size.y(), (i & 4 ? 0.5 : -0.5) * size.z());
  }
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    addTriangle(mesh, f[0], f[1], f[2]);
    addTriangle(mesh, f[0], f[2], f[3]);
  }
  return mesh;
}

TriangleMesh cylinderMesh(double radius, double length, int segments) {
  TriangleMesh mesh;
  for (int i = 0; i < segments; ++i) {
    const double angle = 2.0 * M_PI * i / segments;
    for (const double z : {-0.5 * length, 0.5 * length}) mesh.vertices.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
  }
  const int bottom = static_cast<int>(mesh.vertices.size());
  mesh.vertices.emplace_back(0.0, 0.0, -0.5 * length);
  mesh.vertices.emplace_back(0.0, 0.0, 0.5 * length);
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % segments;
    addTriangle(mesh, 2 * i, 2 * j, 2 * j + 1);
    addTriangle(mesh, 2 * i, 2 * j + 1, 2 * i + 1);
    addTriangle(mesh, bottom, 2 * j, 2 * i);
    addTriangle(mesh, bottom + 1, 2 * i + 1, 2 * j + 1);
  }
  return mesh;
}

TriangleMesh sphereMesh(double radius, int segments) {
  TriangleMesh mesh;
  const int rings = std::max(2, segments / 2);
  mesh.vertices.emplace_back(0.0, 0.0, -radius);
  for (int r = 1; r < rings; ++r) {
    const double polar = M_PI * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double azimuth = 2.0 * M_PI * s / segments;
      mesh.vertices.emplace_back(radius * std::sin(polar) * std::cos(azimuth), radius * std::sin(polar) * std::sin(azimuth),
                                 -radius * std::cos(polar));
    }
  }
  const int top = static_cast<int>(mesh.vertices.size());
  mesh.vertices.emplace_back(0.0, 0.0, radius);
  const auto at = [segments](int ring, int s) { return 1 + (ring - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) {
    addTriangle(mesh, 0, at(1, s + 1), at(1, s));
    addTriangle(mesh, top, at(rings - 1, s), at(rings - 1, s + 1));
    for (int r = 1; r + 1 < rings; ++r) {
      addTriangle(mesh, at(r, s), at(r, s + 1), at(r + 1, s + 1));
      addTriangle(mesh, at(r, s), at(r + 1, s + 1), at(r + 1, s));
    }
  }
  return mesh;
}

void requireRoundSegments(int roundSegments) {
  if (roundSegments < 3) throw InputError("glTF: a round shape needs at least 3 segments, got " + std::to_string(roundSegments));
}

}  // namespace

TriangleMesh tessellated(const Geometry& geometry, int roundSegments) {
  requireRoundSegments(roundSegments);
  if (const auto* box = std::get_if<Box>(&geometry)) return boxMesh(box->size);
  if (const auto* sphere = std::get_if<Sphere>(&geometry)) return sphereMesh(sphere->radius, roundSegments);
  if (const auto* cylinder = std::get_if<Cylinder>(&geometry)) return cylinderMesh(cylinder->radius, cylinder->length, roundSegments);
  const auto& mesh = std::get<MeshGeometry>(geometry);
  TriangleMesh scaled;
  if (!mesh.mesh) return scaled;
  scaled.source = mesh.mesh->source;
  scaled.triangles = mesh.mesh->triangles;
  scaled.colour = mesh.mesh->colour;
  scaled.palette = mesh.mesh->palette;
  scaled.triangleColours = mesh.mesh->triangleColours;
  for (const Vector3& v : mesh.mesh->vertices) scaled.vertices.push_back(v.cwiseProduct(mesh.scale));
  return scaled;
}

std::string sceneToGlb(const Scene& scene, const GltfOptions& options, GltfSummary* summary) {
  requireRoundSegments(options.roundSegments);
  GlbBuilder builder(options.geometry, options.roundSegments);
  addSceneBodies(scene, builder);
  return builder.finish(summary);
}

std::vector<int> addSceneBodies(const Scene& scene, GlbBuilder& builder) {
  std::vector<int> nodes;
  for (const SceneRobot& robot : scene.robots()) {
    const std::vector<Pose> X_BL = robot.model->linkPoses(robot.configuration);
    for (std::size_t l = 0; l < robot.model->links().size(); ++l) {
      const Link& link = robot.model->links()[l];
      nodes.push_back(builder.addBody(robot.name + "/" + link.name, "link", link.visuals, link.collisions, robot.basePose * X_BL[l]));
    }
  }
  for (const SceneObject& object : scene.objects()) {
    nodes.push_back(builder.addBody(object.name, "object", object.visuals, object.collisions, scene.objectWorldPose(object.name)));
  }
  return nodes;
}

}  // namespace lang2manip
