#pragma once
/// @file One stop condition for IK, planners, grasp search and LLM calls: a deadline, cancel
/// flags, or both. Cheap to copy; checking it is thread-safe.

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <vector>

namespace lang2manip {

/// A shared flag that a caller sets to cancel work in progress.
using CancelFlag = std::shared_ptr<std::atomic<bool>>;

class StopCondition {
 public:
  using Clock = std::chrono::steady_clock;

  /// Never stops by itself.
  static StopCondition never() { return {}; }

  /// Stops once `seconds` have passed from now. Throws InputError unless seconds > 0 and finite.
  static StopCondition afterSeconds(double seconds);

  /// Stops when `flag` is set.
  static StopCondition onCancel(CancelFlag flag);

  /// Stops when either this or `other` would stop.
  [[nodiscard]] StopCondition orElse(const StopCondition& other) const;

  /// True once the deadline has passed or any flag is set.
  [[nodiscard]] bool shouldStop() const;

  /// Seconds until the deadline (infinity when there is none; 0 when passed).
  [[nodiscard]] double secondsLeft() const;

 private:
  std::optional<Clock::time_point> deadline_;
  std::vector<CancelFlag> flags_;
};

/// Seconds of the steady clock since `start`.
inline double secondsSince(StopCondition::Clock::time_point start) {
  return std::chrono::duration<double>(StopCondition::Clock::now() - start).count();
}

}  // namespace lang2manip
