#pragma once
/// @file The phase plane (s, v = ds/dt) of a BlendedPath under joint velocity and acceleration
/// limits (Kunz and Stilman, RSS 2012, section V): the velocity-limit curve, the acceleration-limit
/// curve and the range of path accelerations at a phase-plane point. Internal to
/// timeOptimalParameterize (time_optimal_trajectory.hpp).

#include <cstddef>
#include <limits>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/planning/blended_path.hpp"

namespace lang2manip::totg {

/// Caps when no joint limits a path direction (a path coordinate no trajectory joint depends on).
inline constexpr double kMaxPathSpeed = 1e4;
inline constexpr double kMaxPathAcceleration = 1e6;

/// A limit curve's value and its derivative with respect to s.
struct CurvePoint {
  double value = 0.0;
  double slope = 0.0;
};

/// Path accelerations allowed at a phase-plane point; empty (lower > upper) above the
/// acceleration-limit curve.
struct AccelerationRange {
  double lower = 0.0;
  double upper = 0.0;
};

/// Everything the integration asks at one phase-plane point.
struct PointLimits {
  CurvePoint velocity;       // the velocity-limit curve at s
  AccelerationRange range;   // the path accelerations allowed at (s, v)
  bool above = false;        // (s, v) is above the velocity- or the acceleration-limit curve
};

/// Which constraint makes the limit curve at a point: the velocity limit of joint `first`, or the
/// acceleration limits of joints `first` and `second` together (of `first` alone when its
/// derivative is zero: second < 0). first < 0: none (a line, or no joint moves).
struct CurveBranch {
  bool acceleration = false;
  int first = -1;
  int second = -1;

  friend bool operator==(const CurveBranch&, const CurveBranch&) = default;
};

/// The limit curve at s, and the path accelerations allowed on it.
struct CurveLimits {
  CurvePoint velocity;   // the velocity-limit curve
  double acceleration = std::numeric_limits<double>::infinity();  // the acceleration-limit curve
  double value = 0.0;    // the lower of the two
  double slope = 0.0;    // its derivative (0 where a joint's derivative is zero: a corner)
  AccelerationRange range;  // at (s, value)
  CurveBranch branch;    // what makes `value`
};

/// The limits of the joints q = J x along a BlendedPath x(s): |q_i'(s) v| <= maxVelocity_i and
/// |q_i'(s) a + q_i''(s) v^2| <= maxAcceleration_i. Segment indices are the path's; s is the
/// path's arc length, within the segment given (its ends included, so that both sides of a
/// segment boundary can be asked for). Not thread-safe (scratch buffers); one per call.
class PhasePlane {
 public:
  /// `jacobian` (rows: joints, columns: path coordinates) maps the path to the limited joints;
  /// nullptr is the identity. The limits must be positive and finite (checked by the caller).
  PhasePlane(const BlendedPath& path, const MatrixX* jacobian, const VectorX& maxVelocity,
             const VectorX& maxAcceleration);

  [[nodiscard]] const BlendedPath& path() const noexcept { return path_; }
  [[nodiscard]] int jointCount() const noexcept { return static_cast<int>(maxVelocity_.size()); }
  [[nodiscard]] double segmentStart(std::size_t k) const noexcept { return segments_[k].start; }
  [[nodiscard]] double segmentEnd(std::size_t k) const noexcept { return segments_[k].end; }
  [[nodiscard]] bool isArc(std::size_t k) const noexcept { return segments_[k].radius > 0.0; }
  [[nodiscard]] double radius(std::size_t k) const noexcept { return segments_[k].radius; }

  /// The velocity-limit curve: the largest v within every joint's velocity limit.
  [[nodiscard]] CurvePoint velocityCurve(std::size_t k, double s) const;
  /// The limit curve: the lower of the velocity-limit curve and the acceleration-limit curve
  /// (the largest v at which some path acceleration keeps every joint within its acceleration
  /// limit; infinite on straight segments), at most kMaxPathSpeed.
  [[nodiscard]] double limitCurve(std::size_t k, double s) const;
  /// Both curves at s and the acceleration range on the lower one.
  [[nodiscard]] CurveLimits curveLimits(std::size_t k, double s) const;
  /// The speed limit that one constraint alone (a branch of the limit curve) sets at s.
  [[nodiscard]] double branchValue(std::size_t k, double s, const CurveBranch& branch) const;
  /// The path accelerations within every joint's acceleration limit at (s, v).
  [[nodiscard]] AccelerationRange accelerationRange(std::size_t k, double s, double v) const;
  /// True when (s, v) is above the velocity-limit or the acceleration-limit curve (with a
  /// relative tolerance of 1e-9).
  [[nodiscard]] bool isAboveLimit(std::size_t k, double s, double v) const { return limitsAt(k, s, v).above; }
  /// velocityCurve(), accelerationRange() and isAboveLimit() at once.
  [[nodiscard]] PointLimits limitsAt(std::size_t k, double s, double v) const;
  /// Appends the path arc lengths strictly inside arc k where some joint's derivative q_i'
  /// crosses zero (where the acceleration-limit curve may have a corner).
  void appendZeroDerivativePoints(std::size_t k, std::vector<double>& out) const;
  /// Joint velocities q' v and accelerations q' a + q'' v^2 at (s, v, a), into sized vectors.
  void jointMotion(std::size_t k, double s, double v, double a, VectorX& velocity,
                   VectorX& acceleration) const;

 private:
  struct Segment {
    double start = 0.0;
    double end = 0.0;
    double radius = 0.0;  // 0 for a line
    // Lines: the speed and acceleration bounds, constant along them.
    double lineSpeed = 0.0;
    double lineAcceleration = 0.0;
  };
  // q'(s), q''(s) and 1/q'(s) (0 where q' is tiny) of arc k into the scratch buffers.
  void arcDerivatives(std::size_t k, double s) const;
  // The curves and the acceleration range from the scratch derivatives.
  [[nodiscard]] CurvePoint velocityCurveFromScratch(CurveBranch* branch = nullptr) const;
  [[nodiscard]] CurvePoint accelerationCurveFromScratch(CurveBranch* branch = nullptr) const;
  [[nodiscard]] AccelerationRange rangeFromScratch(double v) const;

  const BlendedPath& path_;
  std::vector<Segment> segments_;
  // Columns per segment: J axisX and J axisY (zero for lines).
  MatrixX axisX_;
  MatrixX axisY_;
  VectorX maxVelocity_;
  VectorX maxAcceleration_;
  mutable std::vector<double> first_;
  mutable std::vector<double> second_;
  mutable std::vector<double> inverse_;
  mutable std::vector<double> width_;
  mutable std::vector<double> ratio_;
  mutable std::vector<int> joint_;
};

}  // namespace lang2manip::totg
