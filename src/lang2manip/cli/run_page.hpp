#pragma once
/// @file The self-contained run page (run.html): the viewer's script, the run document and the
/// scene GLB in one HTML file that opens offline from the file system; and where the built
/// viewer is.

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace lang2manip {

/// Edges of an exploration graph kept per planner query by --record-tree: enough to see the
/// exploration, few enough for a page of a few megabytes.
inline constexpr std::size_t kRecordedTreeEdges = 20000;

/// The built viewer's directory (viewer.js, index.html): $LANG2MANIP_VIEWER_DIR when set, else
/// build/viewer/dist beside a build tree's program or PREFIX/share/lang2manip/viewer beside an
/// installed one; empty when none has viewer.js.
std::filesystem::path builtViewerDirectory();

/// The viewer's script, read from builtViewerDirectory(). Throws InputError saying how to get it
/// when there is none.
std::string viewerScript();

/// The page: `runDocument` and `glb` (base64) inline, then `script`. Throws InputError when the
/// script could end its <script> element early (it contains "</script").
std::string runPageHtml(const nlohmann::json& runDocument, const std::string& glb, const std::string& script);

/// Base64 (RFC 4648, with padding).
std::string base64(const std::string& bytes);

}  // namespace lang2manip
