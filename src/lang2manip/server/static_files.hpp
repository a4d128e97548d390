#pragma once
/// @file The viewer's static files: only regular files inside one directory, whatever the path
/// says (no "..", no symbolic link out of it).

#include <filesystem>
#include <string>

namespace lang2manip {

struct StaticFile {
  std::string content;
  std::string contentType;
};

/// The file at URL path `urlPath` ("/" is index.html) under `directory`. Throws ApiError 404 when
/// `directory` is empty (no viewer) or the file does not exist, 403 for a path that leaves the
/// directory (a ".." segment, a backslash, a NUL, a hidden segment, or a link resolving outside).
StaticFile readStaticFile(const std::filesystem::path& directory, const std::string& urlPath);

}  // namespace lang2manip
