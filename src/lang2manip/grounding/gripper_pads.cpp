// Where a gripper's pads meet an object: the contact face of each pad, found on its collision
// surface, and the band along the approach axis where the pads hold an object.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <variant>

#include "lang2manip/grounding/gripper_fingers.hpp"

namespace lang2manip::gripper_detail {
namespace {

/// A facet looks toward the other pads when its normal is within about 45 degrees of it.
constexpr double kFacingCosine = 0.7;
/// Facets whose distances along the inward direction differ by less than this form one face (m).
constexpr double kLayerDepth = 1e-3;
/// A facet whose normal is within about 18 degrees of its face's lies along it.
constexpr double kAlongFaceCosine = 0.95;
/// A face holds an object when its area is at least this share of the largest one facing it.
constexpr double kLeastFaceShare = 0.25;
constexpr int kCylinderStrips = 16;

void addPolygon(std::vector<Vector3> corners, std::vector<Facet>& facets) {
  const Vector3 cross = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
  double area = 0.5 * cross.norm();
  if (corners.size() == 4) area *= 2.0;  // a parallelogram
  if (area <= 0.0) return;
  facets.push_back({cross.normalized(), area, std::move(corners)});
}

void addBoxFacets(const Box& box, std::vector<Facet>& facets) {
  const Vector3 half = 0.5 * box.size;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    for (const double side : {-1.0, 1.0}) {
      // Corners ordered so that (c1 - c0) x (c2 - c0) points along side * axis.
      std::vector<Vector3> corners;
      for (const auto& [a, b] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {-1.0, 1.0}}) {
        Vector3 p;
        p[axis] = side * half[axis];
        p[u] = a * half[u];
        p[v] = b * half[v];
        corners.push_back(p);
      }
      if (side < 0.0) std::swap(corners[1], corners[2]);
      corners.push_back(corners[1] + corners[2] - corners[0]);
      addPolygon(std::move(corners), facets);
    }
  }
}

void addCylinderFacets(const Cylinder& cylinder, std::vector<Facet>& facets) {
  const double h = 0.5 * cylinder.length;
  for (int k = 0; k < kCylinderStrips; ++k) {
    const double a0 = 2.0 * std::numbers::pi * k / kCylinderStrips;
    const double a1 = 2.0 * std::numbers::pi * (k + 1) / kCylinderStrips;
    const Vector3 r0(cylinder.radius * std::cos(a0), cylinder.radius * std::sin(a0), 0.0);
    const Vector3 r1(cylinder.radius * std::cos(a1), cylinder.radius * std::sin(a1), 0.0);
    addPolygon({r0 - h * Vector3::UnitZ(), r1 - h * Vector3::UnitZ(), r0 + h * Vector3::UnitZ(), r1 + h * Vector3::UnitZ()}, facets);
  }
}

void addMeshFacets(const MeshGeometry& mesh, std::vector<Facet>& facets) {
  if (!mesh.mesh) return;
  const std::vector<Vector3>& vertices = mesh.mesh->vertices;
  const auto count = static_cast<int>(vertices.size());
  // A mirroring scale turns the winding, and with it the normals, inside out.
  const bool mirrored = mesh.scale.prod() < 0.0;
  for (const std::array<int, 3>& triangle : mesh.mesh->triangles) {
    if (std::any_of(triangle.begin(), triangle.end(), [&](int v) { return v < 0 || v >= count; })) continue;
    const auto corner = [&](int k) { return Vector3(vertices[static_cast<std::size_t>(triangle[static_cast<std::size_t>(k)])].cwiseProduct(mesh.scale)); };
    addPolygon({corner(0), corner(mirrored ? 2 : 1), corner(mirrored ? 1 : 2)}, facets);
  }
}

/// The lowest and highest of `points` along `axis`.
std::pair<double, double> rangeAlong(const std::vector<Vector3>& points, const Vector3& axis) {
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (const Vector3& p : points) {
    low = std::min(low, p.dot(axis));
    high = std::max(high, p.dot(axis));
  }
  return {low, high};
}

}  // namespace

std::vector<Facet> collisionFacets(const Link& link) {
  std::vector<Facet> facets;
  for (const Shape& shape : link.collisions) {
    const std::size_t first = facets.size();
    if (const auto* box = std::get_if<Box>(&shape.geometry)) addBoxFacets(*box, facets);
    if (const auto* cylinder = std::get_if<Cylinder>(&shape.geometry)) addCylinderFacets(*cylinder, facets);
    if (const auto* mesh = std::get_if<MeshGeometry>(&shape.geometry)) addMeshFacets(*mesh, facets);
    for (std::size_t i = first; i < facets.size(); ++i) {
      facets[i].normal = shape.origin.linear() * facets[i].normal;
      for (Vector3& corner : facets[i].corners) corner = shape.origin * corner;
    }
  }
  return facets;
}

