#include "lang2manip/kinematics/dls_descent.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lang2manip {
namespace {

using Vector6 = DlsWorkspace::Vector6;

// Tuning constants of the descent, all in one place.
/// Damping (m^2) at the start of a descent and its bounds.
constexpr double kInitialDamping = 1e-3;
constexpr double kMinDamping = 1e-12;
constexpr double kMinAxisDamping = 1e-9;  // approach-axis targets: J J^T is singular
constexpr double kMaxDamping = 1e3;
/// Iterations of one descent before a restart.
constexpr int kDescentIterations = 60;
/// Re-solves of one step after holding joints on their limits.
constexpr int kActiveSetPasses = 3;
/// Largest joint step of one iteration (rad or m).
constexpr double kMaxStep = 0.6;
/// Stagnation: every kStagnationWindow iterations the squared error must have shrunk by
/// kStagnationProgress, unless it is below kStagnationFloor (near a singular solution the last
/// digits come linearly, and finishing is cheaper than a restart).
constexpr int kStagnationWindow = 3;
constexpr double kStagnationProgress = 0.5;
constexpr double kStagnationFloor = 1e-6;

/// Rotation vector taking unit vector `from` onto unit vector `to`.
Vector3 rotationBetween(const Vector3& from, const Vector3& to) noexcept {
  const Vector3 cross = from.cross(to);
  const double sine = cross.norm();
  const double angle = std::atan2(sine, from.dot(to));
  if (sine > 1e-12) return cross * (angle / sine);
  return angle > 1.0 ? Vector3(from.unitOrthogonal() * std::numbers::pi) : Vector3(cross);
}

/// Rotation vector of the rotation `rotation` (log map), shortest way.
Vector3 rotationVector(const Quaternion& rotation) noexcept {
  const double sign = rotation.w() < 0.0 ? -1.0 : 1.0;
  const Vector3 v = sign * rotation.vec();
  const double sine = v.norm();
  if (sine < 1e-12) return 2.0 * v;
  return v * (2.0 * std::atan2(sine, sign * rotation.w()) / sine);
}

/// The 6D error (target minus current, in the base frame); for an approach-axis target also
/// projects the angular rows of `jacobian` (rotation about the tool axis is free).
void errorAndProjection(const IkTarget& target, const Pose& X_BT, Vector6& error,
                        Jacobian6& jacobian) noexcept {
  error.head<3>() = target.position - X_BT.translation();
  if (target.kind == IkTarget::Kind::kPose) {
    error.tail<3>() = rotationVector(target.orientation * Quaternion(X_BT.linear()).conjugate());
    return;
  }
  const Vector3 axis = X_BT.linear() * target.toolAxis;
  error.tail<3>() = rotationBetween(axis, target.approachAxis);
  for (Eigen::Index c = 0; c < jacobian.cols(); ++c) {
    const Vector3 angular = jacobian.col(c).tail<3>();
    jacobian.col(c).tail<3>() = angular - axis * axis.dot(angular);
  }
}

bool converged(const IkProblem& problem, const Vector6& error) noexcept {
  return error.head<3>().norm() <= problem.positionTolerance &&
         error.tail<3>().norm() <= problem.orientationTolerance;
}

/// Evaluates configuration `q` into pose, Jacobian and error.
void evaluate(const IkProblem& problem, const VectorX& q, Pose& pose, Jacobian6& jacobian,
              Vector6& error) noexcept {
  problem.chain.poseAndJacobian(q, pose, jacobian);
  errorAndProjection(problem.target, pose, error, jacobian);
}

/// The damped least-squares step of the columns in w.active towards w.residual, clamped to
/// kMaxStep (held joints have zero columns, hence a zero step).
void dampedStep(DlsWorkspace& w, double damping) noexcept {
  w.normal.noalias() = w.active.lazyProduct(w.active.transpose());
  w.normal.diagonal().array() += damping;
  Vector6 y;
  w.llt.compute(w.normal);
  if (w.llt.info() == Eigen::Success) {
    y = w.llt.solve(w.residual);
  } else {
    w.ldlt.compute(w.normal);
    y = w.ldlt.solve(w.residual);
  }
  w.step.noalias() = w.active.transpose() * y;
  const double largest = w.step.cwiseAbs().maxCoeff();
  if (largest > kMaxStep) w.step *= kMaxStep / largest;
}

/// Holds the free joints whose step would cross a limit: each moves exactly onto its limit.
/// Returns true when some joint was newly held.
bool holdCrossingJoints(const IkProblem& problem, DlsWorkspace& w) noexcept {
  bool changed = false;
  for (Eigen::Index i = 0; i < w.step.size(); ++i) {
    if (w.held[i] != 0.0) continue;
    const double next = w.q[i] + w.step[i];
    if (next >= problem.lower[i] && next <= problem.upper[i]) continue;
    w.heldStep[i] = (next < problem.lower[i] ? problem.lower[i] : problem.upper[i]) - w.q[i];
    w.held[i] = 1.0;
    w.active.col(i).setZero();
    changed = true;
  }
  return changed;
}

/// The step with joint limits as an active set: a joint whose step would cross a limit is held
/// on it (its column removed, its motion taken out of the error) and the step recomputed for the
/// others, so reaching a limit does not waste the step of every other joint.
void limitedStep(const IkProblem& problem, DlsWorkspace& w, double damping) noexcept {
  w.active = w.jacobian;
  w.residual = w.error;
  w.held.setZero();
  w.heldStep.setZero();
  for (int pass = 0; pass < kActiveSetPasses; ++pass) {
    dampedStep(w, damping);
    if (!holdCrossingJoints(problem, w)) break;
    w.residual.noalias() = w.error - w.jacobian * w.heldStep;
    if (pass + 1 == kActiveSetPasses) dampedStep(w, damping);
  }
  w.step += w.heldStep;
}

/// Accepts the trial point as the current one.
void accept(DlsWorkspace& w) noexcept {
  w.q.swap(w.trial);
  w.jacobian.swap(w.trialJacobian);
  w.error = w.trialError;
  w.pose = w.trialPose;
}

}  // namespace

