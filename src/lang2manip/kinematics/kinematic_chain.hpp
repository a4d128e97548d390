#pragma once
/// @file The serial chain of joints between a base link and a tip link of a RobotModel, with an
/// allocation-free pose and Jacobian for inner loops (IK). Immutable once built, so every const
/// method is thread-safe.

#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

/// A 6 x n Jacobian: linear velocity rows on top, angular velocity rows below.
using Jacobian6 = Eigen::Matrix<double, 6, Eigen::Dynamic>;

/// One joint on the path from the base link to the tip link.
struct ChainJoint {
  /// Index in RobotModel::joints().
  int joint = -1;
  JointType type = JointType::kFixed;
  /// X_PJ, the joint frame in its parent link.
  Pose origin = Pose::Identity();
  Vector3 axis = Vector3::UnitZ();
  /// 0, 1 or 2 when `axis` is exactly +x, +y or +z (a faster rotation), otherwise -1.
  int coordinateAxis = -1;
  /// Chain variable that drives this joint (-1 for a fixed joint).
  int variable = -1;
  /// Joint value = multiplier * chain variable + offset (1 and 0 unless the joint is a mimic).
  double multiplier = 1.0;
  double offset = 0.0;
};

/// See the file comment. Chain variables are the robot variables that move some joint of the
/// path (a mimic joint adds its source variable), in base-to-tip order.
class KinematicChain {
 public:
  /// Throws InputError listing the links when `baseLink` or `tipLink` is unknown, and when the
  /// base is not a proper ancestor of the tip or no joint of the path moves.
  KinematicChain(const RobotModel& model, const std::string& baseLink, const std::string& tipLink);

  [[nodiscard]] const std::string& baseLink() const noexcept { return baseLink_; }
  [[nodiscard]] const std::string& tipLink() const noexcept { return tipLink_; }
  /// Number of chain variables.
  [[nodiscard]] int dof() const noexcept { return static_cast<int>(variables_.size()); }
  /// Robot variable index of each chain variable.
  [[nodiscard]] const std::vector<int>& variables() const noexcept { return variables_; }
  /// The joints of the path, base to tip (fixed joints included).
  [[nodiscard]] const std::vector<ChainJoint>& joints() const noexcept { return joints_; }
  /// An upper bound on the distance between the base origin and the tip origin.
  [[nodiscard]] double reach() const noexcept { return reach_; }
  /// True when some joint of the chain is a mimic (or two joints share a variable).
  [[nodiscard]] bool hasCoupledJoints() const noexcept { return coupled_; }

  /// X_BT for chain configuration `qc` (dof() values, not checked).
  [[nodiscard]] Pose pose(const VectorX& qc) const noexcept;

  /// X_BT and the geometric Jacobian of the tip origin in the base frame (6 x dof(), resized by
  /// the caller beforehand). Allocation-free.
  void poseAndJacobian(const VectorX& qc, Pose& X_BT, Jacobian6& jacobian) const noexcept;

  /// The chain variables of a full robot configuration.
  void gather(const VectorX& q, VectorX& qc) const noexcept;
  /// Writes the chain variables `qc` into the full robot configuration `q`.
  void scatter(const VectorX& qc, VectorX& q) const noexcept;

 private:
  void addJoint(const RobotModel& model, int joint);

  std::string baseLink_;
  std::string tipLink_;
  std::vector<ChainJoint> joints_;
  std::vector<int> variables_;
  double reach_ = 0.0;
  bool coupled_ = false;
};

}  // namespace lang2manip
