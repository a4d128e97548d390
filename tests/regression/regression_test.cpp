// Replays the inputs the fuzzers found (tests/regression/<target>/<file>) through the same code
// as the harness (fuzz/fuzz_inputs.hpp): each must be accepted or rejected with the parser's
// documented error; a crash, another exception or a broken round trip fails.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_inputs.hpp"

namespace lang2manip::fuzz {
namespace {

const std::filesystem::path kRegressionDirectory = LANG2MANIP_REGRESSION_DIR;

std::string fileText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The files of tests/regression/<target>/, sorted (none when the directory is absent).
std::vector<std::filesystem::path> regressionInputs(const std::string& target) {
  std::vector<std::filesystem::path> files;
  const std::filesystem::path directory = kRegressionDirectory / target;
  if (!std::filesystem::is_directory(directory)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

class FuzzRegressionTest : public testing::TestWithParam<FuzzTarget> {};

TEST_P(FuzzRegressionTest, EveryInputIsAcceptedOrRejected) {
  for (const std::filesystem::path& file : regressionInputs(GetParam().name)) {
    SCOPED_TRACE(file.string());
    EXPECT_NO_THROW((void)GetParam().feed(fileText(file)));
  }
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzRegressionTest, testing::ValuesIn(fuzzTargets()),
                         [](const testing::TestParamInfo<FuzzTarget>& target) {
                           return target.param.name;
                         });

// A directory whose name is no target would never be replayed.
TEST(FuzzRegressionDirectories, EachNamesATarget) {
  for (const auto& entry : std::filesystem::directory_iterator(kRegressionDirectory)) {
    if (!entry.is_directory()) continue;
    const std::string name = entry.path().filename().string();
    EXPECT_NO_THROW((void)fuzzTarget(name)) << name << " is not a fuzz target";
  }
}

}  // namespace
}  // namespace lang2manip::fuzz
