#pragma once
/// @file An immutable kinematic and geometric robot description (links, joints, limits,
/// geometry, semantics). Built once by a reader; shared read-only, so every const method is
/// thread-safe. Per-call state (FK results) lives in the kinematics module's workspaces.

#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/geometry.hpp"
#include "lang2manip/model/robot_semantics.hpp"

namespace lang2manip {

enum class JointType { kRevolute, kContinuous, kPrismatic, kFixed, kFloating, kPlanar };

/// "revolute", "continuous", ...
std::string jointTypeName(JointType type);

/// The velocity limit trajectories are timed with for a joint whose URDF velocity limit is zero or
/// absent (rad/s, or m/s for prismatic joints). The URDF reader warns once per such joint.
inline constexpr double kDefaultJointVelocityLimit = 1.0;
/// Velocity limits below this (rad/s or m/s) are refused: a motion of such a joint would take days.
inline constexpr double kSmallestJointVelocityLimit = 1e-4;

/// A joint's limits in SI units (rad or m; per second, per second squared, ...).
struct JointLimits {
  double lower = 0.0;
  double upper = 0.0;
  /// 0 when the URDF gives none (see kDefaultJointVelocityLimit).
  double velocity = 0.0;
  double effort = 0.0;
  /// True when lower/upper come from a URDF safety_controller (soft limits).
  bool soft = false;
  /// Maximum acceleration; nullopt = unknown (URDF has no such field: it comes from a
  /// joint_limits.yaml, see joint_limits_reader.hpp). Positive and finite when set.
  std::optional<double> acceleration = std::nullopt;
  /// Maximum jerk; nullopt = unknown. Positive and finite when set.
  std::optional<double> jerk = std::nullopt;
};

/// q_this = multiplier * q_source + offset.
struct JointMimic {
  std::string sourceJoint;
  double multiplier = 1.0;
  double offset = 0.0;
};

struct Joint {
  std::string name;
  JointType type = JointType::kFixed;
  std::string parentLink;
  std::string childLink;
  /// X_PJ: the joint frame in the parent link frame (the child frame when q = 0).
  Pose origin = Pose::Identity();
  /// Unit axis in the joint frame.
  Vector3 axis = Vector3::UnitZ();
  JointLimits limits;
  std::optional<JointMimic> mimic;
};

struct Link {
  std::string name;
  std::vector<Shape> visuals;
  std::vector<Shape> collisions;
};

/// Throws InputError at `where` unless every shape of `link` is within the model length range
/// (requireShapeInRange in geometry.hpp).
void requireLinkInRange(const Link& link, const SourceLocation& where);

/// The plain data a RobotModel is built from; readers fill it, RobotModel validates it.
struct RobotModelData {
  std::string name;
  std::vector<Link> links;
  std::vector<Joint> joints;
  RobotSemantics semantics;
  /// The file the model was read from (empty when built in code).
  std::string source;
};

/// See the file comment. Links and joints are stored parent before child whatever their order
/// in the file. Configuration vectors hold one value per *variable*: each movable joint that is
/// not a mimic, in that order.
class RobotModel {
 public:
  /// Validates and orders `data`. Throws InputError (naming `data.source`) on duplicate names,
  /// joints that reference unknown links, a link with two parents, a cycle, several roots,
  /// non-finite numbers, lower > upper limits, an acceleration or jerk limit that is not
  /// positive, a zero axis, or a mimic of an unknown joint.
  explicit RobotModel(RobotModelData data);

  [[nodiscard]] const std::string& name() const noexcept { return data_.name; }
  [[nodiscard]] const std::string& source() const noexcept { return data_.source; }
  [[nodiscard]] const std::vector<Link>& links() const noexcept { return data_.links; }
  [[nodiscard]] const std::vector<Joint>& joints() const noexcept { return data_.joints; }
  [[nodiscard]] const RobotSemantics& semantics() const noexcept { return data_.semantics; }

  /// Index of the root link (always 0).
  [[nodiscard]] int rootLink() const noexcept { return 0; }
  /// Index of the joint whose child is link `link` (-1 for the root).
  [[nodiscard]] int parentJoint(int link) const { return parentJoint_[static_cast<std::size_t>(link)]; }
  /// Index of link `name`, or nullopt.
  [[nodiscard]] std::optional<int> findLink(const std::string& name) const;
  /// Index of link `name`; throws InputError listing the links when unknown.
  [[nodiscard]] int linkIndex(const std::string& name) const;
  [[nodiscard]] std::optional<int> findJoint(const std::string& name) const;
  /// Index of joint `name`; throws InputError listing the joints when unknown.
  [[nodiscard]] int jointIndex(const std::string& name) const;
  /// Link indices of joint `joint`'s child and parent.
  [[nodiscard]] int childLinkOf(int joint) const noexcept {
    return childLink_[static_cast<std::size_t>(joint)];
  }
  [[nodiscard]] int parentLinkOf(int joint) const noexcept {
    return parentLink_[static_cast<std::size_t>(joint)];
  }

