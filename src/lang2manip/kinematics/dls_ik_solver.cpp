#include "lang2manip/kinematics/dls_ik_solver.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Cholesky>

#include "lang2manip/core/random.hpp"
#include "lang2manip/kinematics/ik_search.hpp"

namespace lang2manip {
namespace {

// Tuning constants of the solver, all in one place.
/// Damping (m^2) at the start of an attempt, its bounds, and its factors on success / failure.
constexpr double kInitialDamping = 1e-3;
constexpr double kMinDamping = 1e-12;
constexpr double kMinAxisDamping = 1e-9;  // approach-axis targets: J J^T is singular
constexpr double kMaxDamping = 1e3;
constexpr double kDampingDown = 0.2;
constexpr double kDampingUp = 10.0;
/// Iterations of one attempt before a restart.
constexpr int kMaxIterations = 60;
/// Re-solves of one step after holding joints at their limits.
constexpr int kActiveSetPasses = 2;
/// Largest joint step of one iteration (rad or m).
constexpr double kMaxStep = 0.6;

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// Per-call state; every buffer is sized once.
struct Workspace {
  explicit Workspace(int dof)
      : jacobian(6, dof), trialJacobian(6, dof), active(6, dof), q(dof), trial(dof), step(dof) {}
  Jacobian6 jacobian;
  Jacobian6 trialJacobian;
  /// The Jacobian without the columns of joints held at a limit.
  Jacobian6 active;
  VectorX q;
  VectorX trial;
  VectorX step;
  Pose pose = Pose::Identity();
  Pose trialPose = Pose::Identity();
  Vector6 error = Vector6::Zero();
  Vector6 trialError = Vector6::Zero();
  Matrix6 normal = Matrix6::Zero();
  Eigen::LDLT<Matrix6> ldlt;
};

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

/// The damped least-squares step of the columns in w.active, clamped to kMaxStep.
void dampedStep(Workspace& w, double damping) noexcept {
  w.normal.noalias() = w.active.lazyProduct(w.active.transpose());
  w.normal.diagonal().array() += damping;
  w.ldlt.compute(w.normal);
  const Vector6 y = w.ldlt.solve(w.error);
  w.step.noalias() = w.active.transpose() * y;
  const double largest = w.step.cwiseAbs().maxCoeff();
  if (largest > kMaxStep) w.step *= kMaxStep / largest;
}

/// The step with joint limits as an active set: a joint at a limit whose step pushes past it is
/// held (its column removed) and the step recomputed for the others, so clamping does not
/// waste the step of every other joint.
void limitedStep(const IkProblem& problem, Workspace& w, double damping) noexcept {
  w.active = w.jacobian;
  for (int pass = 0; pass < kActiveSetPasses; ++pass) {
    dampedStep(w, damping);
    bool changed = false;
    for (Eigen::Index i = 0; i < w.step.size(); ++i) {
      const bool atLower = w.q[i] <= problem.lower[i] && w.step[i] < 0.0;
      const bool atUpper = w.q[i] >= problem.upper[i] && w.step[i] > 0.0;
      if ((atLower || atUpper) && !w.active.col(i).isZero(0.0)) {
        w.active.col(i).setZero();
        changed = true;
      }
    }
    if (!changed) return;
  }
  dampedStep(w, damping);
}

/// One attempt from w.q. Returns true when converged (w.q is then the solution).
bool runAttempt(const IkProblem& problem, Workspace& w, IkSearch& search) noexcept {
  const double minDamping =
      problem.target.kind == IkTarget::Kind::kPose ? kMinDamping : kMinAxisDamping;
  double damping = kInitialDamping;
  evaluate(problem, w.q, w.pose, w.jacobian, w.error);
  double cost = w.error.squaredNorm();
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    if (converged(problem, w.error)) return true;
    if (search.shouldStop()) break;
    search.countIteration();
    limitedStep(problem, w, damping);
    w.trial = (w.q + w.step).cwiseMax(problem.lower).cwiseMin(problem.upper);
    evaluate(problem, w.trial, w.trialPose, w.trialJacobian, w.trialError);
    const double trialCost = w.trialError.squaredNorm();
    if (trialCost < cost) {
      w.q.swap(w.trial);
      w.jacobian.swap(w.trialJacobian);
      w.error = w.trialError;
      w.pose = w.trialPose;
      cost = trialCost;
      damping = std::max(damping * kDampingDown, minDamping);
    } else {
      damping *= kDampingUp;
      if (damping > kMaxDamping) break;
    }
  }
  if (converged(problem, w.error)) return true;
  search.recordFailure(w.q, w.pose);
  return false;
}

}  // namespace

IkResult DlsIkSolver::doSolve(const IkProblem& problem) const {
  Workspace w(problem.chain.dof());
  IkSearch search(problem);
  Random random(problem.randomSeed);
  w.q = problem.seed.cwiseMax(problem.lower).cwiseMin(problem.upper);
  while (!search.done()) {
    search.countAttempt();
    if (runAttempt(problem, w, search)) search.addSolution(w.q, w.pose);
    search.randomConfiguration(random, w.q);
  }
  return search.result();
}

std::unique_ptr<IkSolver> makeDlsIkSolver() { return std::make_unique<DlsIkSolver>(); }

}  // namespace lang2manip
