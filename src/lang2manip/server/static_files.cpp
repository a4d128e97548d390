#include "lang2manip/server/static_files.hpp"

#include <fstream>
#include <sstream>

#include "lang2manip/server/api_types.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;

constexpr std::uintmax_t kMaxStaticBytes = std::uintmax_t{64} << 20;

std::string contentTypeOf(const fs::path& file) {
  const std::string extension = file.extension().string();
  if (extension == ".html") return "text/html; charset=utf-8";
  if (extension == ".js" || extension == ".mjs") return "text/javascript; charset=utf-8";
  if (extension == ".css") return "text/css; charset=utf-8";
  if (extension == ".json") return "application/json";
  if (extension == ".glb") return "model/gltf-binary";
  if (extension == ".png") return "image/png";
  if (extension == ".svg") return "image/svg+xml";
  return "application/octet-stream";
}

/// The path below the directory, refusing anything that could leave it.
fs::path relativePath(const std::string& urlPath) {
  std::string relative = urlPath.empty() || urlPath == "/" ? "index.html" : urlPath.substr(urlPath[0] == '/' ? 1 : 0);
  if (relative.find('\\') != std::string::npos || relative.find('\0') != std::string::npos) {
    throw ApiError(403, "forbidden", "path " + urlPath.substr(0, 200) + ": not a file of the viewer");
  }
  for (const fs::path& segment : fs::path(relative)) {
    const std::string name = segment.string();
    if (name.empty() || name.front() == '.' || name == "/") throw ApiError(403, "forbidden", "path " + urlPath.substr(0, 200) + ": not a file of the viewer");
  }
  return relative;
}

}  // namespace

StaticFile readStaticFile(const fs::path& directory, const std::string& urlPath) {
  if (directory.empty()) {
    throw ApiError(404, "not_found", "this server has no viewer directory (lang2manip serve --viewer DIR; the build puts it in build/viewer/dist)");
  }
  const fs::path relative = relativePath(urlPath);
  std::error_code error;
  const fs::path root = fs::canonical(directory, error);
  const fs::path file = fs::weakly_canonical(root / relative, error);
  const std::string rootText = root.string() + "/";
  if (error || file.string().rfind(rootText, 0) != 0) throw ApiError(403, "forbidden", "path " + urlPath.substr(0, 200) + ": outside the viewer's directory");
  if (!fs::is_regular_file(file, error)) throw ApiError(404, "not_found", "no file " + urlPath.substr(0, 200) + " in the viewer");
  if (fs::file_size(file, error) > kMaxStaticBytes) throw ApiError(403, "forbidden", "file " + urlPath.substr(0, 200) + " is too large to serve");
  std::ifstream in(file, std::ios::binary);
  std::ostringstream content;
  content << in.rdbuf();
  if (!in && !in.eof()) throw ApiError(500, "internal_error", "cannot read " + urlPath.substr(0, 200));
  return {content.str(), contentTypeOf(file)};
}

}  // namespace lang2manip
