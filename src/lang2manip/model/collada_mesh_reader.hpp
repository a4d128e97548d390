#pragma once
/// @file Internal: reads the triangles of a COLLADA (.dae) file, for loadTriangleMesh().

#include <filesystem>

#include "lang2manip/model/triangle_mesh.hpp"

namespace lang2manip {

/// Reads the triangles of a COLLADA 1.4/1.5 file, in the file's root frame.
///
/// What is read: the scene's <instance_visual_scene> (else the first <visual_scene>; a file with
/// no visual scene places every <geometry> at the origin), its <node> tree with <matrix>,
/// <translate>, <rotate> and <scale> applied in document order, <instance_geometry>,
/// <instance_node> and <instance_controller> (a skin's source geometry under its
/// bind_shape_matrix, a morph's base geometry); in each <mesh>, the positions of <triangles>,
/// <polylist>, <polygons> (holes ignored), <trifans> and <tristrips>, polygons split into fans.
/// Lines, normals, texture coordinates and materials are skipped. The <unit meter="..."> of the
/// root <asset> is applied and <up_axis> ignored, as RViz does: URDF meshes are expressed in their
/// link frame as written.
///
/// Every count, offset and index is checked against the data it refers to, so a malformed or
/// hostile file is an error, never a read outside the file's arrays. (assimp 5.2's COLLADA reader
/// trusts them and crashes: tests/regression/mesh_dae/.)
///
/// @throws InputError "path:line: ..." for malformed XML, elements nested more than kMaxXmlDepth
/// levels, a URL that names no element or another file, numbers that are not finite, an index
/// beyond its array, instances nested more than kMaxXmlDepth levels or more than
/// kMaxColladaInstances in all or kMaxColladaCorners corners, <lookat>/<skew> transforms (not supported), and a mesh that is
/// unusable (see MeshBuilder::problem()). Thread-safe.
TriangleMesh readColladaMesh(const std::filesystem::path& path);

/// Most geometry and node instances one file may expand to (a node instanced twice at each of
/// 40 levels would otherwise mean 2^40 copies).
inline constexpr int kMaxColladaInstances = 100000;

/// Most triangle corners (three per triangle, before merging) one file may expand to: about
/// 3.3 million triangles, far beyond any collision or visual mesh of a robot.
inline constexpr long kMaxColladaCorners = 10000000;

}  // namespace lang2manip
