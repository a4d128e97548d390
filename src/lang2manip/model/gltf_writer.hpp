#pragma once
/// @file Scenes as glTF 2.0 binary (GLB), the format browsers (three.js) and every glTF viewer
/// draw: each robot link and object shape placed in the world, meshes of every format the model
/// layer reads (STL, DAE, OBJ, PLY, Inventor, VRML) and primitives tessellated, with their
/// colours. The world's z-up frame hangs under a root node turned to glTF's y-up.

#include <string>
#include <vector>

#include "lang2manip/model/glb_builder.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {

struct GltfOptions {
  /// The visual geometry (links without one are not drawn, as RViz does not draw them; objects
  /// without one are drawn by their collision geometry), the collision geometry, or both (as
  /// each body's "visual" and "collision" children; the viewer shows collision when toggled).
  GltfGeometry geometry = GltfGeometry::kVisual;
  /// Segments around a cylinder or sphere.
  int roundSegments = 24;
};

/// The triangles of a geometry in its own frame, scale applied (primitives tessellated with
/// `roundSegments` segments around).
TriangleMesh tessellated(const Geometry& geometry, int roundSegments = 24);

/// The scene with each robot at its configuration (held objects with their links) as GLB bytes.
/// Throws InputError for roundSegments below 3.
std::string sceneToGlb(const Scene& scene, const GltfOptions& options = {}, GltfSummary* summary = nullptr);

/// Adds a body node for every link of every robot (named "robot/link", kind "link") and every
/// object (kind "object") at its place in `scene`; their node indices, links first, in order.
std::vector<int> addSceneBodies(const Scene& scene, GlbBuilder& builder);

}  // namespace lang2manip
