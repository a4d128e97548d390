#pragma once
/// @file Outputs written so that a reader never sees a mix of two runs or a half-written file,
/// and never through a symbolic link planted where an output goes: single files are written
/// beside their place and renamed over it; directories of outputs are staged beside their place
/// and swapped in whole, the earlier set kept as `<DIR>.previous`.

#include <filesystem>
#include <string>
#include <string_view>

namespace lang2manip {

/// Writes `bytes` to `path` in one step: into a new file beside it (created exclusively, never
/// through a symbolic link), then renamed over `path`, so a reader sees the old file or the
/// whole new one. A directory, FIFO or device at `path` is refused; a symbolic link there is
/// replaced, not followed. Throws InputError "<what> <path>: <reason>".
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes, std::string_view what);

/// Name of the file every output directory of lang2manip holds, so that a later command knows
/// the directory is one of its own and may replace it.
inline constexpr std::string_view kOutputMarkerName = ".lang2manip-output";

/// Suffix of the directory where the set an output directory held before is kept.
inline constexpr std::string_view kPreviousOutputSuffix = ".previous";

/// A directory of outputs written as one set. Files go into a fresh directory beside the target
/// (`.<name>.partial-<pid>-XXXXXX`); commit() swaps it into place, so the target holds either the
/// earlier set or the whole new one, also when the process is interrupted. The earlier set is
/// kept as `<target>.previous` (an earlier `.previous` of lang2manip's is removed). A non-empty
/// target that lang2manip did not write is refused unless `force` (it is then kept as the
/// `.previous`); the current directory, a directory holding it and a git checkout are always
/// refused. An uncommitted set is removed when the object is destroyed; sets left by a process
/// that died are removed by the next one writing beside them.
class OutputDirectory {
 public:
  /// Checks `target` and creates the staging directory. `what` names the option in messages
  /// ("run: --out"). Throws InputError naming the path and what to do.
  OutputDirectory(const std::filesystem::path& target, std::string what, bool force = false);
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  /// Writes the file `name` (a plain file name, no directory part) into the set.
  void write(std::string_view name, std::string_view bytes);
  /// Where the set is staged until commit(), for writers that need a directory of their own.
  [[nodiscard]] const std::filesystem::path& stagingDirectory() const { return staging_; }
  /// The directory the set goes to (symbolic links in it resolved).
  [[nodiscard]] const std::filesystem::path& target() const { return target_; }
  /// `<target>.previous`.
  [[nodiscard]] std::filesystem::path previousDirectory() const;
  /// Moves the set into place. Throws InputError when it cannot; the target is then unchanged.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path staging_;
  std::string what_;
  bool committed_ = false;
};

}  // namespace lang2manip
