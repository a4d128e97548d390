#pragma once
/// @file KDL's Newton-Raphson IK with joint limits (ChainIkSolverPos_NR_JL), the paper's solver:
/// `kdl` makes one attempt from the seed, `kdl_restarts` restarts from random configurations
/// until the time budget runs out (the "KDL + random restarts" baseline of TRAC-IK).

#include <memory>

#include "lang2manip/kinematics/ik_solver.hpp"

namespace lang2manip {

/// KDL::ChainIkSolverPos_NR_JL (Smits, Bruyninckx, Aertbelien: KDL, the Orocos Kinematics and
/// Dynamics Library) on a KDL chain converted by makeKdlChain(), with KDL's default 100
/// iterations per attempt. Approach-axis targets are solved as full poses with the orientation
/// of the seed's tool frame turned onto the axis (KDL has no free-axis mode). The KDL chain and
/// solvers of a chain are built on a thread's first call for it and reused by that thread's later
/// calls (KDL's solvers keep internal buffers): thread-safe.
class KdlIkSolver final : public IkSolver {
 public:
  /// `restarts`: random restarts under the time budget (otherwise one attempt from the seed).
  explicit KdlIkSolver(bool restarts) : restarts_(restarts) {}

  [[nodiscard]] std::string name() const override { return restarts_ ? "kdl_restarts" : "kdl"; }

 protected:
  [[nodiscard]] IkResult doSolve(const IkProblem& problem) const override;

 private:
  bool restarts_;
};

/// Factories for the registry.
std::unique_ptr<IkSolver> makeKdlIkSolver();
std::unique_ptr<IkSolver> makeKdlRestartsIkSolver();

}  // namespace lang2manip
