#pragma once
/// @file Reading what a run directory holds for viewers (render): the key moments of
/// viewer.json and the structure of scene.glb, each checked with errors that name the file.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lang2manip {

/// A moment of a run worth a picture.
struct ViewerMoment {
  double time = 0.0;
  std::string label;
};

/// The "moments" of a viewer document (format_version 1). Throws InputError naming `file` and
/// the field for a document of another kind or version, no moments, a moment without a finite
/// time >= 0 and a label or after the run's "duration", a "duration" that is not a number >= 0,
/// and "actions" that are not an array of objects.
std::vector<ViewerMoment> viewerMoments(const nlohmann::json& document, const std::string& file);

/// Throws InputError naming `file` unless `bytes` is a GLB of glTF 2.0 whose length matches its
/// header.
void checkGlbHeader(const std::string& bytes, const std::string& file);

/// Throws InputError naming `file` and what is wrong unless `bytes` is a well-formed GLB: the
/// header (checkGlbHeader()), a JSON chunk that is a glTF document and a binary chunk within the
/// file, and in the document every buffer, bufferView, accessor, mesh, node, scene and animation
/// index in range and every byte range inside its buffer (glb_structure.cpp).
void checkGlb(const std::string& bytes, const std::string& file);

}  // namespace lang2manip
