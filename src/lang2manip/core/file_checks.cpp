#include "lang2manip/core/file_checks.hpp"

#include "lang2manip/core/error.hpp"

namespace lang2manip {

std::string notRegularFileReason(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (status.type() == fs::file_type::not_found) return "does not exist";
  if (error) return "cannot be inspected (" + error.message() + ")";
  switch (status.type()) {
    case fs::file_type::regular: return {};
    case fs::file_type::directory: return "is a directory, not a file";
    case fs::file_type::character: return "is a character device, not a regular file";
    case fs::file_type::block: return "is a block device, not a regular file";
    case fs::file_type::fifo: return "is a FIFO, not a regular file";
    case fs::file_type::socket: return "is a socket, not a regular file";
    default: return "is not a regular file";
  }
}

void requireRegularFile(const std::filesystem::path& path, std::string_view what) {
  const std::string reason = notRegularFileReason(path);
  if (!reason.empty()) {
    throw InputError(SourceLocation{path.string(), 0}, std::string(what) + " " + reason);
  }
}

std::string triedCandidates(const std::vector<std::filesystem::path>& candidates) {
  std::string tried;
  for (const std::filesystem::path& candidate : candidates) {
    const std::string reason = notRegularFileReason(candidate);
    tried += (tried.empty() ? "tried: " : ", ") + candidate.lexically_normal().string() + " (" +
             (reason.empty() ? "a regular file" : reason) + ")";
  }
  return tried;
}

}  // namespace lang2manip