  /// Number of configuration variables.
  [[nodiscard]] int variableCount() const noexcept { return static_cast<int>(variables_.size()); }
  /// Joint index of each variable.
  [[nodiscard]] const std::vector<int>& variableJoints() const noexcept { return variables_; }
  /// Variable index of joint `joint` (-1 for fixed joints; a mimic's *source* variable for
  /// mimic joints is found through mimicSource()).
  [[nodiscard]] int variableOfJoint(int joint) const { return variableOfJoint_[static_cast<std::size_t>(joint)]; }
  /// For a mimic joint, the variable it follows; -1 otherwise.
  [[nodiscard]] int mimicSource(int joint) const { return mimicSource_[static_cast<std::size_t>(joint)]; }
  /// Names of the variables (their joint names).
  [[nodiscard]] std::vector<std::string> variableNames() const;
  /// Index of the variable of joint `name`; throws InputError listing the variables if unknown.
  [[nodiscard]] int variableIndex(const std::string& name) const;
  [[nodiscard]] const VectorX& lowerLimits() const noexcept { return lower_; }
  [[nodiscard]] const VectorX& upperLimits() const noexcept { return upper_; }
  /// The URDF's velocity limit of each variable (or a joint_limits.yaml's); 0 where none is given.
  [[nodiscard]] const VectorX& velocityLimits() const noexcept { return velocity_; }
  /// The acceleration limit of variable `variable`; nullopt when unknown (no joint limits file
  /// gave one; planning then uses its default, see JointLimitDefaults).
  [[nodiscard]] std::optional<double> accelerationLimit(int variable) const;
  /// The jerk limit of variable `variable`; nullopt when unknown.
  [[nodiscard]] std::optional<double> jerkLimit(int variable) const;

  /// Replaces the limits of joint `joint` (an index of joints()), checked as the constructor
  /// checks them; a continuous joint keeps its [-pi, pi] range. Throws InputError (naming
  /// source()) when they are invalid; the model is then unchanged. For readers completing a model
  /// before it is shared (joint_limits_reader.hpp): not thread-safe, and a shared model
  /// (RobotModelPtr points to const) cannot be changed.
  void setJointLimits(int joint, const JointLimits& limits);

  /// MoveIt's default_velocity_scaling_factor and default_acceleration_scaling_factor of the
  /// robot's joint_limits.yaml, in (0, 1]; nullopt where it gave none. Runs use them unless a
  /// request names its own scaling.
  struct ScalingDefaults {
    std::optional<double> velocity;
    std::optional<double> acceleration;
  };
  [[nodiscard]] const ScalingDefaults& scalingDefaults() const noexcept { return scalingDefaults_; }
  /// Sets scalingDefaults() (a reader completing the model, as setJointLimits()).
  void setScalingDefaults(const ScalingDefaults& defaults) { scalingDefaults_ = defaults; }

  /// Value of joint `joint` for configuration `q` (mimics applied; 0 for fixed joints).
  [[nodiscard]] double jointValue(int joint, const VectorX& q) const noexcept;

  /// X_PC: the pose of joint `joint`'s child link in its parent link for joint value `value`.
  [[nodiscard]] Pose jointTransform(int joint, double value) const noexcept;

  /// X_RL of every link for configuration `q` (allocates; the kinematics module has the
  /// allocation-free version for inner loops). `q` is checked as in checkConfiguration().
  [[nodiscard]] std::vector<Pose> linkPoses(const VectorX& q) const;

  /// The midpoint of the limits (the usual neutral configuration).
  [[nodiscard]] VectorX middleConfiguration() const;

  /// Throws InputError unless `q` has variableCount() finite values (`what` names it).
  void checkConfiguration(const VectorX& q, const std::string& what) const;

  /// One description per variable of `q` outside its joint's limits by more than `tolerance`
  /// ("panda_joint4 = 0.1 is above its upper limit -0.0698"); continuous joints have none.
  /// Empty when `q` is within the limits. `q` is checked as in checkConfiguration().
  [[nodiscard]] std::vector<std::string> limitViolations(const VectorX& q, double tolerance = 1e-9) const;

  /// The named state `name` (SRDF group_state) as a full configuration starting from the middle
  /// configuration; throws InputError listing the named states when unknown.
  [[nodiscard]] VectorX namedConfiguration(const std::string& name) const;

 private:
  void orderTopologically();
  void indexVariables();

  RobotModelData data_;
  std::unordered_map<std::string, int> linkByName_;
  std::unordered_map<std::string, int> jointByName_;
  std::vector<int> parentJoint_;
  std::vector<int> childLink_;
  std::vector<int> parentLink_;
  std::vector<int> variables_;
  std::vector<int> variableOfJoint_;
  std::vector<int> mimicSource_;
  VectorX lower_;
  VectorX upper_;
  VectorX velocity_;
  ScalingDefaults scalingDefaults_;
};

using RobotModelPtr = std::shared_ptr<const RobotModel>;

}  // namespace lang2manip
