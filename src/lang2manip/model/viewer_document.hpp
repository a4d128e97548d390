#pragma once
/// @file Reading what a run directory holds for viewers (render): the key moments of
/// viewer.json and the header of scene.glb, each checked with errors that name the file.

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
/// the entry for a document of another kind or version, no moments, or a moment without a
/// finite time >= 0 and a label.
std::vector<ViewerMoment> viewerMoments(const nlohmann::json& document, const std::string& file);

/// Throws InputError naming `file` unless `bytes` is a GLB of glTF 2.0 whose length matches its
/// header.
void checkGlbHeader(const std::string& bytes, const std::string& file);

}  // namespace lang2manip
