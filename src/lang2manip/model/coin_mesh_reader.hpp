#pragma once
/// @file Internal: reads Inventor .iv and VRML 1 / 2 .wrl/.vrml meshes through Coin3D, for
/// loadTriangleMesh().

#include <filesystem>

#include "lang2manip/model/triangle_mesh.hpp"

namespace lang2manip {

/// Reads the triangles of an Inventor or VRML file in its root frame (transforms applied,
/// primitives such as Cube, Sphere and Cylinder tessellated by Coin; points and lines dropped).
/// The caller has checked that the file exists and can be read. Coin's warnings (a missing
/// texture image among them) are logged as warnings "path: what".
///
/// Throws InputError located at `path` (with Coin's line number when it gives one) when the
/// file nests deeper than kMaxMeshNestingDepth, is malformed, holds a NURBS surface or a shape
/// that indexes coordinates that do not exist, or the mesh is unusable (see
/// MeshBuilder::problem()).
///
/// Thread-safe: files are read one at a time, since Coin's state is global.
TriangleMesh readMeshWithCoin(const std::filesystem::path& path);

}  // namespace lang2manip
