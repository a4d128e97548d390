#include "lang2manip/core/output_files.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <set>

#include "lang2manip/core/error.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string readText(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

/// Names in `directory`, the marker left out.
std::set<std::string> namesIn(const fs::path& directory) {
  std::set<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory)) {
    const std::string name = entry.path().filename().string();
    if (name != kOutputMarkerName) names.insert(name);
  }
  return names;
}

void writeSet(const fs::path& target, const std::vector<std::pair<std::string, std::string>>& files, bool force = false) {
  OutputDirectory set(target, "test: --out", force);
  for (const auto& [name, text] : files) set.write(name, text);
  set.commit();
}

class OutputFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("lang2manip_output_files_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    out_ = root_ / "out";
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
  fs::path out_;
};

TEST_F(OutputFilesTest, ASetReplacesTheEarlierOneWholeAndKeepsItAsPrevious) {
  writeSet(out_, {{"report.json", "first"}, {"trajectory.json", "old motion"}});
  EXPECT_EQ(namesIn(out_), (std::set<std::string>{"report.json", "trajectory.json"}));
  writeSet(out_, {{"report.json", "second"}});
  EXPECT_EQ(namesIn(out_), std::set<std::string>{"report.json"}) << "no file of the earlier set is mixed in";
  EXPECT_EQ(readText(out_ / "report.json"), "second");
  EXPECT_EQ(readText(root_ / "out.previous" / "trajectory.json"), "old motion");
  writeSet(out_, {{"report.json", "third"}});
  EXPECT_EQ(readText(root_ / "out.previous" / "report.json"), "second");
  EXPECT_EQ(namesIn(root_), (std::set<std::string>{"out", "out.previous"})) << "nothing staged is left beside";
}

TEST_F(OutputFilesTest, ASetNotCommittedLeavesTheTargetAsItWas) {
  writeSet(out_, {{"report.json", "first"}});
  {
    OutputDirectory set(out_, "test: --out");
    set.write("report.json", "unfinished");
  }
  EXPECT_EQ(readText(out_ / "report.json"), "first");
  EXPECT_EQ(namesIn(root_), std::set<std::string>{"out"});
}

TEST_F(OutputFilesTest, AProcessKilledWhileWritingLeavesTheEarlierSetAndItsLeftoversAreRemovedLater) {
  writeSet(out_, {{"report.json", "first"}});
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    OutputDirectory set(out_, "test: --out");
    set.write("report.json", "interrupted");
    ::kill(::getpid(), SIGKILL);
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(readText(out_ / "report.json"), "first");
  EXPECT_EQ(namesIn(root_).size(), 2u) << "the killed process's staging directory is still there";
  writeSet(out_, {{"report.json", "second"}});
  EXPECT_EQ(namesIn(root_), (std::set<std::string>{"out", "out.previous"}));
}

TEST_F(OutputFilesTest, ADirectoryLang2manipDidNotWriteIsRefusedUnlessForcedAndThenKept) {
  fs::create_directories(out_);
  std::ofstream(out_ / "thesis.tex") << "years of work";
  try {
    writeSet(out_, {{"report.json", "x"}});
    FAIL() << "a directory of someone else's files was replaced";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("holds files lang2manip did not write"));
    EXPECT_THAT(error.what(), HasSubstr("--force"));
  }
  EXPECT_EQ(readText(out_ / "thesis.tex"), "years of work");
  writeSet(out_, {{"report.json", "x"}}, /*force=*/true);
  EXPECT_EQ(readText(root_ / "out.previous" / "thesis.tex"), "years of work");
  EXPECT_THAT([&] { writeSet(out_, {{"report.json", "y"}}); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("out.previous: holds files lang2manip did not write")));
  EXPECT_EQ(readText(root_ / "out.previous" / "thesis.tex"), "years of work");
}

