#include "lang2manip/planning/switching_points.hpp"

#include <algorithm>
#include <cmath>

namespace lang2manip::totg {
namespace {

// Step of the finite differences of the limit curve, relative to the arc radius.
constexpr double kSlopeStep = 1e-7;
// Relative difference of the two one-sided limit-curve values that counts as a jump.
constexpr double kJump = 1e-9;
constexpr int kMaxBisections = 60;

// The end of the last stretch of (below, above) where f > 0, given f(below) > 0 >= f(above): the
// point on the f <= 0 side of the change, within `tolerance`, by regula falsi (Illinois).
template <typename Function>
double lastPositive(const Function& f, double below, double above, double tolerance) {
  double fBelow = f(below);
  double fAbove = f(above);
  int side = 0;
  for (int i = 0; i < kMaxBisections && above - below > tolerance; ++i) {
    const bool secant = fBelow > 0.0 && fAbove <= 0.0 && std::isfinite(fBelow) && std::isfinite(fAbove);
    double middle = secant ? below + (above - below) * fBelow / (fBelow - fAbove) : 0.5 * (below + above);
    // Strictly inside, so that the bracket shrinks.
    middle = std::clamp(middle, below + 0.01 * (above - below), above - 0.01 * (above - below));
    const double value = f(middle);
    if (value > 0.0) {
      below = middle;
      fBelow = value;
      if (side == 1) fAbove *= 0.5;
      side = 1;
    } else {
      above = middle;
      fAbove = value;
      if (side == -1) fBelow *= 0.5;
      side = -1;
    }
  }
  return above;
}

}  // namespace

SwitchingPointFinder::SwitchingPointFinder(const PhasePlane& plane, std::size_t first, std::size_t last)
    : plane_(plane), first_(first), last_(last), scanned_(first) {}

std::optional<SwitchingPoint> SwitchingPointFinder::next(double from) {
  while (true) {
    for (; cursor_ < found_.size(); ++cursor_) {
      const SwitchingPoint& point = found_[cursor_];
      if (point.s > lastReturned_ && point.s >= from) {
        lastReturned_ = point.s;
        return found_[cursor_++];
      }
    }
    if (scanned_ > last_) return std::nullopt;
    const std::size_t k = std::max(scanned_, std::clamp(plane_.path().segmentIndex(from), first_, last_));
    if (k > first_) scanBoundary(k);
    if (plane_.isArc(k)) scanArc(k);
    scanned_ = k + 1;
  }
}

SwitchingPointFinder::Node SwitchingPointFinder::evaluate(std::size_t k, double s, bool hasLeft,
                                                          bool hasRight, bool corner) const {
  const CurveLimits here = plane_.curveLimits(k, s);
  Node node;
  node.s = s;
  node.v = here.value;
  node.branch = here.branch;
  if (!corner) {  // the curve's derivative is its analytic one (0 on a line)
    node.gLeft = sideG(here, false, here.slope);
    node.gRight = sideG(here, true, here.slope);
    node.slopeRight = here.slope;
    return node;
  }
  // One-sided values next to a corner of the curve.
  const double step = kSlopeStep * plane_.radius(k);
  if (hasLeft) {
    const CurveLimits left = plane_.curveLimits(k, s - step);
    node.gLeft = sideG(left, false, (node.v - left.value) / step);
  }
  if (hasRight) {
    const CurveLimits right = plane_.curveLimits(k, s + step);
    node.slopeRight = (right.value - node.v) / step;
    node.gRight = sideG(right, true, node.slopeRight);
  }
  return node;
}

double SwitchingPointFinder::sideG(const CurveLimits& curve, bool leaving, double slope) {
  // Arriving, the trajectory brakes as hard as it can. Leaving, it accelerates as hard as it can
  // under the acceleration-limit curve (where the range is one point), while on the
  // velocity-limit curve it may follow the curve as long as it can brake as fast as it falls.
  const bool accelerationLimited = curve.acceleration < curve.velocity.value;
  const double chosen = leaving && accelerationLimited ? curve.range.upper : curve.range.lower;
  return chosen / curve.value - slope;
}

void SwitchingPointFinder::add(std::size_t before, std::size_t after, double s, double v, double slopeRight,
                               bool onCurve) {
  // The accelerations next to s (at s itself a joint whose derivative is zero allows any), in
  // the segments that hold the points next to it.
  const double step = before == after ? kSlopeStep * plane_.radius(after) : 0.0;
  if (before > first_ && s - step <= plane_.segmentStart(before)) --before;
  if (after < last_ && s + step >= plane_.segmentEnd(after)) ++after;
  SwitchingPoint point;
  point.s = s;
  point.v = v;
  point.beforeAcceleration = plane_.accelerationRange(before, s - step, v).lower;
  const AccelerationRange range = plane_.accelerationRange(after, s + step, v);
  point.afterAcceleration = onCurve ? std::max(range.lower, std::min(range.upper, slopeRight * v)) : range.upper;
  found_.push_back(point);
}

void SwitchingPointFinder::scanBoundary(std::size_t k) {
  const double s = plane_.segmentStart(k);
  const Node left = evaluate(k - 1, s, true, false, false);
  const Node right = evaluate(k, s, false, true, false);
  // A drop of the curve lets the trajectory come from below on the left; a rise lets it leave
  // on the right.
  const bool fromBelow = left.v > right.v * (1.0 + kJump) || left.gLeft > 0.0;
  const bool leavesBelow = right.v > left.v * (1.0 + kJump) || right.gRight <= 0.0;
  if (!fromBelow || !leavesBelow) return;
  const double v = std::min(left.v, right.v);
  add(k - 1, k, s, v, right.slopeRight, v >= right.v * (1.0 - kJump));
}

void SwitchingPointFinder::scanArc(std::size_t k) {
  const double start = plane_.segmentStart(k);
  const double end = plane_.segmentEnd(k);
  const double maxSpacing = kMaxNodeAngle * plane_.radius(k);
  corners_.clear();
  plane_.appendZeroDerivativePoints(k, corners_);
  corners_.push_back(end);  // not a corner: the last anchor
  std::sort(corners_.begin(), corners_.end() - 1);
  Node previous = evaluate(k, start, false, true, false);
  double a = start;
  for (std::size_t i = 0; i < corners_.size(); ++i) {
    const double b = corners_[i];
    const bool atEnd = i + 1 == corners_.size();
    if (b - a <= 1e-12 * plane_.radius(k)) continue;
    const int count = std::max(1, static_cast<int>(std::ceil((b - a) / maxSpacing)));
    for (int j = 1; j <= count; ++j) {
      const bool last = atEnd && j == count;
      const double s = j == count ? b : a + (b - a) * j / count;
      const Node current = evaluate(k, s, true, !last, j == count && !atEnd);
      if (!(previous.branch == current.branch)) {
        // The constraint that makes the curve changes in between: a corner of the curve, after
        // which it may fall faster than the trajectory can brake (a short stretch).
        const double change = changeOfBranch(k, previous, current);
        const Node middle = evaluate(k, change, true, true, true);
        compare(k, previous, middle, true);
        compare(k, middle, current, !last);
      } else {
        compare(k, previous, current, !last);
      }
      previous = current;
    }
    a = b;
  }
}

void SwitchingPointFinder::compare(std::size_t k, const Node& left, const Node& right, bool rightIsInside) {
  if (left.gRight > 0.0 && right.gLeft <= 0.0) {
    bisect(k, left.s, right.s);
  } else if (rightIsInside && right.gLeft > 0.0 && right.gRight <= 0.0) {  // at a corner
    add(k, k, right.s, right.v, right.slopeRight, true);
  }
}

double SwitchingPointFinder::changeOfBranch(std::size_t k, const Node& left, const Node& right) const {
  // The left branch is the lower one at `left`, the right one at `right`.
  return lastPositive(
      [&](double s) { return plane_.branchValue(k, s, right.branch) - plane_.branchValue(k, s, left.branch); },
      left.s, right.s, 1e-10 * plane_.radius(k));
}

void SwitchingPointFinder::bisect(std::size_t k, double below, double above) {
  // g = (gLeft + gRight) / 2 changes from > 0 to <= 0 between below and above.
  const double s = lastPositive(
      [&](double point) {
        const Node node = evaluate(k, point, true, true, false);
        return 0.5 * (node.gLeft + node.gRight);
      },
      below, above, 1e-10 * plane_.radius(k));
  const Node node = evaluate(k, s, true, s < plane_.segmentEnd(k), false);
  add(k, k, s, node.v, node.slopeRight, true);
}

}  // namespace lang2manip::totg
