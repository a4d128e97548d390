#include "lang2manip/core/file_checks.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>

#include "lang2manip/core/error.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

/// A fresh directory under the system temporary directory, removed at the end of the test.
class FileChecksTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() / ("lang2manip_file_checks_" + std::to_string(::getpid()));
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }
  fs::path directory_;
};

TEST_F(FileChecksTest, SaysWhatAPathNamesWhenItIsNotARegularFile) {
  std::ofstream(directory_ / "file.txt") << "x";
  EXPECT_EQ(notRegularFileReason(directory_ / "file.txt"), "");
  EXPECT_EQ(notRegularFileReason(directory_ / "missing.txt"), "does not exist");
  EXPECT_EQ(notRegularFileReason(directory_), "is a directory, not a file");
  EXPECT_EQ(notRegularFileReason("/dev/zero"), "is a character device, not a regular file");
  ASSERT_EQ(::mkfifo((directory_ / "pipe").c_str(), 0600), 0);
  EXPECT_EQ(notRegularFileReason(directory_ / "pipe"), "is a FIFO, not a regular file");
  fs::create_symlink(directory_ / "file.txt", directory_ / "link");
  EXPECT_EQ(notRegularFileReason(directory_ / "link"), "");
  fs::create_symlink(directory_ / "missing.txt", directory_ / "dangling");
  EXPECT_EQ(notRegularFileReason(directory_ / "dangling"), "does not exist");
}

TEST_F(FileChecksTest, RequireRegularFileNamesThePathAndWhatItIs) {
  try {
    requireRegularFile(directory_, "URDF file");
    FAIL() << "a directory was accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), directory_.string() + ": URDF file is a directory, not a file");
  }
  std::ofstream(directory_ / "file.txt") << "x";
  EXPECT_NO_THROW(requireRegularFile(directory_ / "file.txt", "file"));
}

TEST_F(FileChecksTest, TriedCandidatesListsEachWithItsReason) {
  std::ofstream(directory_ / "file.txt") << "x";
  const std::string tried = triedCandidates({directory_ / "a" / ".." / "missing.stl", "/dev/zero", directory_});
  EXPECT_THAT(tried, HasSubstr("tried: " + (directory_ / "missing.stl").string() + " (does not exist)"));
  EXPECT_THAT(tried, HasSubstr(", /dev/zero (is a character device, not a regular file)"));
  EXPECT_THAT(tried, HasSubstr(directory_.string() + " (is a directory, not a file)"));
}

}  // namespace
}  // namespace lang2manip
