#include "lang2manip/kinematics/ik_solver.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "lang2manip/core/error.hpp"
#include "lang2manip/kinematics/dls_ik_solver.hpp"
#include "lang2manip/kinematics/kdl_ik_solver.hpp"
#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {
namespace {

constexpr double kUnitTolerance = 1e-6;

constexpr std::array<IkSolverEntry, 3> kRegistry = {{
    {"dls", "damped least squares (Levenberg-Marquardt) with joint-limit projection and random "
            "restarts under the time budget (default)", &makeDlsIkSolver},
    {"kdl", "KDL ChainIkSolverPos_NR_JL, one attempt from the seed (the paper's solver)",
     &makeKdlIkSolver},
    {"kdl_restarts", "KDL ChainIkSolverPos_NR_JL with random restarts under the time budget",
     &makeKdlRestartsIkSolver},
}};

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

bool allFinite(const Vector3& v) { return v.allFinite(); }

const Manipulator* findManipulator(const RobotModel& model, const std::string& name) {
  const auto& manipulators = model.semantics().manipulators;
  if (name.empty()) return manipulators.empty() ? nullptr : &manipulators.front();
  for (const Manipulator& manipulator : manipulators) {
    if (manipulator.name == name) return &manipulator;
  }
  std::vector<std::string> names;
  for (const Manipulator& manipulator : manipulators) names.push_back(manipulator.name);
  throw InputError("unknown manipulator \"" + name + "\" of robot \"" + model.name() +
                   "\"; valid manipulators: " + joined(names));
}

KinematicChain resolveChain(const IkRequest& request) {
  const RobotModel& model = *request.model;
  std::string base = request.baseLink;
  std::string tip = request.tipLink;
  if (base.empty() || tip.empty() || !request.manipulator.empty()) {
    const Manipulator* manipulator = findManipulator(model, request.manipulator);
    if (manipulator == nullptr) {
      throw InputError("robot \"" + model.name() +
                       "\" has no manipulator: give the IK chain's base and tip links");
    }
    if (base.empty()) base = manipulator->baseLink;
    if (tip.empty()) tip = manipulator->toolFrame;
  }
  return KinematicChain(model, base, tip);
}

void checkLimits(const RobotModel& model, const VectorX& lower, const VectorX& upper) {
  if (lower.size() != model.variableCount() || upper.size() != model.variableCount()) {
    throw InputError("IK joint limits have " + std::to_string(lower.size()) + " and " +
                     std::to_string(upper.size()) + " values; the robot has " +
                     std::to_string(model.variableCount()) + " joint variables");
  }
  for (Eigen::Index i = 0; i < lower.size(); ++i) {
    if (std::isnan(lower[i]) || std::isnan(upper[i]) || lower[i] > upper[i]) {
      throw InputError("IK joint limits of \"" + model.variableNames()[static_cast<std::size_t>(i)] +
                       "\" are not an interval (lower > upper or NaN)");
    }
  }
}

Vector3 checkedAxis(const Vector3& axis, const std::string& what) {
  if (!allFinite(axis) || axis.norm() < kUnitTolerance) {
    throw InputError("IK target " + what + " must be a finite, non-zero vector");
  }
  return axis.normalized();
}

IkTarget checkedTarget(const IkTarget& target) {
  IkTarget checked = target;
  if (!allFinite(target.position)) throw InputError("IK target position is not finite");
  if (target.kind == IkTarget::Kind::kPose) {
    if (!target.orientation.coeffs().allFinite()) {
      throw InputError("IK target orientation is not finite");
    }
    const double norm = target.orientation.norm();
    if (std::abs(norm - 1.0) > kUnitTolerance) {
      throw InputError("IK target orientation is not a unit quaternion (norm " +
                       std::to_string(norm) + ", must be 1 within 1e-6)");
    }
    checked.orientation.normalize();
  } else {
    checked.approachAxis = checkedAxis(target.approachAxis, "approach axis");
    checked.toolAxis = checkedAxis(target.toolAxis, "tool axis");
  }
  return checked;
}

void checkScalars(const IkRequest& request) {
  if (!(request.timeoutSeconds > 0.0) || !std::isfinite(request.timeoutSeconds)) {
    throw InputError("IK time budget must be > 0 seconds and finite (got " +
                     numberText(request.timeoutSeconds) + ")");
  }
  if (!(request.positionTolerance > 0.0) || !(request.orientationTolerance > 0.0)) {
    throw InputError("IK tolerances must be > 0");
  }
  if (request.solutionCount < 1) throw InputError("IK solution count must be >= 1");
  if (request.maxAttempts < 0) throw InputError("IK attempt cap must be >= 0 (0 = none), got " + std::to_string(request.maxAttempts));
}

VectorX restricted(const KinematicChain& chain, const VectorX& full) {
  VectorX values(chain.dof());
  chain.gather(full, values);
  return values;
}

/// Full configurations from chain solutions, nearest to the seed first.
std::vector<VectorX> fullSolutions(const KinematicChain& chain, const VectorX& seed,
                                   const std::vector<VectorX>& chainSolutions) {
  const VectorX chainSeed = restricted(chain, seed);
  std::vector<VectorX> sorted = chainSolutions;
  std::stable_sort(sorted.begin(), sorted.end(), [&](const VectorX& a, const VectorX& b) {
    return (a - chainSeed).squaredNorm() < (b - chainSeed).squaredNorm();
  });
  std::vector<VectorX> full;
  for (const VectorX& solution : sorted) {
    full.push_back(seed);
    chain.scatter(solution, full.back());
  }
  return full;
}

}  // namespace

