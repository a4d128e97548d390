#pragma once
/// @file The default IK solver: damped least squares (Levenberg-Marquardt) on the 6D pose error
/// with joint limits by projection, adaptive damping and random restarts under the time budget.

#include <memory>

#include "lang2manip/kinematics/ik_solver.hpp"

namespace lang2manip {

/// Levenberg-Marquardt IK (Levenberg 1944, Marquardt 1963; as damped least squares for
/// manipulators: Wampler 1986, Nakamura & Hanafusa 1986). Each iteration solves
/// (J J^T + lambda I) y = e, steps dq = J^T y, projects q + dq onto the joint limits and keeps the
/// step only if the squared error decreased (lambda shrinks on success and grows on failure).
/// An attempt ends when converged, after a fixed number of iterations, or when the damping
/// saturates (stuck at a limit or a local minimum); the next attempt starts from a uniformly
/// random configuration (the first from the seed), until enough distinct solutions are found or
/// the time budget runs out. For an approach-axis target the angular rows are projected onto the
/// plane orthogonal to the current tool axis (rotation about it is free). The inner loop is
/// noexcept and allocation-free. Stateless: thread-safe.
class DlsIkSolver final : public IkSolver {
 public:
  [[nodiscard]] std::string name() const override { return "dls"; }

 protected:
  [[nodiscard]] IkResult doSolve(const IkProblem& problem) const override;
};

/// Factory for the registry.
std::unique_ptr<IkSolver> makeDlsIkSolver();

}  // namespace lang2manip
