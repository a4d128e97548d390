#include "lang2manip/planning/phase_integrator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "lang2manip/core/error.hpp"
#include "lang2manip/planning/switching_points.hpp"
#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip::totg {
namespace {

constexpr int kCrossingBisections = 40;
// A step whose corrected acceleration is outside the range at its end by more than this
// (relative) is halved, at most kMaxHalvings times.
constexpr double kRangeSlack = 1e-9;
constexpr int kMaxHalvings = 10;
// Relative slack of the speed above the limit curve in the middle of a step.
constexpr double kChordSlack = 1e-5;
// A step ending above the limit curve is halved this many times before it counts as crossing
// it (a long step can pass below a corner of the curve and end above it just after).
constexpr int kMaxCrossingHalvings = 4;

// v^2 along the constant-acceleration step from `a` to `b` (linear in s), at s.
double stepSquared(const PhasePoint& a, const PhasePoint& b, double s) {
  if (b.s == a.s) return b.v * b.v;
  return a.v * a.v + (b.v * b.v - a.v * a.v) * (s - a.s) / (b.s - a.s);
}

}  // namespace

PhaseIntegrator::PhaseIntegrator(const PhasePlane& plane, double timeStep, std::size_t maxSteps)
    : plane_(plane), timeStep_(timeStep), maxSteps_(maxSteps) {}

const std::vector<PhasePoint>& PhaseIntegrator::integratePiece(std::size_t first, std::size_t last) {
  first_ = first;
  last_ = last;
  pieceEnd_ = plane_.segmentEnd(last);
  forward_.clear();
  forward_.push_back({plane_.segmentStart(first), 0.0});
  SwitchingPointFinder finder(plane_, first, last);
  std::size_t k = first;
  double firstAcceleration = std::numeric_limits<double>::infinity();
  // Each round uses up one switching point, so this ends.
  while (!integrateForward(k, firstAcceleration)) {
    // A switching point inside the step that crossed the curve is where the trajectory touches
    // it (the step may have passed below a corner of the curve and crossed just after it).
    const std::optional<SwitchingPoint> next = finder.next(crossingStepStart_);
    if (!next) break;
    cutForwardAt(next->s);
    integrateBackward({next->s, next->v}, next->beforeAcceleration);
    k = std::clamp(plane_.path().segmentIndex(next->s), first_, last_);
    firstAcceleration = next->afterAcceleration;
  }
  integrateBackward({pieceEnd_, 0.0}, plane_.accelerationRange(last, pieceEnd_, 0.0).lower);
  return forward_;
}

double PhaseIntegrator::stepTime(std::size_t k, double v) const {
  const double dt = timeStep_ * stepScale_;
  if (!plane_.isArc(k) || v * dt <= kMaxTurnPerStep * plane_.radius(k)) return dt;
  return kMaxTurnPerStep * plane_.radius(k) / v;
}

PhasePoint PhaseIntegrator::step(std::size_t k, const PhasePoint& from, double acceleration, bool forward,
                                 double scale) const {
  if (!plane_.isArc(k)) return lineStep(k, from, acceleration, forward);
  const double dt = stepTime(k, from.v) * scale;
  const double direction = forward ? 1.0 : -1.0;
  PhasePoint to;
  to.v = std::max(0.0, from.v + direction * dt * acceleration);
  to.s = from.s + direction * 0.5 * dt * (from.v + to.v);
  // Stop at the segment's end (start, backward), with the speed of the same acceleration.
  const double limit = forward ? plane_.segmentEnd(k) : plane_.segmentStart(k);
  if (direction * (to.s - limit) > 0.0) {
    to.s = limit;
    to.v = std::sqrt(std::max(0.0, from.v * from.v + 2.0 * acceleration * (limit - from.s)));
  }
  return to;
}

// On a line the limits are constant: one step to where the speed reaches the line's limit
// (then one step along it), or to the line's end, exactly.
PhasePoint PhaseIntegrator::lineStep(std::size_t k, const PhasePoint& from, double acceleration,
                                     bool forward) const {
  const double limit = plane_.velocityCurve(k, from.s).value;
  const double end = forward ? plane_.segmentEnd(k) : plane_.segmentStart(k);
  const double direction = forward ? 1.0 : -1.0;
  const double length = std::abs(end - from.s);
  // v^2 grows by 2 gain per unit of distance travelled (backward: a < 0 makes v grow).
  const double gain = direction * acceleration;
  if (gain >= 0.0 && from.v >= limit) return {end, limit};
  if (gain > 0.0) {
    const double reach = (limit * limit - from.v * from.v) / (2.0 * gain);
    if (reach < length) return {from.s + direction * reach, limit};
  } else if (gain < 0.0) {
    const double reach = from.v * from.v / (-2.0 * gain);
    if (reach < length) return {from.s + direction * reach, 0.0};
  } else {
    return {end, from.v};
  }
  return {end, std::sqrt(std::max(0.0, from.v * from.v + 2.0 * gain * length))};
}

