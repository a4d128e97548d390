#pragma once
/// @file Forward kinematics of every link of a RobotModel.
/// The model is immutable and shared; KinematicsData is the per-thread workspace (allocated once
/// for a model, never per call), as in Pinocchio's Model/Data split.

#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

/// Results of computeForwardKinematics(): X_RL for every link L, in the robot root frame R.
/// Not thread-safe; give each thread its own.
class KinematicsData {
 public:
  explicit KinematicsData(const RobotModel& model);

  /// X_RL, indexed like RobotModel::links().
  std::vector<Pose> linkPoses;
  /// Value of every joint (mimics applied), indexed like RobotModel::joints().
  std::vector<double> jointValues;
};

/// Fills `data` for configuration `q` (variableCount() values, not checked: inner-loop call).
void computeForwardKinematics(const RobotModel& model, const VectorX& q,
                              KinematicsData& data) noexcept;

/// Convenience: X_RL of link `link` for `q`. Checks its arguments; throws InputError for an
/// unknown link (listing the links) or a configuration of the wrong size or with NaN.
Pose computeLinkPose(const RobotModel& model, const VectorX& q, const std::string& link);

}  // namespace lang2manip
