#include "lang2manip/core/output_files.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <system_error>
#include <vector>

#include "lang2manip/core/error.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;

std::string errnoText(int code) { return std::generic_category().message(code); }

/// Writes all of `bytes` to `fd` and closes it; the errno of the first failure, 0 when none.
int writeAllAndClose(int fd, std::string_view bytes) {
  int failure = 0;
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t written = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (written < 0) {
      if (errno == EINTR) continue;
      failure = errno;
      break;
    }
    done += static_cast<std::size_t>(written);
  }
  if (::close(fd) != 0 && failure == 0) failure = errno;
  return failure;
}

/// "is a directory", "is a FIFO", ...: why an output may not replace what is at `path`; empty
/// when nothing is there or a regular file or symbolic link is (both are replaced by a rename).
std::string notReplaceableReason(const fs::path& path) {
  std::error_code error;
  const fs::file_status status = fs::symlink_status(path, error);
  switch (status.type()) {
    case fs::file_type::not_found:
    case fs::file_type::regular:
    case fs::file_type::symlink:
      return {};
    case fs::file_type::directory:
      return "is a directory";
    case fs::file_type::fifo:
      return "is a FIFO";
    case fs::file_type::character:
    case fs::file_type::block:
      return "is a device";
    case fs::file_type::socket:
      return "is a socket";
    default:
      return error ? error.message() : "is not a regular file";
  }
}

bool isEmptyDirectory(const fs::path& path) {
  std::error_code error;
  return fs::is_directory(path, error) && fs::is_empty(path, error) && !error;
}

/// True when lang2manip wrote `directory` (it holds the marker) or it is empty.
bool isOursOrEmpty(const fs::path& directory) {
  std::error_code error;
  return isEmptyDirectory(directory) ||
         fs::is_regular_file(fs::symlink_status(directory / kOutputMarkerName, error));
}

/// True when `inner` is `outer` or lies inside it (both absolute and canonical).
bool isWithin(const fs::path& inner, const fs::path& outer) {
  auto innerPart = inner.begin();
  for (const fs::path& part : outer) {
    if (part.empty()) continue;
    if (innerPart == inner.end() || *innerPart != part) return false;
    ++innerPart;
  }
  return true;
}

std::string partialPrefix(const fs::path& target) { return "." + target.filename().string() + ".partial-"; }

/// Removes staging directories beside `target` left by processes that no longer run.
void removeAbandonedSets(const fs::path& target) {
  const std::string prefix = partialPrefix(target);
  std::error_code error;
  std::vector<fs::path> abandoned;
  for (const fs::directory_entry& entry : fs::directory_iterator(target.parent_path(), error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    if (pid <= 0 || (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)) {
      if (entry.is_directory(error) && isOursOrEmpty(entry.path())) abandoned.push_back(entry.path());
    }
  }
  for (const fs::path& path : abandoned) fs::remove_all(path, error);
}

/// `path` made absolute with every symbolic link of its existing part resolved.
fs::path resolvedTarget(const fs::path& path, const std::string& what) {
  std::error_code error;
  fs::path resolved = fs::weakly_canonical(fs::absolute(path, error), error);
  if (error) throw InputError(what + " " + path.string() + ": " + error.message());
  if (resolved.filename().empty()) resolved = resolved.parent_path();
  return resolved;
}

}  // namespace

void writeFileAtomically(const fs::path& path, std::string_view bytes, std::string_view what) {
  const std::string context = std::string(what) + " " + path.string() + ": ";
  if (path.filename().empty() || path.filename() == "." || path.filename() == "..") {
    throw InputError(context + "names a directory, not a file");
  }
  if (const std::string reason = notReplaceableReason(path); !reason.empty()) throw InputError(context + reason);
  const fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code error;
  if (!fs::is_directory(parent, error)) throw InputError(context + "its directory " + parent.string() + " does not exist");
  std::string temporary = (parent / (partialPrefix(path) + std::to_string(::getpid()) + "-XXXXXX")).string();
  const int fd = ::mkstemp(temporary.data());
  if (fd < 0) throw InputError(context + "cannot create a file beside it: " + errnoText(errno));
  ::fchmod(fd, 0644);
  if (const int failure = writeAllAndClose(fd, bytes); failure != 0) {
    ::unlink(temporary.c_str());
    throw InputError(context + "cannot write: " + errnoText(failure));
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int failure = errno;
    ::unlink(temporary.c_str());
    throw InputError(context + "cannot replace it: " + errnoText(failure));
  }
}

