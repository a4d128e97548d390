#pragma once
/// @file The default IK solver: damped least squares (Levenberg-Marquardt) on the 6D pose error
/// with joint limits as an active set, adaptive damping and random restarts under the time budget.

#include <memory>

#include "lang2manip/kinematics/ik_solver.hpp"

namespace lang2manip {

/// Levenberg-Marquardt IK (Levenberg 1944, Marquardt 1963; as damped least squares for
/// manipulators: Wampler 1986, Nakamura & Hanafusa 1986): descents by dlsDescend() (see
/// dls_descent.hpp: active-set joint limits, gain-ratio damping, early end on stagnation), the
/// first from the seed and each next one from a uniformly random configuration within the limits
/// (seeded by the request), until enough distinct solutions are found or the time budget runs
/// out. For an approach-axis target the angular rows are projected onto the plane orthogonal to
/// the current tool axis (rotation about it is free). Stateless: thread-safe.
class DlsIkSolver final : public IkSolver {
 public:
  [[nodiscard]] std::string name() const override { return "dls"; }

 protected:
  [[nodiscard]] IkResult doSolve(const IkProblem& problem) const override;
};

/// Factory for the registry.
std::unique_ptr<IkSolver> makeDlsIkSolver();

}  // namespace lang2manip
