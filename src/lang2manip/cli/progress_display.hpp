#pragma once
/// @file Progress of a command's long work on stderr: on a terminal one line redrawn in place (a
/// bar, the count, the rate and the time left), otherwise a plain line at every tenth of the work
/// and at least every ten seconds, so that logs stay short.

#include <chrono>
#include <cstddef>
#include <iosfwd>
#include <string>

#include "lang2manip/core/progress.hpp"

namespace lang2manip {

/// A run's phase as a line for people: "asking the task planner (round 1)", "step 2: place marker
/// in holder", "step 2: succeeded (...)", "checking the goals on the final world".
std::string runPhaseText(const ProgressEvent& event);

class ProgressDisplay {
 public:
  /// Shows progress through `total` items named `unit` ("problems") of the work `what` ("bench
  /// mbm") on `stream`, redrawn in place when `terminal`.
  ProgressDisplay(std::ostream& stream, std::string what, std::size_t total, std::string unit, bool terminal);
  /// As above on std::cerr, redrawn in place when stderr is a terminal.
  ProgressDisplay(std::string what, std::size_t total, std::string unit);
  /// Ends the line (as finish()).
  ~ProgressDisplay();
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

  /// `count` more items are done.
  void advance(std::size_t count = 1);
  /// Shows the final count (once; later calls do nothing).
  void finish();

  /// "bench mbm: 12/40 problems, 3.2/s, about 9 s left" (the bar is drawn before the count on a
  /// terminal).
  [[nodiscard]] std::string line() const;

 private:
  using Clock = std::chrono::steady_clock;
  void show();

  std::ostream& stream_;
  std::string what_;
  std::size_t total_;
  std::string unit_;
  bool terminal_;
  std::size_t done_ = 0;
  std::size_t lastShownTenth_ = 0;
  Clock::time_point start_ = Clock::now();
  Clock::time_point lastShown_ = start_;
  bool finished_ = false;
};

}  // namespace lang2manip