OutputDirectory::OutputDirectory(const fs::path& target, std::string what, bool force) : what_(std::move(what)) {
  if (target.empty()) throw InputError(what_ + ": must name a directory");
  target_ = resolvedTarget(target, what_);
  const std::string context = what_ + " " + target.string() + ": ";
  std::error_code error;
  const fs::path here = fs::canonical(fs::current_path(error), error);
  if (!error && isWithin(here, target_)) {
    throw InputError(context + "is the current directory or holds it; name a directory of its own for the outputs");
  }
  if (fs::exists(fs::symlink_status(target_, error))) {
    if (!fs::is_directory(target_, error)) throw InputError(context + "exists and is not a directory");
    if (fs::exists(target_ / ".git", error)) throw InputError(context + "is a git checkout; name a directory of its own for the outputs");
    if (!isOursOrEmpty(target_) && !force) {
      throw InputError(context + "holds files lang2manip did not write; name another directory, empty it, or pass --force to keep them in " +
                       previousDirectory().string());
    }
    if (fs::exists(fs::symlink_status(previousDirectory(), error)) && !isOursOrEmpty(previousDirectory())) {
      throw InputError(what_ + " " + previousDirectory().string() +
                       ": holds files lang2manip did not write and the earlier outputs would replace them; remove or rename it");
    }
  }
  fs::create_directories(target_.parent_path(), error);
  if (error) throw InputError(context + "cannot create " + target_.parent_path().string() + ": " + error.message());
  removeAbandonedSets(target_);
  std::string staging = (target_.parent_path() / (partialPrefix(target_) + std::to_string(::getpid()) + "-XXXXXX")).string();
  if (::mkdtemp(staging.data()) == nullptr) {
    throw InputError(context + "cannot create a directory beside it: " + errnoText(errno));
  }
  staging_ = staging;
  ::chmod(staging_.c_str(), 0755);
  write(kOutputMarkerName, "written by lang2manip; the directory is replaced whole by its next output set\n");
}

OutputDirectory::~OutputDirectory() {
  if (committed_ || staging_.empty()) return;
  std::error_code error;
  fs::remove_all(staging_, error);
}

fs::path OutputDirectory::previousDirectory() const {
  return target_.parent_path() / (target_.filename().string() + std::string(kPreviousOutputSuffix));
}

void OutputDirectory::write(std::string_view name, std::string_view bytes) {
  const std::string file(name);
  if (file.empty() || file == "." || file == ".." || file.find('/') != std::string::npos || committed_) {
    throw InputError(what_ + ": cannot write \"" + file + "\" into the output set");
  }
  const fs::path path = staging_ / file;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError(what_ + " " + (target_ / file).string() + ": cannot create: " + errnoText(errno));
  if (const int failure = writeAllAndClose(fd, bytes); failure != 0) {
    throw InputError(what_ + " " + (target_ / file).string() + ": cannot write: " + errnoText(failure));
  }
}

void OutputDirectory::commit() {
  if (committed_) return;
  const std::string context = what_ + " " + target_.string() + ": ";
  if (std::rename(staging_.c_str(), target_.c_str()) == 0) {
    committed_ = true;
    return;
  }
  std::error_code error;
  if (!fs::is_directory(target_, error)) throw InputError(context + "cannot move the outputs into place: " + errnoText(errno));
  const fs::path previous = previousDirectory();
  if (fs::exists(fs::symlink_status(previous, error))) {
    if (!isOursOrEmpty(previous)) throw InputError(what_ + " " + previous.string() + ": holds files lang2manip did not write; remove or rename it");
    fs::remove_all(previous, error);
    if (error) throw InputError(what_ + " " + previous.string() + ": cannot remove the outputs kept there: " + error.message());
  }
  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) == 0) {
    committed_ = true;  // staging_ now holds the earlier set
    if (isEmptyDirectory(staging_)) {
      fs::remove(staging_, error);
    } else if (std::rename(staging_.c_str(), previous.c_str()) != 0) {
      throw InputError(context + "the new outputs are in place, but the earlier ones stay in " + staging_.string() + ": " +
                       errnoText(errno));
    }
    return;
  }
  // A file system without an atomic exchange: a short moment without the target.
  if (std::rename(target_.c_str(), previous.c_str()) != 0) throw InputError(context + "cannot keep the earlier outputs: " + errnoText(errno));
  if (std::rename(staging_.c_str(), target_.c_str()) != 0) {
    const int failure = errno;
    std::rename(previous.c_str(), target_.c_str());
    throw InputError(context + "cannot move the outputs into place: " + errnoText(failure));
  }
  committed_ = true;
}

}  // namespace lang2manip
