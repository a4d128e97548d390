#include "lang2manip/planning/phase_plane.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

namespace lang2manip::totg {
namespace {

// A joint whose derivative along the path is smaller than this is treated as not moving with
// the path speed (its acceleration limit then bounds v^2 |q''| alone).
constexpr double kTinyDerivative = 1e-12;
// Relative slack of isAboveLimit(), so that points computed on a limit curve are not above it.
constexpr double kLimitSlack = 1e-9;

}  // namespace

PhasePlane::PhasePlane(const BlendedPath& path, const MatrixX* jacobian, const VectorX& maxVelocity,
                       const VectorX& maxAcceleration)
    : path_(path), maxVelocity_(maxVelocity), maxAcceleration_(maxAcceleration) {
  const auto count = static_cast<Eigen::Index>(path.segments().size());
  const Eigen::Index joints = maxVelocity.size();
  axisX_ = MatrixX::Zero(joints, count);
  axisY_ = MatrixX::Zero(joints, count);
  segments_.reserve(path.segments().size());
  for (Eigen::Index k = 0; k < count; ++k) {
    const PathSegment& source = path.segments()[static_cast<std::size_t>(k)];
    axisX_.col(k) = jacobian != nullptr ? VectorX(*jacobian * source.axisX) : source.axisX;
    if (source.kind == PathSegment::Kind::kArc) {
      axisY_.col(k) = jacobian != nullptr ? VectorX(*jacobian * source.axisY) : source.axisY;
    }
    Segment segment;
    segment.start = source.start;
    segment.end = source.start + source.length;
    segment.radius = source.kind == PathSegment::Kind::kArc ? source.radius : 0.0;
    segment.lineSpeed = kMaxPathSpeed;
    segment.lineAcceleration = kMaxPathAcceleration;
    for (Eigen::Index i = 0; i < joints; ++i) {
      const double derivative = std::abs(axisX_(i, k));
      if (derivative <= kTinyDerivative) continue;
      segment.lineSpeed = std::min(segment.lineSpeed, maxVelocity[i] / derivative);
      segment.lineAcceleration = std::min(segment.lineAcceleration, maxAcceleration[i] / derivative);
    }
    segments_.push_back(segment);
  }
  const auto size = static_cast<std::size_t>(joints);
  first_.assign(size, 0.0);
  second_.assign(size, 0.0);
  inverse_.assign(size, 0.0);
  width_.assign(size, 0.0);
  ratio_.assign(size, 0.0);
  joint_.assign(size, 0);
}

void PhasePlane::arcDerivatives(std::size_t k, double s) const {
  const Segment& segment = segments_[k];
  const double angle = (std::clamp(s, segment.start, segment.end) - segment.start) / segment.radius;
  const double cosine = std::cos(angle);
  const double sine = std::sin(angle);
  const double curvature = -1.0 / segment.radius;
  const double* x = axisX_.col(static_cast<Eigen::Index>(k)).data();
  const double* y = axisY_.col(static_cast<Eigen::Index>(k)).data();
  for (std::size_t i = 0; i < first_.size(); ++i) {
    first_[i] = y[i] * cosine - x[i] * sine;
    second_[i] = (x[i] * cosine + y[i] * sine) * curvature;
    inverse_[i] = std::abs(first_[i]) > kTinyDerivative ? 1.0 / first_[i] : 0.0;
  }
}

CurvePoint PhasePlane::velocityCurveFromScratch(CurveBranch* branch) const {
  CurvePoint best{kMaxPathSpeed, 0.0};
  for (std::size_t i = 0; i < first_.size(); ++i) {
    const double limit = maxVelocity_[static_cast<Eigen::Index>(i)] * std::abs(inverse_[i]);
    if (inverse_[i] != 0.0 && limit < best.value) {
      // d/ds (vmax / |q'|) = -vmax sign(q') q'' / q'^2
      best = {limit, -limit * second_[i] * inverse_[i]};
      if (branch != nullptr) *branch = {false, static_cast<int>(i), -1};
    }
  }
  return best;
}

AccelerationRange PhasePlane::rangeFromScratch(double v) const {
  AccelerationRange range{-kMaxPathAcceleration, kMaxPathAcceleration};
  const double speedSquared = v * v;
  for (std::size_t i = 0; i < first_.size(); ++i) {
    if (inverse_[i] == 0.0) continue;
    const double centre = -second_[i] * speedSquared * inverse_[i];
    const double width = maxAcceleration_[static_cast<Eigen::Index>(i)] * std::abs(inverse_[i]);
    range.lower = std::max(range.lower, centre - width);
    range.upper = std::min(range.upper, centre + width);
  }
  return range;
}

CurvePoint PhasePlane::accelerationCurveFromScratch(CurveBranch* branch) const {
  // Joint i allows a in [c_i - w_i, c_i + w_i] with c_i = -r_i v^2, r_i = q_i''/q_i', and
  // w_i = amax_i / |q_i'|: the intervals meet pairwise while v^2 |r_i - r_j| <= w_i + w_j.
  double bound = std::numeric_limits<double>::infinity();
  CurveBranch single;
  std::size_t moving = 0;
  for (std::size_t i = 0; i < first_.size(); ++i) {
    const double limit = maxAcceleration_[static_cast<Eigen::Index>(i)];
    if (inverse_[i] == 0.0) {
      if (std::abs(second_[i]) > kTinyDerivative && limit / std::abs(second_[i]) < bound) {
        bound = limit / std::abs(second_[i]);
        single = {true, static_cast<int>(i), -1};
      }
      continue;
    }
    width_[moving] = limit * std::abs(inverse_[i]);
    ratio_[moving] = second_[i] * inverse_[i];
    joint_[moving] = static_cast<int>(i);
    ++moving;
  }
  // The smallest (w_i + w_j) / |r_i - r_j| as a fraction, divided once.
  double numerator = 1.0;
  double denominator = 0.0;
  std::size_t bestI = 0;
  std::size_t bestJ = 0;
  for (std::size_t i = 0; i < moving; ++i) {
    for (std::size_t j = i + 1; j < moving; ++j) {
      const double sum = width_[i] + width_[j];
      const double gap = std::abs(ratio_[i] - ratio_[j]);
      if (sum * denominator < numerator * gap) {
        numerator = sum;
        denominator = gap;
        bestI = i;
        bestJ = j;
      }
    }
  }
  if (denominator == 0.0 || bound <= numerator / denominator) {
    if (branch != nullptr) *branch = single;
    return {std::sqrt(bound), 0.0};
  }
  if (branch != nullptr) *branch = {true, joint_[bestI], joint_[bestJ]};
  // On an arc q''' = -q' / R^2, so w' = -w r and r' = -1/R^2 - r^2, which make
  // d(v^2)/ds = (w_i r_j + w_j r_i) / |r_i - r_j|.
  const double value = std::sqrt(numerator / denominator);
  const double squaredSlope = (width_[bestI] * ratio_[bestJ] + width_[bestJ] * ratio_[bestI]) / denominator;
  return {value, squaredSlope / (2.0 * value)};
}

double PhasePlane::branchValue(std::size_t k, double s, const CurveBranch& branch) const {
  if (!isArc(k) || branch.first < 0) return limitCurve(k, s);
  // Only the joints of the branch: their derivatives at s.
  const Segment& segment = segments_[k];
  const double angle = (std::clamp(s, segment.start, segment.end) - segment.start) / segment.radius;
  const double cosine = std::cos(angle);
  const double sine = std::sin(angle);
  const auto column = static_cast<Eigen::Index>(k);
  const auto derivatives = [&](int joint) {
    const double x = axisX_(joint, column);
    const double y = axisY_(joint, column);
    return std::pair{y * cosine - x * sine, -(x * cosine + y * sine) / segment.radius};
  };
  const auto [first, second] = derivatives(branch.first);
  const double limit = branch.acceleration ? maxAcceleration_[branch.first] : maxVelocity_[branch.first];
  const bool still = std::abs(first) <= kTinyDerivative;
  if (!branch.acceleration) return still ? kMaxPathSpeed : limit / std::abs(first);
  if (branch.second < 0) return std::sqrt(limit / std::max(std::abs(second), kTinyDerivative));
  const auto [otherFirst, otherSecond] = derivatives(branch.second);
  const double otherLimit = maxAcceleration_[branch.second];
  if (still) return std::sqrt(limit / std::max(std::abs(second), kTinyDerivative));
  if (std::abs(otherFirst) <= kTinyDerivative) return std::sqrt(otherLimit / std::max(std::abs(otherSecond), kTinyDerivative));
  const double sum = limit / std::abs(first) + otherLimit / std::abs(otherFirst);
  const double gap = std::abs(second / first - otherSecond / otherFirst);
  return gap > 0.0 ? std::sqrt(sum / gap) : kMaxPathSpeed;
}

CurvePoint PhasePlane::velocityCurve(std::size_t k, double s) const {
  if (!isArc(k)) return {segments_[k].lineSpeed, 0.0};
  arcDerivatives(k, s);
  return velocityCurveFromScratch();
}

double PhasePlane::limitCurve(std::size_t k, double s) const { return curveLimits(k, s).value; }

CurveLimits PhasePlane::curveLimits(std::size_t k, double s) const {
  CurveLimits limits;
  if (!isArc(k)) {
    const Segment& segment = segments_[k];
    limits.velocity = {segment.lineSpeed, 0.0};
    limits.value = segment.lineSpeed;
    limits.slope = 0.0;
    limits.range = {-segment.lineAcceleration, segment.lineAcceleration};
    return limits;
  }
  arcDerivatives(k, s);
  CurveBranch velocityBranch;
  CurveBranch accelerationBranch;
  limits.velocity = velocityCurveFromScratch(&velocityBranch);
  const CurvePoint acceleration = accelerationCurveFromScratch(&accelerationBranch);
  limits.acceleration = acceleration.value;
  const bool accelerationLimited = acceleration.value < limits.velocity.value;
  limits.value = std::min(limits.velocity.value, acceleration.value);
  limits.slope = accelerationLimited ? acceleration.slope : limits.velocity.slope;
  limits.branch = accelerationLimited ? accelerationBranch : velocityBranch;
  limits.range = rangeFromScratch(limits.value);
  return limits;
}

AccelerationRange PhasePlane::accelerationRange(std::size_t k, double s, double v) const {
  const Segment& segment = segments_[k];
  if (!isArc(k)) return {-segment.lineAcceleration, segment.lineAcceleration};
  arcDerivatives(k, s);
  return rangeFromScratch(v);
}

PointLimits PhasePlane::limitsAt(std::size_t k, double s, double v) const {
  const Segment& segment = segments_[k];
  PointLimits limits;
  if (!isArc(k)) {
    limits.velocity = {segment.lineSpeed, 0.0};
    limits.range = {-segment.lineAcceleration, segment.lineAcceleration};
    limits.above = v > segment.lineSpeed * (1.0 + kLimitSlack);
    return limits;
  }
  // arcDerivatives(), velocityCurveFromScratch() and rangeFromScratch() in one pass (the
  // integration's inner loop).
  const double angle = (std::clamp(s, segment.start, segment.end) - segment.start) / segment.radius;
  const double cosine = std::cos(angle);
  const double sine = std::sin(angle);
  const double curvature = -1.0 / segment.radius;
  const double* x = axisX_.col(static_cast<Eigen::Index>(k)).data();
  const double* y = axisY_.col(static_cast<Eigen::Index>(k)).data();
  const double* maxVelocity = maxVelocity_.data();
  const double* maxAcceleration = maxAcceleration_.data();
  const double speedSquared = v * v;
  CurvePoint velocity{kMaxPathSpeed, 0.0};
  AccelerationRange range{-kMaxPathAcceleration, kMaxPathAcceleration};
  bool above = false;
  for (std::size_t i = 0; i < first_.size(); ++i) {
    const double first = y[i] * cosine - x[i] * sine;
    const double second = (x[i] * cosine + y[i] * sine) * curvature;
    if (std::abs(first) <= kTinyDerivative) {
      above = above || std::abs(second) * speedSquared > maxAcceleration[i] * (1.0 + kLimitSlack);
      continue;
    }
    const double inverse = 1.0 / first;
    const double limit = maxVelocity[i] * std::abs(inverse);
    if (limit < velocity.value) velocity = {limit, -limit * second * inverse};
    const double centre = -second * speedSquared * inverse;
    const double width = maxAcceleration[i] * std::abs(inverse);
    range.lower = std::max(range.lower, centre - width);
    range.upper = std::min(range.upper, centre + width);
  }
  limits.velocity = velocity;
  limits.range = range;
  limits.above = above || v > velocity.value * (1.0 + kLimitSlack) ||
                 range.lower > range.upper + kLimitSlack * (1.0 + std::abs(range.lower) + std::abs(range.upper));
  return limits;
}

void PhasePlane::appendZeroDerivativePoints(std::size_t k, std::vector<double>& out) const {
  if (!isArc(k)) return;
  const Segment& segment = segments_[k];
  const double sweep = (segment.end - segment.start) / segment.radius;
  const auto column = static_cast<Eigen::Index>(k);
  for (Eigen::Index i = 0; i < axisX_.rows(); ++i) {
    const double x = axisX_(i, column);
    const double y = axisY_(i, column);
    if (std::abs(x) + std::abs(y) <= kTinyDerivative) continue;
    // q_i' = y cos(t) - x sin(t) is zero at t = atan2(y, x) modulo pi.
    double angle = std::atan2(y, x);
    if (angle < 0.0) angle += std::numbers::pi;
    for (; angle < sweep; angle += std::numbers::pi) {
      if (angle > 0.0) out.push_back(segment.start + angle * segment.radius);
    }
  }
}

void PhasePlane::jointMotion(std::size_t k, double s, double v, double a, VectorX& velocity,
                             VectorX& acceleration) const {
  if (!isArc(k)) {
    velocity.noalias() = axisX_.col(static_cast<Eigen::Index>(k)) * v;
    acceleration.noalias() = axisX_.col(static_cast<Eigen::Index>(k)) * a;
    return;
  }
  arcDerivatives(k, s);
  for (std::size_t i = 0; i < first_.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    velocity[row] = first_[i] * v;
    acceleration[row] = first_[i] * a + second_[i] * v * v;
  }
}

}  // namespace lang2manip::totg
