#include "lang2manip/core/stop_condition.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {

StopCondition StopCondition::afterSeconds(double seconds) {
  if (!std::isfinite(seconds) || seconds <= 0.0) {
    throw InputError("time budget must be a positive number of seconds, got " +
                     numberText(seconds));
  }
  StopCondition condition;
  condition.deadline_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(seconds));
  return condition;
}

StopCondition StopCondition::onCancel(CancelFlag flag) {
  if (!flag) throw InputError("cancel flag must not be null");
  StopCondition condition;
  condition.flags_.push_back(std::move(flag));
  return condition;
}

StopCondition StopCondition::orElse(const StopCondition& other) const {
  StopCondition combined = *this;
  if (other.deadline_ && (!combined.deadline_ || *other.deadline_ < *combined.deadline_)) {
    combined.deadline_ = other.deadline_;
  }
  combined.flags_.insert(combined.flags_.end(), other.flags_.begin(), other.flags_.end());
  return combined;
}

bool StopCondition::shouldStop() const {
  for (const CancelFlag& flag : flags_) {
    if (flag->load(std::memory_order_relaxed)) return true;
  }
  return deadline_ && Clock::now() >= *deadline_;
}

double StopCondition::secondsLeft() const {
  if (!deadline_) return std::numeric_limits<double>::infinity();
  const double left = std::chrono::duration<double>(*deadline_ - Clock::now()).count();
  return left > 0.0 ? left : 0.0;
}

}  // namespace lang2manip