void PhaseIntegrator::countStep() {
  stepScale_ = std::min(1.0, 2.0 * stepScale_);
  if (++steps_ <= maxSteps_) return;
  throw InputError("time-optimal parameterization: more than " + std::to_string(maxSteps_) +
                   " integration steps (a very long trajectory for the time step " +
                   numberText(timeStep_) + " s); use a larger time step");
}

// From forward_.back() with the maximum path acceleration (the first step with
// firstAcceleration), following the velocity-limit curve where the trajectory can brake as fast
// as the curve falls. True at the piece's end; false after crossing the limit curve, with
// forward_.back() the last point below it.
bool PhaseIntegrator::integrateForward(std::size_t k, double firstAcceleration) {
  PhasePoint from = forward_.back();
  // Leaving a switching point, where the acceleration range is one value changing along the
  // curve, with short steps (a constant acceleration per step misses the change).
  stepScale_ = std::isfinite(firstAcceleration) ? 0.5 * kFirstStepScale : 1.0;
  while (k < last_ && from.s >= plane_.segmentEnd(k)) ++k;
  PointLimits here = plane_.limitsAt(k, from.s, from.v);
  // At a switching point the range is the one-sided limit on the wrong side where the curve has
  // a corner: its own after-acceleration is used as given.
  double acceleration = std::isfinite(firstAcceleration) ? firstAcceleration : here.range.upper;
  while (true) {
    countStep();
    PointLimits there;
    const PhasePoint to = forwardStep(k, from, here, acceleration, there);
    forward_.push_back(to);
    if (to.s >= pieceEnd_) return true;
    const std::size_t next = k < last_ && to.s >= plane_.segmentEnd(k) ? k + 1 : k;
    const bool aboveInSegment = there.above;
    if (next != k) there = plane_.limitsAt(next, to.s, to.v);
    if (aboveInSegment || there.above) {
      refineCrossing(k, from);
      return false;
    }
    from = to;
    here = there;
    k = next;
    acceleration = here.range.upper;
  }
}

// One forward step in segment k, with the limits at its end into `there`. Follows the
// velocity-limit curve when the trajectory can brake as fast as it falls; otherwise the
// acceleration is also kept within the range at the step's end. A step that would end above the
// limit curve, or whose acceleration is outside the range at its end or (near the curve) in its
// middle, is halved.
PhasePoint PhaseIntegrator::forwardStep(std::size_t k, const PhasePoint& from, const PointLimits& here,
                                        double acceleration, PointLimits& there) const {
  double scale = 1.0;
  for (int halving = 0;; ++halving) {
    PhasePoint to = step(k, from, acceleration, true, scale);
    there = plane_.limitsAt(k, to.s, to.v);
    if (!plane_.isArc(k)) return to;  // lineStep() stops at the speed limit
    if (to.v > there.velocity.value && canFollowVelocityCurve(k, from, here)) {
      to.v = there.velocity.value;
      there = plane_.limitsAt(k, to.s, to.v);
    } else if (there.above) {
      if (halving >= kMaxCrossingHalvings) return to;
      scale *= 0.5;
      continue;
    } else if (there.range.upper < acceleration) {
      to = step(k, from, there.range.upper, true, scale);
      there = plane_.limitsAt(k, to.s, to.v);
    }
    if (fitsAlong(k, from, here, to, there)) return to;
    if (halving == kMaxHalvings) {
      if (to.s > from.s) return to;
      to = step(k, from, acceleration, true, scale);  // progress rather than a standstill
      there = plane_.limitsAt(k, to.s, to.v);
      return to;
    }
    scale *= 0.5;
  }
}

