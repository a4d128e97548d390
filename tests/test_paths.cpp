#include "test_paths.hpp"

#include <atomic>
#include <random>
#include <string>
#include <unistd.h>

namespace lang2manip::test {

std::filesystem::path testDataDirectory() { return LANG2MANIP_TEST_DATA_DIR; }

std::optional<std::filesystem::path> sharedDataDirectory() {
  const std::filesystem::path data = std::filesystem::path(LANG2MANIP_SHARED_DIR) / "data";
  if (std::filesystem::is_directory(data)) return std::filesystem::canonical(data);
  return std::nullopt;
}

TempDirectory::TempDirectory() {
  static std::atomic<int> counter{0};
  path_ = std::filesystem::temp_directory_path() /
          ("lang2manip_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TempDirectory::~TempDirectory() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

}  // namespace lang2manip::test