IkTarget IkTarget::pose(const Vector3& position, const Quaternion& orientation) {
  IkTarget target;
  target.position = position;
  target.orientation = orientation;
  return target;
}

IkTarget IkTarget::pose(const Pose& X_BT) {
  return pose(X_BT.translation(), Quaternion(X_BT.linear()));
}

IkTarget IkTarget::positionAndAxis(const Vector3& position, const Vector3& approachAxis,
                                   const Vector3& toolAxis) {
  IkTarget target;
  target.kind = Kind::kPositionAndAxis;
  target.position = position;
  target.approachAxis = approachAxis;
  target.toolAxis = toolAxis;
  return target;
}

std::string ikStatusName(IkStatus status) {
  switch (status) {
    case IkStatus::kSuccess: return "success";
    case IkStatus::kTimeout: return "timeout";
    case IkStatus::kNoConvergence: return "no convergence";
    case IkStatus::kJointLimits: return "joint limits";
    case IkStatus::kUnreachable: return "unreachable";
  }
  return "unknown";
}

void ikTargetError(const IkTarget& target, const Pose& X_BT, double& positionError,
                   double& orientationError) noexcept {
  positionError = (target.position - X_BT.translation()).norm();
  if (target.kind == IkTarget::Kind::kPose) {
    orientationError = target.orientation.angularDistance(Quaternion(X_BT.linear()));
  } else {
    const Vector3 axis = X_BT.linear() * target.toolAxis;
    orientationError = std::atan2(axis.cross(target.approachAxis).norm(),
                                  axis.dot(target.approachAxis));
  }
}

IkResult IkSolver::solve(const IkRequest& request) const {
  const auto start = std::chrono::steady_clock::now();
  if (request.model == nullptr) throw InputError("IK request has no robot model");
  const RobotModel& model = *request.model;
  const KinematicChain chain = resolveChain(request);
  model.checkConfiguration(request.seed, "IK seed");
  const VectorX& lower = request.lowerLimits.size() == 0 ? model.lowerLimits() : request.lowerLimits;
  const VectorX& upper = request.upperLimits.size() == 0 ? model.upperLimits() : request.upperLimits;
  checkLimits(model, lower, upper);
  checkScalars(request);
  const IkProblem problem{model,
                          chain,
                          checkedTarget(request.target),
                          restricted(chain, request.seed),
                          restricted(chain, lower),
                          restricted(chain, upper),
                          StopCondition::afterSeconds(request.timeoutSeconds).orElse(request.stop),
                          request.positionTolerance,
                          request.orientationTolerance,
                          request.solutionCount,
                          request.randomSeed,
                          request.maxAttempts};
  IkResult result;
  if (problem.target.position.norm() > chain.reach() + request.positionTolerance) {
    result.status = IkStatus::kUnreachable;
    result.message = "target is " + std::to_string(problem.target.position.norm()) +
                     " m from the base of chain " + chain.baseLink() + " -> " + chain.tipLink() +
                     ", which reaches at most " + std::to_string(chain.reach()) + " m";
  } else {
    result = doSolve(problem);
    result.solutions = fullSolutions(chain, request.seed, result.solutions);
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::span<const IkSolverEntry> ikSolverRegistry() { return kRegistry; }

std::vector<std::string> ikSolverNames() {
  std::vector<std::string> names;
  for (const IkSolverEntry& entry : kRegistry) names.emplace_back(entry.name);
  return names;
}

std::string defaultIkSolverName() { return std::string(kRegistry.front().name); }

std::unique_ptr<IkSolver> makeIkSolver(const std::string& name) {
  for (const IkSolverEntry& entry : kRegistry) {
    if (entry.name == name) return entry.make();
  }
  throw InputError("unknown IK solver \"" + name + "\"; valid solvers: " + joined(ikSolverNames()));
}

}  // namespace lang2manip