TEST_F(OutputFilesTest, TheCurrentDirectoryItsParentsAFileAndACheckoutAreRefused) {
  const fs::path here = fs::current_path();
  fs::current_path(root_);
  EXPECT_THAT([&] { OutputDirectory(".", "test: --out"); }, ::testing::ThrowsMessage<InputError>(HasSubstr("is the current directory")));
  EXPECT_THAT([&] { OutputDirectory("..", "test: --out"); }, ::testing::ThrowsMessage<InputError>(HasSubstr("is the current directory")));
  fs::current_path(here);
  std::ofstream(root_ / "file") << "x";
  EXPECT_THAT([&] { OutputDirectory(root_ / "file", "test: --out"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("file: exists and is not a directory")));
  fs::create_directories(root_ / "checkout" / ".git");
  EXPECT_THAT([&] { OutputDirectory(root_ / "checkout", "test: --out", true); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("is a git checkout")));
  EXPECT_THAT([&] { OutputDirectory("", "test: --out"); }, ::testing::ThrowsMessage<InputError>(HasSubstr("must name a directory")));
}

TEST_F(OutputFilesTest, ALinkPlantedWhereAnOutputGoesIsNeverWrittenThrough) {
  writeSet(out_, {{"report.json", "first"}});
  std::ofstream(root_ / "elsewhere") << "precious";
  fs::create_symlink(root_ / "elsewhere", out_ / "trajectory.json");
  writeSet(out_, {{"report.json", "second"}, {"trajectory.json", "motion"}});
  EXPECT_EQ(readText(root_ / "elsewhere"), "precious");
  EXPECT_EQ(fs::symlink_status(out_ / "trajectory.json").type(), fs::file_type::regular);
  EXPECT_EQ(readText(out_ / "trajectory.json"), "motion");
  OutputDirectory set(out_, "test: --out");
  EXPECT_THAT([&] { set.write("../escape", "x"); }, ::testing::ThrowsMessage<InputError>(HasSubstr("cannot write")));
}

TEST_F(OutputFilesTest, TheTargetThroughALinkIsTheLinkedDirectory) {
  fs::create_directories(root_ / "real");
  fs::create_directory_symlink(root_ / "real", root_ / "link");
  writeSet(root_ / "link", {{"report.json", "x"}});
  EXPECT_EQ(fs::symlink_status(root_ / "link").type(), fs::file_type::symlink);
  EXPECT_EQ(readText(root_ / "real" / "report.json"), "x");
}

TEST_F(OutputFilesTest, ASingleFileIsReplacedWholeAndNeverThroughALink) {
  const fs::path file = root_ / "result.json";
  writeFileAtomically(file, "one", "test: --out");
  writeFileAtomically(file, "two", "test: --out");
  EXPECT_EQ(readText(file), "two");
  std::ofstream(root_ / "elsewhere") << "precious";
  fs::create_symlink(root_ / "elsewhere", root_ / "log");
  writeFileAtomically(root_ / "log", "log", "test: --log");
  EXPECT_EQ(readText(root_ / "elsewhere"), "precious");
  EXPECT_EQ(readText(root_ / "log"), "log");
  EXPECT_EQ(namesIn(root_), (std::set<std::string>{"elsewhere", "log", "result.json"}));
  ASSERT_EQ(::mkfifo((root_ / "pipe").c_str(), 0600), 0);
  EXPECT_THAT([&] { writeFileAtomically(root_ / "pipe", "x", "test: --log"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("pipe: is a FIFO")));
  EXPECT_THAT([&] { writeFileAtomically(root_, "x", "test: --log"); }, ::testing::ThrowsMessage<InputError>(HasSubstr("is a directory")));
  EXPECT_THAT([&] { writeFileAtomically(root_ / "missing" / "x.json", "x", "test: --out"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("its directory " + (root_ / "missing").string() + " does not exist")));
}

TEST_F(OutputFilesTest, AParentThatCannotBeWrittenIsAClearError) {
  // /proc refuses new entries to every user, root included.
  EXPECT_THAT([&] { OutputDirectory("/proc/lang2manip-out", "test: --out"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("test: --out /proc/lang2manip-out: cannot create a directory beside it")));
  EXPECT_THAT([&] { writeFileAtomically("/proc/lang2manip.json", "x", "test: --out"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("test: --out /proc/lang2manip.json: cannot create a file beside it")));
}

}  // namespace
}  // namespace lang2manip
