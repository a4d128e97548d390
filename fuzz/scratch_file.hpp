#pragma once
/// @file Files for parsers that only read files: one directory per process (under $TMPDIR, else
/// /dev/shm, else the system's temporary directory), removed when the process exits normally.

#include <filesystem>
#include <string>
#include <string_view>

namespace lang2manip::fuzz {

/// The process's scratch directory (created on first use).
const std::filesystem::path& scratchDirectory();

/// Writes `content` to `name` in the scratch directory (replacing it) and returns its path.
/// Throws std::runtime_error when it cannot be written.
std::filesystem::path writeScratchFile(const std::string& name, std::string_view content);

}  // namespace lang2manip::fuzz