ContactFace contactFace(const FingerLink& link, const Pose& X_TL, const Vector3& inward, const Vector3& approach, double nearest) {
  struct Facing {
    double depth;
    std::size_t facet;
  };
  std::vector<Facing> facing;
  for (std::size_t i = 0; i < link.facets.size(); ++i) {
    const Facet& facet = link.facets[i];
    if ((X_TL.linear() * facet.normal).dot(inward) < kFacingCosine) continue;
    Vector3 centre = Vector3::Zero();
    for (const Vector3& corner : facet.corners) centre += corner;
    centre = X_TL * (centre / static_cast<double>(facet.corners.size()));
    if (centre.dot(approach) < nearest) continue;
    facing.push_back({centre.dot(inward), i});
  }
  if (facing.empty()) return {};
  std::sort(facing.begin(), facing.end(), [](const Facing& a, const Facing& b) { return a.depth < b.depth; });
  struct Layer {
    std::size_t first, end;
    double area;
  };
  std::vector<Layer> layers;
  for (std::size_t first = 0; first < facing.size();) {
    Layer layer{first, first + 1, link.facets[facing[first].facet].area};
    while (layer.end < facing.size() && facing[layer.end].depth - facing[layer.end - 1].depth <= kLayerDepth) {
      layer.area += link.facets[facing[layer.end++].facet].area;
    }
    layers.push_back(layer);
    first = layer.end;
  }
  double largest = 0.0;
  for (const Layer& layer : layers) largest = std::max(largest, layer.area);
  // The innermost layer of a good size: a raised pad stands in front of the face it sits on, and
  // a lip or rib in front of both is too small to hold anything.
  const auto pad = std::find_if(layers.rbegin(), layers.rend(), [&](const Layer& layer) { return layer.area >= kLeastFaceShare * largest; });
  const std::size_t bestFirst = pad->first, bestEnd = pad->end;
  Vector3 mainNormal = Vector3::Zero();
  for (std::size_t i = bestFirst; i < bestEnd; ++i) mainNormal += link.facets[facing[i].facet].area * link.facets[facing[i].facet].normal;
  mainNormal.normalize();
  ContactFace face;
  for (std::size_t i = bestFirst; i < bestEnd; ++i) {
    const Facet& facet = link.facets[facing[i].facet];
    Vector3 centre = Vector3::Zero();
    for (const Vector3& corner : facet.corners) centre += corner;
    face.corners.insert(face.corners.end(), facet.corners.begin(), facet.corners.end());
    // A facet along the face lies on it to its corners; a bevel's corners stand back from it.
    if (facet.normal.dot(mainNormal) >= kAlongFaceCosine) face.surface.insert(face.surface.end(), facet.corners.begin(), facet.corners.end());
    face.surface.push_back(centre / static_cast<double>(facet.corners.size()));
  }
  return face;
}

std::pair<double, double> contactBand(const FingerSet& fingers, const PadLayout& layout, const std::vector<Pose>& poses) {
  double low = -std::numeric_limits<double>::infinity(), high = -low;
  double unionLow = high, unionHigh = low;
  for (std::size_t f = 0; f < layout.pads.size(); ++f) {
    const FingerLink& pad = fingers.links()[layout.pads[f]];
    const Pose& X_TL = poses[static_cast<std::size_t>(pad.link)];
    std::vector<Vector3> corners;
    const bool hasFace = f < layout.contactFaces.size() && !layout.contactFaces[f].empty();
    for (const Vector3& p : hasFace ? layout.contactFaces[f].corners : pad.points) corners.push_back(X_TL * p);
    const auto [padLow, padHigh] = rangeAlong(corners, layout.approach);
    low = std::max(low, padLow);
    high = std::min(high, padHigh);
    unionLow = std::min(unionLow, padLow);
    unionHigh = std::max(unionHigh, padHigh);
  }
  if (!layout.jawFace.empty() && fingers.fixedJaw()) {
    const Pose& X_TJ = poses[static_cast<std::size_t>(fingers.fixedJaw()->link)];
    std::vector<Vector3> corners;
    for (const Vector3& p : layout.jawFace.corners) corners.push_back(X_TJ * p);
    const auto [jawLow, jawHigh] = rangeAlong(corners, layout.approach);
    low = std::max(low, jawLow);
    high = std::min(high, jawHigh);
    unionLow = std::min(unionLow, jawLow);
    unionHigh = std::max(unionHigh, jawHigh);
  }
  return low <= high ? std::pair{low, high} : std::pair{unionLow, unionHigh};
}

std::vector<Vector3> jawContactPoints(const FingerSet& fingers, const PadLayout& layout, const std::vector<Pose>& poses) {
  std::vector<Vector3> points;
  if (layout.jawFace.empty() || !fingers.fixedJaw()) return points;
  const Pose& X_TJ = poses[static_cast<std::size_t>(fingers.fixedJaw()->link)];
  for (const Vector3& p : layout.jawFace.surface) points.push_back(X_TJ * p);
  return points;
}

std::vector<Vector3> padContactPoints(const FingerSet& fingers, const PadLayout& layout, std::size_t f,
                                      const std::vector<Pose>& poses) {
  if (f < layout.contactFaces.size() && !layout.contactFaces[f].empty()) {
    const Pose& X_TL = poses[static_cast<std::size_t>(fingers.links()[layout.pads[f]].link)];
    std::vector<Vector3> points;
    points.reserve(layout.contactFaces[f].surface.size());
    for (const Vector3& p : layout.contactFaces[f].surface) points.push_back(X_TL * p);
    return points;
  }
  return fingers.pointsInTool(layout.pads[f], poses);
}

}  // namespace lang2manip::gripper_detail
