#pragma once
/// @file Inverse kinematics behind one interface, and the registry of solvers by name.
///
/// A solver keeps no state between calls that changes its answers: every solve() builds its
/// per-call state (chain, workspace, random generator), and the KDL solvers reuse per-thread KDL
/// chains and solver objects, so one solver object may serve many threads at once.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lang2manip/core/stop_condition.hpp"
#include "lang2manip/core/types.hpp"
#include "lang2manip/kinematics/kinematic_chain.hpp"
#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

/// What the tip frame must reach, in the chain's base frame.
struct IkTarget {
  enum class Kind {
    /// Full 6D pose: position and orientation.
    kPose,
    /// Position, and the tip's `toolAxis` pointing along `approachAxis`; free rotation about it.
    kPositionAndAxis,
  };
  Kind kind = Kind::kPose;
  Vector3 position = Vector3::Zero();
  /// Orientation of the tip (kPose); must be a unit quaternion within 1e-6.
  Quaternion orientation = Quaternion::Identity();
  /// kPositionAndAxis: the direction, in the base frame, the tool axis must point along.
  Vector3 approachAxis = Vector3::UnitZ();
  /// kPositionAndAxis: the axis of the tip frame that must point along approachAxis.
  Vector3 toolAxis = Vector3::UnitZ();

  /// A full pose target.
  static IkTarget pose(const Vector3& position, const Quaternion& orientation);
  /// A full pose target from X_BT.
  static IkTarget pose(const Pose& X_BT);
  /// A position with the tip's `toolAxis` along `approachAxis` (both normalized by solve()).
  static IkTarget positionAndAxis(const Vector3& position, const Vector3& approachAxis,
                                  const Vector3& toolAxis = Vector3::UnitZ());
};

/// One IK query. Only `model`, `target` and `seed` have no usable default.
struct IkRequest {
  /// The robot (must outlive the call).
  const RobotModel* model = nullptr;
  /// Chain base link; empty = the manipulator's baseLink.
  std::string baseLink;
  /// Chain tip (any link or frame); empty = the manipulator's toolFrame.
  std::string tipLink;
  /// Manipulator whose base and tool frame are the defaults; empty = the first one.
  std::string manipulator;
  IkTarget target;
  /// Full robot configuration (variableCount() values): the start of the search, and the source
  /// of the values of every variable outside the chain.
  VectorX seed;
  /// Joint limits (full robot size); empty = the model's.
  VectorX lowerLimits;
  VectorX upperLimits;
  /// Time budget in seconds (> 0).
  double timeoutSeconds = 0.005;
  /// Extra condition (e.g. a cancel flag) that also ends the search.
  StopCondition stop = StopCondition::never();
  /// Position tolerance (m) and orientation tolerance (rad), as in the TRAC-IK protocol.
  double positionTolerance = 1e-5;
  double orientationTolerance = 1e-5;
  /// Number of distinct solutions wanted (>= 1); the search stops when that many are found.
  /// Finding fewer before the time budget runs out is still a success.
  int solutionCount = 1;
  /// Seed of the solver's random restarts (same seed, same sequence of restarts).
  std::uint64_t randomSeed = 1;
  /// At most this many attempts (descents) when > 0, whatever time is left: a search whose
  /// answer must not depend on the machine's speed (0 = only the time budget ends it).
  int maxAttempts = 0;
};

enum class IkStatus {
  kSuccess,
  /// The time budget ran out (or the stop condition fired) before any solution was found.
  kTimeout,
  /// The solver ended its search (e.g. a single attempt) without converging.
  kNoConvergence,
  /// The best attempt ended pressed against a joint limit: the target needs a joint beyond it.
  kJointLimits,
  /// The target is farther from the chain base than the chain can reach.
  kUnreachable,
};

/// "success", "timeout", ...
std::string ikStatusName(IkStatus status);

struct IkResult {
  IkStatus status = IkStatus::kNoConvergence;
  /// Why it failed, for people (empty on success).
  std::string message;
  /// Full robot configurations, nearest to the seed first; variables outside the chain are the
  /// seed's. Non-empty exactly when status == kSuccess.
  std::vector<VectorX> solutions;
  /// Solver iterations (0 for solvers that do not report them, such as KDL) and attempts
  /// (restarts + 1) over the whole call.
  int iterations = 0;
  int attempts = 0;
  /// Wall time of the call in seconds.
  double seconds = 0.0;
  /// Errors of the best configuration found (of solutions[0] on success).
  double positionError = 0.0;
  double orientationError = 0.0;
};

/// A request after validation, as the solvers see it: chain resolved, target normalized, limits
/// and seed restricted to the chain variables, stop condition combined with the deadline.
struct IkProblem {
  const RobotModel& model;
  const KinematicChain& chain;
  IkTarget target;
  VectorX seed;
  VectorX lower;
  VectorX upper;
  StopCondition stop;
  double positionTolerance;
  double orientationTolerance;
  int solutionCount;
  std::uint64_t randomSeed;
  /// 0 = no cap (see IkRequest::maxAttempts).
  int maxAttempts = 0;
};

/// Position error (m) and orientation error (rad) of tip pose `X_BT` against `target`.
void ikTargetError(const IkTarget& target, const Pose& X_BT, double& positionError,
                   double& orientationError) noexcept;

/// The IK interface (non-virtual interface: solve() checks, doSolve() solves). Implementations
/// are final and keep no state between calls; see the file comment for thread-safety.
class IkSolver {
 public:
  virtual ~IkSolver() = default;

  /// The registry name.
  [[nodiscard]] virtual std::string name() const = 0;

  /// Solves `request`. Throws InputError for bad input: no model, unknown manipulator or link
  /// names (listing the valid ones), a base that is not an ancestor of the tip, a seed or limits
  /// of the wrong size or not finite, lower > upper, a non-finite target, a non-unit
  /// quaternion, a zero approach or tool axis, a time budget not > 0, non-positive tolerances
  /// or solution count. Expected failures (timeout, unreachable, ...) come back as a status.
  [[nodiscard]] IkResult solve(const IkRequest& request) const;

 protected:
  /// Solves a validated problem. Fills status, message, solutions (chain variables only, in
  /// any order), iterations, attempts and the errors; solve() does the rest.
  [[nodiscard]] virtual IkResult doSolve(const IkProblem& problem) const = 0;
};

/// An entry of the compile-time registry.
struct IkSolverEntry {
  std::string_view name;
  std::string_view description;
  std::unique_ptr<IkSolver> (*make)();
};

/// Every registered solver, the default first.
std::span<const IkSolverEntry> ikSolverRegistry();

/// Names of the registered solvers, the default first.
std::vector<std::string> ikSolverNames();

/// Name of the default solver ("dls").
std::string defaultIkSolverName();

/// A new solver by name; throws InputError listing the valid names when unknown.
std::unique_ptr<IkSolver> makeIkSolver(const std::string& name);

}  // namespace lang2manip
