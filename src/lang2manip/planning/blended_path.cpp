#include "lang2manip/planning/blended_path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {
namespace {

// Lines shorter than this (what is left between two arcs that each use half of it) are dropped.
constexpr double kMinLineLength = 1e-12;

void checkDeviation(double deviation, const std::string& which) {
  if (!(deviation >= 0.0 && std::isfinite(deviation))) {
    throw InputError("blended path: " + which + " must be finite and >= 0 (got " + std::to_string(deviation) + ")");
  }
}

void checkWaypoints(const std::vector<VectorX>& waypoints) {
  if (waypoints.empty()) throw InputError("blended path: the path is empty (no waypoints)");
  const Eigen::Index size = waypoints.front().size();
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    const VectorX& point = waypoints[i];
    if (point.size() == 0) throw InputError("blended path: waypoint " + std::to_string(i) + " has no values");
    if (point.size() != size) {
      throw InputError("blended path: waypoint " + std::to_string(i) + " has " + std::to_string(point.size()) +
                       " values; waypoint 0 has " + std::to_string(size));
    }
    for (Eigen::Index j = 0; j < point.size(); ++j) {
      if (!std::isfinite(point[j])) {
        throw InputError("blended path: waypoint " + std::to_string(i) + " value " + std::to_string(j) +
                         " is not a finite number");
      }
    }
  }
}

// The indices of the waypoints kept: not those within kMinWaypointDistance of the previous kept
// one, except that a repeated last waypoint replaces the point it repeats, so that the path ends
// exactly on it.
std::vector<std::size_t> keptWaypoints(const std::vector<VectorX>& waypoints) {
  std::vector<std::size_t> kept{0};
  for (std::size_t i = 1; i < waypoints.size(); ++i) {
    if ((waypoints[i] - waypoints[kept.back()]).norm() > BlendedPath::kMinWaypointDistance) {
      kept.push_back(i);
    } else if (i + 1 == waypoints.size() && kept.size() > 1) {
      kept.back() = i;
    }
  }
  return kept;
}

std::vector<double> everyCorner(std::size_t waypoints, double maxDeviation) {
  checkDeviation(maxDeviation, "max deviation");
  return std::vector<double>(waypoints, maxDeviation);
}

}  // namespace

VectorX PathSegment::position(double u) const {
  if (u >= length) return end;
  u = std::max(u, 0.0);
  if (kind == Kind::kLine) return origin + u * axisX;
  const double angle = u / radius;
  return origin + radius * (axisX * std::cos(angle) + axisY * std::sin(angle));
}

VectorX PathSegment::tangent(double u) const {
  if (kind == Kind::kLine) return axisX;
  const double angle = std::clamp(u, 0.0, length) / radius;
  return axisY * std::cos(angle) - axisX * std::sin(angle);
}

VectorX PathSegment::curvature(double u) const {
  if (kind == Kind::kLine) return VectorX::Zero(axisX.size());
  const double angle = std::clamp(u, 0.0, length) / radius;
  return -(axisX * std::cos(angle) + axisY * std::sin(angle)) / radius;
}

BlendedPath::BlendedPath(const std::vector<VectorX>& waypoints, double maxDeviation)
    : BlendedPath(waypoints, everyCorner(waypoints.size(), maxDeviation)) {}

BlendedPath::BlendedPath(const std::vector<VectorX>& waypoints, const std::vector<double>& cornerDeviations) {
  checkWaypoints(waypoints);
  if (cornerDeviations.size() != waypoints.size()) {
    throw InputError("blended path: " + std::to_string(cornerDeviations.size()) + " corner deviations for " +
                     std::to_string(waypoints.size()) + " waypoints");
  }
  for (std::size_t i = 0; i < cornerDeviations.size(); ++i) {
    checkDeviation(cornerDeviations[i], "deviation at waypoint " + std::to_string(i));
  }
  const std::vector<std::size_t> kept = keptWaypoints(waypoints);
  for (const std::size_t i : kept) waypoints_.push_back(waypoints[i]);
  dimension_ = static_cast<int>(waypoints_.front().size());
  VectorX lineStart = waypoints_.front();
  for (std::size_t i = 1; i + 1 < waypoints_.size(); ++i) {
    addCorner(i, cornerDeviations[kept[i]], lineStart);
  }
  if (waypoints_.size() > 1) addLine(lineStart, waypoints_.back(), waypoints_.size() - 2);
  starts_.reserve(segments_.size());
  for (const PathSegment& segment : segments_) starts_.push_back(segment.start);
  const auto atAnEnd = [this](double s) { return s <= 0.0 || s >= length_; };
  switching_.erase(std::remove_if(switching_.begin(), switching_.end(), atAnEnd), switching_.end());
  switching_.erase(std::unique(switching_.begin(), switching_.end()), switching_.end());
}