bool PhaseIntegrator::fitsAlong(std::size_t k, const PhasePoint& from, const PointLimits& here,
                                const PhasePoint& to, const PointLimits& there) const {
  const PhasePoint& low = from.s < to.s ? from : to;
  const PhasePoint& high = from.s < to.s ? to : from;
  if (high.s <= low.s) return false;  // no progress: a shorter step makes some
  const double used = (high.v * high.v - low.v * low.v) / (2.0 * (high.s - low.s));
  const double slack = kRangeSlack * (1.0 + std::abs(used));
  if (there.above || used > there.range.upper + slack || used < there.range.lower - slack) return false;
  // Where the velocity-limit curve squared (W = V^2, W' = 2 V V') is convex, its chord is above
  // it by up to (W'(high) - W'(low)) ds / 8: the step must leave that much room below it.
  const CurvePoint& lowCurve = from.s < to.s ? here.velocity : there.velocity;
  const CurvePoint& highCurve = from.s < to.s ? there.velocity : here.velocity;
  const double room = std::min(lowCurve.value * lowCurve.value - low.v * low.v,
                               highCurve.value * highCurve.value - high.v * high.v);
  const double bend = 2.0 * (highCurve.value * highCurve.slope - lowCurve.value * lowCurve.slope) *
                      (high.s - low.s) / 8.0;
  if (bend > room + 2.0 * kChordSlack * highCurve.value * highCurve.value) return false;
  const double width = there.range.upper - there.range.lower;
  const bool nearCurve = to.v > 0.9 * there.velocity.value ||
                         width < 0.2 * (std::abs(there.range.upper) + std::abs(there.range.lower));
  if (!nearCurve) return true;
  // v^2 is linear in s along the step: in its middle it must stay below a convex stretch of the
  // limit curve, within the range there.
  const double middleSpeed = std::sqrt(0.5 * (low.v * low.v + high.v * high.v)) / (1.0 + kChordSlack);
  const PointLimits middle = plane_.limitsAt(k, 0.5 * (low.s + high.s), middleSpeed);
  return !middle.above && used <= middle.range.upper + slack && used >= middle.range.lower - slack;
}

bool PhaseIntegrator::canFollowVelocityCurve(std::size_t k, const PhasePoint& from,
                                             const PointLimits& here) const {
  if (!plane_.isArc(k)) return true;  // the curve is flat
  const double brake = plane_.accelerationRange(k, from.s, here.velocity.value).lower;
  return brake <= here.velocity.slope * here.velocity.value + 1e-9 * std::abs(brake);
}

// forward_.back() is above the limit curve: moves it back along the last step (from `from`, in
// segment k) to the last point found below the curve by bisection.
void PhaseIntegrator::refineCrossing(std::size_t k, const PhasePoint& from) {
  const PhasePoint to = forward_.back();
  crossingStepStart_ = from.s;
  const auto at = [&](double fraction) {
    const double s = from.s + fraction * (to.s - from.s);
    return PhasePoint{s, std::sqrt(std::max(0.0, stepSquared(from, to, s)))};
  };
  const auto isAbove = [&](const PhasePoint& point) {
    if (plane_.isAboveLimit(k, point.s, point.v)) return true;
    return k < last_ && point.s >= plane_.segmentEnd(k) && plane_.isAboveLimit(k + 1, point.s, point.v);
  };
  double below = 0.0;
  double above = 1.0;
  const double tolerance = 1e-12 * std::max(1.0, std::abs(to.s)) / std::max(to.s - from.s, 1e-300);
  for (int i = 0; i < kCrossingBisections && above - below > tolerance; ++i) {
    const double middle = 0.5 * (below + above);
    (isAbove(at(middle)) ? above : below) = middle;
  }
  forward_.pop_back();
  if (below > 0.0) forward_.push_back(at(below));
}

// Drops the forward trajectory beyond s, ending it at s on its last step.
void PhaseIntegrator::cutForwardAt(double s) {
  if (forward_.back().s < s) return;
  PhasePoint beyond = forward_.back();
  while (forward_.size() > 1 && forward_.back().s >= s) {
    beyond = forward_.back();
    forward_.pop_back();
  }
  forward_.push_back({s, std::sqrt(std::max(0.0, stepSquared(forward_.back(), beyond, s)))});
}

