#pragma once
/// @file Scenes as glTF 2.0 binary (GLB), the format browsers (three.js) and every glTF viewer
/// draw: each robot link and object shape placed in the world, meshes of every format the model
/// layer reads (STL, DAE, OBJ, PLY, Inventor, VRML) and primitives tessellated, with their
/// colours. The world's z-up frame hangs under a root node turned to glTF's y-up.

#include <string>

#include "lang2manip/model/scene.hpp"

namespace lang2manip {

struct GltfOptions {
  /// Draw the collision geometry instead of the visual one (links and objects without visual
  /// geometry are drawn by their collision geometry anyway).
  bool collision = false;
  /// Segments around a cylinder or sphere.
  int roundSegments = 24;
};

/// What was written.
struct GltfSummary {
  int nodes = 0;
  int meshes = 0;
  int triangles = 0;
  /// Mesh shapes left out because their file was not loaded (UrdfReadOptions::loadMeshes off).
  int unloadedMeshes = 0;
};

/// The triangles of a geometry in its own frame, scale applied (primitives tessellated with
/// `roundSegments` segments around).
TriangleMesh tessellated(const Geometry& geometry, int roundSegments = 24);

/// The scene with each robot at its configuration (held objects with their links) as GLB bytes.
/// Throws InputError for roundSegments below 3.
std::string sceneToGlb(const Scene& scene, const GltfOptions& options = {}, GltfSummary* summary = nullptr);

}  // namespace lang2manip
