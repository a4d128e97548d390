#pragma once
/// @file Reads MoveIt's joint_limits.yaml and applies it to a RobotModel: the acceleration (and
/// jerk) limits a URDF cannot hold, and velocity, position and effort limits over the URDF's.
///
/// The format (MoveIt's `config/joint_limits.yaml`):
/// ```yaml
/// default_velocity_scaling_factor: 0.1        # optional, in (0, 1]; a run's default scaling
/// default_acceleration_scaling_factor: 0.1    # optional, in (0, 1]; a run's default scaling
/// joint_limits:
///   panda_joint1:
///     has_velocity_limits: true
///     max_velocity: 2.175                     # rad/s or m/s
///     has_acceleration_limits: true
///     max_acceleration: 15.0                  # rad/s^2 or m/s^2
///     has_jerk_limits: false                  # max_jerk: rad/s^3 or m/s^3
///     has_position_limits: true
///     min_position: !degrees -166             # !degrees on any angle: converted to radians
///     max_position: !degrees 166
///     has_effort_limits: true
///     max_effort: 87                          # Nm or N
/// ```
/// A limit is used only when its `has_*_limits` flag is true, and then its value(s) must be
/// given. A value whose flag is false or absent is ignored with a warning (as MoveIt 2 ignores
/// it). ros2_control's keys for soft limits and deceleration (has_soft_limits, k_position,
/// k_velocity, soft_lower_limit, soft_upper_limit, has_deceleration_limits, max_deceleration,
/// angle_wraparound) are accepted and ignored; any other key is an error. The whole may sit under
/// one `robot_description_planning:` key, as MoveIt 2 packages write it.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

/// One joint's entry, values in radians or metres (a `!degrees` value converted); each value is
/// nullopt unless its `has_*_limits` flag is true.
struct JointLimitsEntry {
  std::string joint;
  /// The line of the joint's name in the file (0 when unknown).
  int line = 0;
  std::optional<double> maxVelocity;
  std::optional<double> maxAcceleration;
  std::optional<double> maxJerk;
  std::optional<double> minPosition;
  std::optional<double> maxPosition;
  std::optional<double> maxEffort;
  /// The line of a value the file gave in degrees (0 when none): an error on a prismatic joint.
  int degreesLine = 0;
};

/// A joint_limits.yaml as read: checked on its own (numbers, flags, units), not yet against a
/// robot.
struct JointLimitsFile {
  /// The file name used in messages.
  std::string source;
  /// In file order.
  std::vector<JointLimitsEntry> joints;
  /// MoveIt's defaults for scaling a request's limits, in (0, 1]: applyJointLimits() puts them
  /// on the model (RobotModel::scalingDefaults()), where runs take them as MoveIt does.
  std::optional<double> defaultVelocityScalingFactor;
  std::optional<double> defaultAccelerationScalingFactor;
};

/// Reads a joint_limits.yaml. Throws InputError naming the file, the line and the key path for: a
/// missing, unreadable or malformed file; a top level that is not a map, has no `joint_limits`
/// map or has another key; a joint entry that is not a map, has an unknown key or is given
/// twice; a `has_*_limits` that is not true or false, or is true without its value(s); a value
/// that is not a finite number (`.inf`, `.nan` included); a maximum velocity, acceleration, jerk
/// or effort that is not positive; min_position above max_position; a scaling factor outside
/// (0, 1]; a tag other than `!degrees` or `!radians`, or `!degrees` on an effort or a factor.
/// Logs a warning for each value ignored because its flag is false or absent.
JointLimitsFile readJointLimitsFile(const std::filesystem::path& file);

/// Applies `limits` to `model` (before the model is shared; see RobotModel::setJointLimits):
/// - velocity: replaced by max_velocity;
/// - acceleration and jerk: set from max_acceleration and max_jerk;
/// - position: narrowed to [min_position, max_position] (times `lengthScale` for prismatic joints,
///   as the URDF reader scales them); a bound beyond the URDF's is not used, with a warning, so
///   the URDF's range is never widened; on a continuous joint, ignored with a warning;
/// - effort: replaced by max_effort.
/// Joints that are not variables (mimic, fixed) take the limits too, with no effect on planning.
/// Throws InputError at the entry's file and line for a joint the model does not have (listing
/// the model's joints), and for a `!degrees` value on a prismatic joint; the model is unchanged
/// for the joints not yet applied when it throws.
void applyJointLimits(const JointLimitsFile& limits, RobotModel& model, double lengthScale = 1.0);

}  // namespace lang2manip
