#pragma once
/// @file Where tests find their data: the project's own tests/data, and ../shared/data when
/// present (tests that need it call GTEST_SKIP() with a message when it is absent).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace lang2manip::test {

/// tests/data in the source tree.
std::filesystem::path testDataDirectory();

/// ../shared/data beside the checkout, or nullopt when it is absent.
std::optional<std::filesystem::path> sharedDataDirectory();

/// The whole content of `path` ("" when it cannot be read).
std::string readFileText(const std::filesystem::path& path);

/// The Kautham problems of ../shared/data/kautham (relative to its kautham/ directory) that the
/// model tests check by hand and the planning tests solve; the other problems there must load.
const std::vector<std::string>& handCheckedKauthamProblems();

/// A fresh empty temporary directory for one test (removed by the caller's TempDirectory).
class TempDirectory {
 public:
  TempDirectory();
  ~TempDirectory();
  TempDirectory(const TempDirectory&) = delete;
  TempDirectory& operator=(const TempDirectory&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace lang2manip::test

/// Skips the current test when ../shared/data is absent, and binds its path to `variable`.
#define LANG2MANIP_REQUIRE_SHARED_DATA(variable)                                  \
  const auto variable##Optional = ::lang2manip::test::sharedDataDirectory();      \
  if (!variable##Optional) GTEST_SKIP() << "../shared/data is absent: skipped";   \
  const std::filesystem::path variable = *variable##Optional
