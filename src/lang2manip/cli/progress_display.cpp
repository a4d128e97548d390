#include "lang2manip/cli/progress_display.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace lang2manip {
namespace {

constexpr auto kTerminalRedraw = std::chrono::milliseconds(100);
constexpr auto kPlainLineEvery = std::chrono::seconds(10);
constexpr std::size_t kBarWidth = 24;

std::string durationText(double seconds) {
  char text[32];
  if (seconds < 90.0) {
    std::snprintf(text, sizeof text, "%.0f s", std::ceil(seconds));
  } else if (seconds < 5400.0) {
    std::snprintf(text, sizeof text, "%.0f min", std::ceil(seconds / 60.0));
  } else {
    std::snprintf(text, sizeof text, "%.1f h", seconds / 3600.0);
  }
  return text;
}

/// `text` cut to one short line.
std::string shortened(const std::string& text) {
  const std::string line = text.substr(0, text.find('\n'));
  return line.size() > 160 ? line.substr(0, 157) + "..." : line;
}

}  // namespace

std::string runPhaseText(const ProgressEvent& event) {
  const std::string step = "step " + std::to_string(event.action + 1);
  const std::string why = event.text.empty() ? "" : " (" + shortened(event.text) + ")";
  switch (event.stage) {
    case ProgressStage::kObserve: return "observing the scene";
    case ProgressStage::kPlannerCall: return "asking the task planner (round " + std::to_string(event.round) + ")";
    case ProgressStage::kPlannerAnswer: return "round " + std::to_string(event.round) + ": " + event.status + why;
    case ProgressStage::kActionStarted: return step + ": " + shortened(event.text);
    case ProgressStage::kActionFinished: return step + ": " + event.status + why;
    case ProgressStage::kVerify: return "checking the goals on the final world";
  }
  return progressStageName(event.stage);
}

ProgressDisplay::ProgressDisplay(std::ostream& stream, std::string what, std::size_t total, std::string unit, bool terminal)
    : stream_(stream), what_(std::move(what)), total_(total), unit_(std::move(unit)), terminal_(terminal) {}

ProgressDisplay::ProgressDisplay(std::string what, std::size_t total, std::string unit)
    : ProgressDisplay(std::cerr, std::move(what), total, std::move(unit), ::isatty(STDERR_FILENO) == 1) {}

ProgressDisplay::~ProgressDisplay() { finish(); }

void ProgressDisplay::advance(std::size_t count) {
  done_ = std::min(total_, done_ + count);
  const Clock::time_point now = Clock::now();
  const std::size_t tenth = total_ == 0 ? 10 : done_ * 10 / total_;
  const bool due = terminal_ ? now - lastShown_ >= kTerminalRedraw : (tenth > lastShownTenth_ || now - lastShown_ >= kPlainLineEvery);
  if (due && done_ < total_) {
    lastShownTenth_ = tenth;
    lastShown_ = now;
    show();
  }
}

void ProgressDisplay::finish() {
  if (finished_) return;
  finished_ = true;
  if (done_ == 0 && !terminal_) return;  // nothing was done: no line
  show();
  if (terminal_) stream_ << '\n';
  stream_.flush();
}

std::string ProgressDisplay::line() const {
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  std::string text = what_ + (terminal_ ? " " : ": ");
  if (terminal_) {
    const std::size_t filled = total_ == 0 ? kBarWidth : done_ * kBarWidth / total_;
    text += "[" + std::string(filled, '#') + std::string(kBarWidth - filled, '.') + "] ";
  }
  text += std::to_string(done_) + "/" + std::to_string(total_) + " " + unit_;
  if (done_ > 0 && elapsed > 0.0) {
    const double rate = static_cast<double>(done_) / elapsed;
    char rateText[32];
    std::snprintf(rateText, sizeof rateText, rate >= 10.0 ? "%.0f/s" : "%.2g/s", rate);
    text += std::string(", ") + rateText;
    if (done_ < total_) text += ", about " + durationText(static_cast<double>(total_ - done_) / rate) + " left";
  }
  return text;
}

void ProgressDisplay::show() {
  if (terminal_) {
    stream_ << '\r' << line() << "\033[K";  // erase what a longer earlier line left
  } else {
    stream_ << line() << '\n';
  }
  stream_.flush();
}

}  // namespace lang2manip