bool dlsDescend(const IkProblem& problem, DlsWorkspace& w, IkSearch& search) noexcept {
  const double minDamping =
      problem.target.kind == IkTarget::Kind::kPose ? kMinDamping : kMinAxisDamping;
  double damping = kInitialDamping;
  double growth = 2.0;
  evaluate(problem, w.q, w.pose, w.jacobian, w.error);
  double cost = w.error.squaredNorm();
  double checkpoint = cost;
  for (int iteration = 0; iteration < kDescentIterations; ++iteration) {
    if (converged(problem, w.error)) return true;
    if (iteration > 0 && iteration % kStagnationWindow == 0) {
      if (cost > kStagnationFloor && cost > kStagnationProgress * checkpoint) break;
      checkpoint = cost;
    }
    if (search.shouldStop()) break;
    search.countIteration();
    limitedStep(problem, w, damping);
    w.trial = (w.q + w.step).cwiseMax(problem.lower).cwiseMin(problem.upper);
    // Decrease of the squared error the linear model predicts for the step actually taken.
    w.step = w.trial - w.q;
    const double predicted = cost - (w.error - w.jacobian * w.step).squaredNorm();
    evaluate(problem, w.trial, w.trialPose, w.trialJacobian, w.trialError);
    const double trialCost = w.trialError.squaredNorm();
    if (trialCost < cost) {
      const double gain = predicted > 0.0 ? 2.0 * (cost - trialCost) / predicted - 1.0 : 1.0;
      accept(w);
      cost = trialCost;
      damping = std::max(damping * std::max(1.0 / 3.0, 1.0 - gain * gain * gain), minDamping);
      growth = 2.0;
    } else {
      damping *= growth;
      growth *= 2.0;
      if (damping > kMaxDamping) break;
    }
  }
  if (converged(problem, w.error)) return true;
  search.recordFailure(w.q, w.pose);
  return false;
}

}  // namespace lang2manip