void BlendedPath::addLine(const VectorX& from, const VectorX& to, std::size_t waypoint) {
  const double length = (to - from).norm();
  if (length <= kMinLineLength) return;
  PathSegment line;
  line.waypoint = waypoint;
  line.start = length_;
  line.length = length;
  line.origin = from;
  line.axisX = (to - from) / length;
  line.end = to;
  segments_.push_back(std::move(line));
  length_ += length;
}

void BlendedPath::addCorner(std::size_t index, double maxDeviation, VectorX& lineStart) {
  const VectorX& previous = waypoints_[index - 1];
  const VectorX& corner = waypoints_[index];
  const VectorX& next = waypoints_[index + 1];
  const double lengthIn = (corner - previous).norm();
  const double lengthOut = (next - corner).norm();
  const VectorX in = (corner - previous) / lengthIn;
  const VectorX out = (next - corner) / lengthOut;
  // The turning angle, accurate near 0 and near pi (unlike acos of the dot product).
  const double angle = 2.0 * std::atan2((out - in).norm(), (out + in).norm());
  if (angle < kMinBlendAngle) {  // straight on
    addLine(lineStart, corner, index - 1);
    lineStart = corner;
    return;
  }
  if (maxDeviation == 0.0 || angle > std::numbers::pi - kReversalAngle) {
    addLine(lineStart, corner, index - 1);
    stops_.push_back(length_);
    lineStart = corner;
    return;
  }
  const double half = 0.5 * angle;
  // Distance from the corner to where the arc leaves each line, so that the arc's middle is
  // maxDeviation from the corner: l = d sin(a/2) / (1 - cos(a/2)), 1 - cos(x) = 2 sin^2(x/2).
  const double sinQuarter = std::sin(0.5 * half);
  const double blend = std::min({0.5 * lengthIn, 0.5 * lengthOut,
                                 maxDeviation * std::sin(half) / (2.0 * sinQuarter * sinQuarter)});
  const double radius = blend / std::tan(half);
  const VectorX arcStart = corner - blend * in;
  PathSegment arc;
  arc.kind = PathSegment::Kind::kArc;
  arc.waypoint = index;
  arc.origin = corner + (out - in).normalized() * (radius / std::cos(half));
  arc.axisX = (arcStart - arc.origin).normalized();
  arc.axisY = in;
  arc.radius = radius;
  arc.length = angle * radius;
  arc.end = corner + blend * out;
  addLine(lineStart, arcStart, index - 1);
  arc.start = length_;
  switching_.push_back(length_);
  length_ += arc.length;
  switching_.push_back(length_);
  lineStart = arc.end;
  segments_.push_back(std::move(arc));
}

std::size_t BlendedPath::segmentIndex(double s) const noexcept {
  const auto after = std::upper_bound(starts_.begin(), starts_.end(), s);
  if (after == starts_.begin()) return 0;
  return static_cast<std::size_t>(after - starts_.begin()) - 1;
}

VectorX BlendedPath::position(double s) const {
  if (segments_.empty()) return waypoints_.front();
  if (s >= length_) return segments_.back().end;
  const PathSegment& segment = segments_[segmentIndex(s)];
  return segment.position(s - segment.start);
}

VectorX BlendedPath::tangent(double s) const {
  if (segments_.empty()) return VectorX::Zero(dimension_);
  const PathSegment& segment = segments_[segmentIndex(s)];
  return segment.tangent(s - segment.start);
}

VectorX BlendedPath::curvature(double s) const {
  if (segments_.empty()) return VectorX::Zero(dimension_);
  const PathSegment& segment = segments_[segmentIndex(s)];
  return segment.curvature(s - segment.start);
}

std::vector<VectorX> BlendedPath::sample(double resolution) const {
  if (!(resolution > 0.0 && std::isfinite(resolution))) {
    throw InputError("blended path: sampling resolution must be positive and finite (got " +
                     numberText(resolution) + ")");
  }
  const double count = std::floor(length_ / resolution);
  if (count > 1e8) throw InputError("blended path: sampling resolution too fine (more than 1e8 samples)");
  std::vector<VectorX> samples;
  samples.reserve(static_cast<std::size_t>(count) + 2);
  for (std::size_t k = 0; static_cast<double>(k) * resolution < length_; ++k) {
    samples.push_back(position(static_cast<double>(k) * resolution));
  }
  samples.push_back(position(length_));
  return samples;
}

}  // namespace lang2manip
