#pragma once
/// @file The inner loop of the default IK solver: one Levenberg-Marquardt descent from a start
/// configuration, with joint limits as an active set. Allocation-free once its workspace exists.

#include <Eigen/Cholesky>

#include "lang2manip/kinematics/ik_search.hpp"
#include "lang2manip/kinematics/ik_solver.hpp"

namespace lang2manip {

/// The memory of a descent, sized once for a chain of `dof` variables. One per thread.
struct DlsWorkspace {
  using Vector6 = Eigen::Matrix<double, 6, 1>;
  using Matrix6 = Eigen::Matrix<double, 6, 6>;

  explicit DlsWorkspace(int dof)
      : jacobian(6, dof), trialJacobian(6, dof), active(6, dof), q(dof), trial(dof), step(dof),
        held(dof), heldStep(dof) {}

  Jacobian6 jacobian;
  Jacobian6 trialJacobian;
  /// The Jacobian without the columns of the joints held on a limit.
  Jacobian6 active;
  /// The current configuration (chain variables): the start on entry, the end on return.
  VectorX q;
  VectorX trial;
  VectorX step;
  /// Per joint: 1 when held on a limit for this step, and the step that puts it there.
  VectorX held;
  VectorX heldStep;
  /// X_BT at q.
  Pose pose = Pose::Identity();
  Pose trialPose = Pose::Identity();
  Vector6 error = Vector6::Zero();
  Vector6 trialError = Vector6::Zero();
  /// The error left for the free joints.
  Vector6 residual = Vector6::Zero();
  Matrix6 normal = Matrix6::Zero();
  Eigen::LLT<Matrix6> llt;
  Eigen::LDLT<Matrix6> ldlt;
};

/// One Levenberg-Marquardt descent of `problem` from w.q (within the limits): each iteration
/// solves (J J^T + lambda I) y = e and steps dq = J^T y (at most 0.6 rad or m per joint); a joint
/// whose step would cross a limit is held on it and the others re-solved; the step is kept only
/// if the squared error decreases, and lambda follows the gain ratio (Nielsen 1999). The descent
/// ends converged, after 60 iterations, when lambda saturates, or when the error stagnates
/// (less than halved over 3 iterations while still above 1e-6: a local minimum or a limit).
/// Counts iterations in `search` and stops with it. Returns true when converged (w.q is then a
/// solution and w.pose its tip pose). noexcept and allocation-free.
bool dlsDescend(const IkProblem& problem, DlsWorkspace& w, IkSearch& search) noexcept;

}  // namespace lang2manip
