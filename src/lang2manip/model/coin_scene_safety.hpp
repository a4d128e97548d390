#pragma once
/// @file What makes a Coin (Inventor/VRML) scene safe to read and tessellate: Coin trusts the
/// indices, counts and names of a file and crashes or loops on bad ones (each check below was
/// found by fuzz_mesh_iv or fuzz_mesh_wrl; their inputs are in tests/regression/). Used by
/// coin_mesh_reader.cpp only, under its Coin mutex.

#include <filesystem>
#include <string>

class SoCallbackAction;
class SoNode;

namespace lang2manip::coin {

/// Throws InputError (naming `path`) when the file has a File node and a '%' anywhere: Coin
/// formats the message about a missing include with the name as the format string.
void checkIncludeNames(const std::filesystem::path& path);

/// Throws InputError (naming `name`) when a traversal of `root` would visit more than a million
/// nodes (Array, MultipleCopy and USE repeat their children) or a node contains itself.
void checkTraversalSize(SoNode* root, const std::string& name);

/// Empties normals, texture coordinates and their indices and binds materials OVERALL on every
/// node reachable from `root` (Coin indexes them unchecked); only positions matter here.
void dropNormalsAndTextureCoordinates(SoNode* root);

/// Whether `shape` draws lines or points (no triangles to collect).
bool isLineOrPointShape(const SoNode& shape);

/// Why Coin cannot safely tessellate `shape` in the traversal state of `action` (coordinate
/// indices or counts out of range, faces of fewer than 3 vertices, NURBS), or "".
std::string shapeProblem(const SoCallbackAction& action, const SoNode& shape);

}  // namespace lang2manip::coin
