// Progress of long commands on stderr: plain lines at every tenth of the work when not on a
// terminal, one line redrawn in place on one, and a run's phases in words.
#include "lang2manip/cli/progress_display.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "cli/cli_run.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;

TEST(ProgressDisplay, PlainLinesAtEveryTenthAndAtTheEnd) {
  std::ostringstream stream;
  {
    ProgressDisplay progress(stream, "bench task", 40, "trials", false);
    for (int i = 0; i < 40; ++i) progress.advance();
  }
  const std::string text = stream.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 10) << text;  // 4/40 ... 36/40 and 40/40
  EXPECT_THAT(text, HasSubstr("bench task: 4/40 trials, "));
  EXPECT_THAT(text, HasSubstr("left\n"));
  EXPECT_THAT(text, HasSubstr("bench task: 40/40 trials, "));
  EXPECT_EQ(text.find('\r'), std::string::npos) << "no redrawing in a log";
  std::ostringstream nothing;
  { ProgressDisplay idle(nothing, "bench mbm", 5, "problems", false); }
  EXPECT_EQ(nothing.str(), "") << "no line when nothing was done";
}

TEST(ProgressDisplay, OnATerminalOneLineIsRedrawnWithABar) {
  std::ostringstream stream;
  ProgressDisplay progress(stream, "render", 4, "pictures", true);
  for (int i = 0; i < 4; ++i) progress.advance();
  progress.finish();
  progress.finish();
  const std::string text = stream.str();
  EXPECT_THAT(text, HasSubstr("\rrender [########################] 4/4 pictures"));
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << "one line, ended once";
}

TEST(ProgressDisplay, RunPhasesAreWordsAndTheRunCommandShowsThemOnStderr) {
  EXPECT_EQ(runPhaseText({ProgressStage::kPlannerCall, 2, -1, "", ""}), "asking the task planner (round 2)");
  EXPECT_EQ(runPhaseText({ProgressStage::kActionFinished, 0, 1, "failed", "no grasp\nmore"}), "step 2: failed (no grasp)");
  const TempDirectory directory;
  const RunResult result = run("run --task \"pick up the marker\" --out " + (directory.path() / "out").string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const std::size_t asked = result.output.find("run: asking the task planner (round 1)");
  const std::size_t picked = result.output.find("run: step 1: pick marker");
  const std::size_t summary = result.output.find("SUCCESS");
  ASSERT_NE(asked, std::string::npos) << result.output;
  EXPECT_LT(asked, picked);
  EXPECT_LT(picked, summary);
}

}  // namespace
}  // namespace lang2manip::test
