#pragma once
/// @file Internal: reads STL, COLLADA, OBJ and PLY meshes through assimp, for loadTriangleMesh().

#include <filesystem>

#include "lang2manip/model/triangle_mesh.hpp"

namespace lang2manip {

/// Reads the triangles of an STL, COLLADA (.dae), OBJ or PLY file, node transforms applied, in
/// the file's root frame. The caller has checked that the file exists and can be read.
///
/// COLLADA: assimp 5.2 multiplies the root node's transform (the <visual_scene>'s) by the
/// <unit meter="..."> scale and by a rotation that turns <up_axis> Z_UP or X_UP into Y up. The
/// unit is kept and the up axis ignored, as RViz does (it skips the root transform and applies
/// the unit itself): URDF meshes are expressed in their link frame as written. MoveIt's
/// geometric_shapes clears the root transform, losing the unit too; we follow the spec there.
///
/// Throws InputError located at `path` when assimp cannot read the file, a COLLADA file nests
/// deeper than kMaxMeshNestingDepth, or the mesh is unusable (see MeshBuilder::problem()).
/// Thread-safe.
TriangleMesh readMeshWithAssimp(const std::filesystem::path& path);

}  // namespace lang2manip
