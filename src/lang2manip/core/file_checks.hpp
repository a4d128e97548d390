#pragma once
/// @file Checks that a path names a regular file before it is read, with messages that say what
/// the path names instead (a directory, a device, a FIFO that would block a reader forever).

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace lang2manip {

/// Why `path` cannot be read as a regular file: "does not exist", "is a directory, not a file",
/// "is a character device, not a regular file", ...; empty when it is a regular file (symbolic
/// links are followed).
std::string notRegularFileReason(const std::filesystem::path& path);

/// Throws InputError "<path>: <what> <reason>" unless `path` is a regular file.
void requireRegularFile(const std::filesystem::path& path, std::string_view what);

/// "tried: a (does not exist), b (is a directory, not a file)": every candidate a reference was
/// looked for at, with why it was not taken.
std::string triedCandidates(const std::vector<std::filesystem::path>& candidates);

/// Largest text input file read whole (models, problems, scenes, replay files): 256 MiB.
inline constexpr std::uintmax_t kMaxTextFileBytes = std::uintmax_t{256} << 20;

}  // namespace lang2manip