// From `start` backward in time with the minimum path acceleration (the first step with
// firstAcceleration) until it meets forward_, whose part beyond the meeting point it then
// replaces.
void PhaseIntegrator::integrateBackward(const PhasePoint& start, double firstAcceleration) {
  backward_.clear();
  backward_.push_back(start);
  std::size_t k = std::clamp(plane_.path().segmentIndex(start.s), first_, last_);
  while (k > first_ && start.s <= plane_.segmentStart(k)) --k;
  meet_ = forward_.size() - 1;
  stepScale_ = start.v > 0.0 ? 0.5 * kFirstStepScale : 1.0;
  PhasePoint from = start;
  PointLimits here = plane_.limitsAt(k, from.s, from.v);
  double acceleration = firstAcceleration;
  while (true) {
    countStep();
    PhasePoint to = backwardStep(k, from, here, acceleration);
    backward_.push_back(to);
    if (spliceIfMet(from, to)) return;
    const std::size_t next = k > first_ && to.s <= plane_.segmentStart(k) ? k - 1 : k;
    PointLimits there = plane_.limitsAt(next, to.s, to.v);
    if (there.above || (next != k && plane_.isAboveLimit(k, to.s, to.v))) {
      // Only by rounding near a switching point: slide down the limit curve.
      to.v = std::min({to.v, plane_.limitCurve(k, to.s), plane_.limitCurve(next, to.s)});
      backward_.back() = to;
      there = plane_.limitsAt(next, to.s, to.v);
      if (spliceIfMet(from, to)) return;
    }
    from = to;
    here = there;
    k = next;
    acceleration = there.range.lower;
  }
}

// One backward step in segment k, its acceleration also kept within the range at the step's
// end; halved when it would end above the limit curve or when no constant acceleration fits
// along it.
PhasePoint PhaseIntegrator::backwardStep(std::size_t k, const PhasePoint& from, const PointLimits& here,
                                         double acceleration) const {
  double scale = 1.0;
  for (int halving = 0;; ++halving) {
    PhasePoint to = step(k, from, acceleration, false, scale);
    if (!plane_.isArc(k)) return to;
    PointLimits there = plane_.limitsAt(k, to.s, to.v);
    if (there.above) {
      // Nearing the curve (where it meets the forward trajectory, or by rounding) in shorter
      // steps, each then corrected.
      if (halving >= kMaxCrossingHalvings) return to;
      scale *= 0.5;
      continue;
    }
    if (there.range.lower > acceleration) {
      to = step(k, from, there.range.lower, false, scale);
      there = plane_.limitsAt(k, to.s, to.v);
    }
    if (fitsAlong(k, from, here, to, there)) return to;
    if (halving == kMaxHalvings) return to.s < from.s ? to : step(k, from, acceleration, false, scale);
    scale *= 0.5;
  }
}

double PhaseIntegrator::forwardSquared(double s) const {
  std::size_t i = meet_;
  while (i + 1 < forward_.size() && forward_[i + 1].s <= s) ++i;
  if (i + 1 >= forward_.size()) return forward_[i].v * forward_[i].v;
  return stepSquared(forward_[i], forward_[i + 1], s);
}

// The backward step from `from` to `to` (to.s < from.s): when it reaches forward_ (v^2 of the
// backward curve >= that of the forward one, both linear in s between their points), splices.
bool PhaseIntegrator::spliceIfMet(const PhasePoint& from, const PhasePoint& to) {
  const double forwardEnd = forward_.back().s;
  if (to.s > forwardEnd) return false;
  while (meet_ > 0 && forward_[meet_].s > to.s) --meet_;
  const double leftD = to.v * to.v - forwardSquared(to.s);
  if (leftD < 0.0) return false;
  // The meeting point closest to `from`: walk the forward points inside the step from the right
  // (where d = B^2 - F^2 < 0) to the first with d >= 0.
  const double right = std::min(from.s, forwardEnd);
  double rightS = right;
  double rightD = stepSquared(to, from, right) - forwardSquared(right);
  double leftS = to.s;
  double meetLeftD = leftD;
  std::size_t i = meet_ + 1;
  while (i < forward_.size() && forward_[i].s < right) ++i;
  while (--i > meet_ && rightD < 0.0) {
    const double d = stepSquared(to, from, forward_[i].s) - forward_[i].v * forward_[i].v;
    if (d >= 0.0) {
      leftS = forward_[i].s;
      meetLeftD = d;
      break;
    }
    rightS = forward_[i].s;
    rightD = d;
  }
  const double meetS = rightD >= 0.0 ? rightS : leftS + (rightS - leftS) * meetLeftD / (meetLeftD - rightD);
  const double meetV = std::sqrt(std::max(0.0, forwardSquared(meetS)));
  while (!forward_.empty() && forward_.back().s >= meetS) forward_.pop_back();
  forward_.push_back({meetS, meetV});
  for (auto point = backward_.rbegin(); point != backward_.rend(); ++point) {
    if (point->s > meetS) forward_.push_back(*point);
  }
  return true;
}

}  // namespace lang2manip::totg
