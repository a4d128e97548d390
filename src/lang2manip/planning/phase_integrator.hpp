#pragma once
/// @file Phase-plane integration of the time-optimal trajectory along a BlendedPath (Kunz and
/// Stilman, RSS 2012, section V): forward with the maximum path acceleration, backward with the
/// minimum one from switching points and from the end. Internal to timeOptimalParameterize.

#include <cstddef>
#include <vector>

#include "lang2manip/planning/phase_plane.hpp"

namespace lang2manip::totg {

/// A phase-plane point: arc length s and path speed v = ds/dt.
struct PhasePoint {
  double s = 0.0;
  double v = 0.0;
};

/// Integrates rest-to-rest pieces of a phase plane (Kunz and Stilman's algorithm): forward from
/// rest with the maximum path acceleration, following the velocity-limit curve where it can;
/// where it crosses the limit curve, backward with the minimum one from the next switching
/// point until it meets the forward trajectory, which it replaces from there, then forward again
/// from the switching point; at the end, backward from rest at the end.
/// On arcs, steps are `timeStep` long, shorter so that the tangent turns by at most
/// kMaxTurnPerStep per step and just after switching points; each step's acceleration is the
/// bound at its start, corrected to the bound at its end (a predictor-corrector), the step
/// halved when no constant acceleration fits along it or when it would end above the limit
/// curve. On lines, where the limits are constant, steps are exact and as long as the line (or
/// up to where the speed limit is reached). Should a backward integration still reach the limit
/// curve (a switching point missed between grid points), it slides down the curve there.
/// Holds its buffers across pieces (no allocation per step once they have grown). Not
/// thread-safe.
class PhaseIntegrator {
 public:
  /// `maxSteps` bounds the steps of every piece together.
  PhaseIntegrator(const PhasePlane& plane, double timeStep, std::size_t maxSteps);

  /// Largest turn of the path tangent (rad) within one integration step on an arc.
  static constexpr double kMaxTurnPerStep = 0.05;
  /// The first step from a switching point is this fraction of a step; the next ones double.
  static constexpr double kFirstStepScale = 1.0 / 8.0;

  /// The time-optimal phase trajectory over segments first..last, from rest at the start of
  /// `first` to rest at the end of `last`: s strictly increasing, v^2 linear in s between
  /// consecutive points (a constant path acceleration). Valid until the next call.
  /// Throws InputError when it would take more than maxSteps steps.
  const std::vector<PhasePoint>& integratePiece(std::size_t first, std::size_t last);
  /// Integration steps taken so far (every piece).
  [[nodiscard]] std::size_t steps() const noexcept { return steps_; }

 private:
  [[nodiscard]] double stepTime(std::size_t k, double v) const;
  [[nodiscard]] PhasePoint step(std::size_t k, const PhasePoint& from, double acceleration,
                                bool forward, double scale = 1.0) const;
  [[nodiscard]] PhasePoint lineStep(std::size_t k, const PhasePoint& from, double acceleration,
                                    bool forward) const;
  [[nodiscard]] PhasePoint forwardStep(std::size_t k, const PhasePoint& from, const PointLimits& here,
                                       double acceleration, PointLimits& there) const;
  [[nodiscard]] bool fitsAlong(std::size_t k, const PhasePoint& from, const PointLimits& here,
                               const PhasePoint& to, const PointLimits& there) const;
  [[nodiscard]] PhasePoint backwardStep(std::size_t k, const PhasePoint& from, const PointLimits& here,
                                        double acceleration) const;
  [[nodiscard]] bool canFollowVelocityCurve(std::size_t k, const PhasePoint& from, const PointLimits& here) const;
  void cutForwardAt(double s);
  void countStep();
  bool integrateForward(std::size_t k, double firstAcceleration);
  void refineCrossing(std::size_t k, const PhasePoint& from);
  void integrateBackward(const PhasePoint& start, double firstAcceleration);
  bool spliceIfMet(const PhasePoint& from, const PhasePoint& to);
  [[nodiscard]] double forwardSquared(double s) const;

  const PhasePlane& plane_;
  double timeStep_;
  std::size_t maxSteps_;
  std::size_t steps_ = 0;
  double stepScale_ = 1.0;  // of timeStep_, < 1 just after a switching point
  std::size_t first_ = 0;
  std::size_t last_ = 0;
  double pieceEnd_ = 0.0;
  double crossingStepStart_ = 0.0;  // s where the step that crossed the limit curve started
  std::size_t meet_ = 0;  // forward_[meet_].s <= the backward integration's s
  std::vector<PhasePoint> forward_;
  std::vector<PhasePoint> backward_;
};

}  // namespace lang2manip::totg
