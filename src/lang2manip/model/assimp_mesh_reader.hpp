#pragma once
/// @file Internal: reads STL, OBJ and PLY meshes through assimp, for loadTriangleMesh().

#include <filesystem>

#include "lang2manip/model/triangle_mesh.hpp"

namespace lang2manip {

/// Reads the triangles of an STL, OBJ or PLY file, node transforms applied, in the file's root
/// frame. The caller has checked that the file exists and can be read. (COLLADA is read by
/// readColladaMesh(): assimp 5.2's COLLADA reader crashes on inconsistent files.)
///
/// Throws InputError located at `path` when assimp cannot read the file or the mesh is unusable
/// (see MeshBuilder::problem()). Thread-safe.
TriangleMesh readMeshWithAssimp(const std::filesystem::path& path);

}  // namespace lang2manip
