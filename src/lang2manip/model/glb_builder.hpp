#pragma once
/// @file A glTF 2.0 binary (GLB) built body by body: each body (robot link, object) is a node at
/// its world pose whose children "visual" and "collision" hold its shapes; polylines and line sets
/// (tool paths, exploration trees) in named groups; animations of body poses over time. The
/// world's z-up frame hangs under a root node turned to glTF's y-up. Meshes and primitives are
/// written once per geometry and scale.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// What a GLB holds.
struct GltfSummary {
  int nodes = 0;
  int meshes = 0;
  int triangles = 0;
  /// Mesh shapes left out because their file was not loaded (UrdfReadOptions::loadMeshes off).
  int unloadedMeshes = 0;
};

/// Which geometry a body node carries.
enum class GltfGeometry {
  /// Its visual shapes. A robot link without one is drawn as nothing, as RViz draws it; an
  /// object without one (a Kautham obstacle gives one geometry) by its collision shapes.
  kVisual,
  kCollision,  ///< its collision shapes
  kBoth,       ///< both, as "visual" and "collision" children (the viewer shows one at a time)
};

class GlbBuilder {
 public:
  /// Throws InputError for roundSegments below 3.
  GlbBuilder(GltfGeometry geometry, int roundSegments);
  ~GlbBuilder();
  GlbBuilder(const GlbBuilder&) = delete;
  GlbBuilder& operator=(const GlbBuilder&) = delete;

  /// A body node named `name` with extras {"kind": kind} ("link" or "object") at world pose
  /// `X_WB`; its node index.
  int addBody(const std::string& name, const std::string& kind, const std::vector<Shape>& visuals,
              const std::vector<Shape>& collisions, const Pose& X_WB);
  /// A polyline (LINE_STRIP) in world coordinates, a child of the group node `group`.
  void addPolyline(const std::string& group, const std::string& name, const std::vector<Vector3>& points, const Vector4& rgba);
  /// Line segments (LINES) in world coordinates, a child of the group node `group`.
  void addLines(const std::string& group, const std::string& name, const std::vector<std::pair<Vector3, Vector3>>& lines,
                const Vector4& rgba);
  /// An animation `name`: at each of `times` (seconds, increasing), the world pose of each body
  /// node of `tracks` (node index, one pose per time). Linear interpolation.
  void addAnimation(const std::string& name, const std::vector<double>& times, const std::vector<std::pair<int, std::vector<Pose>>>& tracks);
  /// The GLB bytes; the builder is spent.
  std::string finish(GltfSummary* summary = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lang2manip
