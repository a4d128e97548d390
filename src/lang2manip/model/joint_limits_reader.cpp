#include "lang2manip/model/joint_limits_reader.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <numbers>
#include <set>
#include <utility>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/model/moveit_yaml.hpp"

namespace lang2manip {
namespace {

using moveit_yaml::YamlValue;

constexpr double kRadiansPerDegree = std::numbers::pi / 180.0;
/// A position bound this close to the URDF's counts as the URDF's (360 degrees against 6.2831853).
constexpr double kPositionTolerance = 1e-6;

/// One limit kind: its flag, its value keys and how the values are checked.
struct LimitKind {
  const char* flag;
  std::vector<const char*> keys;
  std::vector<std::optional<double> JointLimitsEntry::*> members;
  bool angle;     // may be given in !degrees
  bool positive;  // a maximum: must be above zero
};

const std::array<LimitKind, 5>& limitKinds() {
  static const std::array<LimitKind, 5> kinds{{
      {"has_velocity_limits", {"max_velocity"}, {&JointLimitsEntry::maxVelocity}, true, true},
      {"has_acceleration_limits", {"max_acceleration"}, {&JointLimitsEntry::maxAcceleration}, true, true},
      {"has_jerk_limits", {"max_jerk"}, {&JointLimitsEntry::maxJerk}, true, true},
      {"has_position_limits", {"min_position", "max_position"},
       {&JointLimitsEntry::minPosition, &JointLimitsEntry::maxPosition}, true, false},
      {"has_effort_limits", {"max_effort"}, {&JointLimitsEntry::maxEffort}, false, true},
  }};
  return kinds;
}

/// ros2_control's keys of a joint's entry that lang2manip has no use for.
const std::set<std::string>& ignoredKeys() {
  static const std::set<std::string> keys{"has_soft_limits", "k_position",       "k_velocity",
                                          "soft_lower_limit", "soft_upper_limit", "has_deceleration_limits",
                                          "max_deceleration", "angle_wraparound"};
  return keys;
}

std::string understoodKeys() {
  std::string keys;
  for (const LimitKind& kind : limitKinds()) {
    keys += std::string(keys.empty() ? "" : ", ") + kind.flag;
    for (const char* key : kind.keys) keys += std::string(", ") + key;
  }
  return keys;
}

/// A number, converted from degrees when tagged `!degrees` (only where `angle` allows it).
double numberOf(const YamlValue& value, bool angle, int& degreesLine) {
  const std::string& tag = value.tag();
  if (tag == "!degrees") {
    if (!angle) value.fail("!degrees applies to angles, not to this value");
    const int line = value.where().line;
    degreesLine = degreesLine == 0 ? line : std::min(degreesLine, line);
    return value.number() * kRadiansPerDegree;
  }
  const bool plain = tag == "?" || tag == "!" || tag == "!radians" ||
                     tag == "tag:yaml.org,2002:float" || tag == "tag:yaml.org,2002:int";
  if (!plain) value.fail("unknown tag " + tag + " (only !degrees and !radians are understood)");
  return value.number();
}

/// A map's entries by key name: the key's node and the value.
using KeyedEntries = std::map<std::string, std::pair<YamlValue, YamlValue>>;

/// The entries of a map, each key given once.
KeyedEntries uniqueEntries(const YamlValue& map) {
  KeyedEntries entries;
  for (const auto& [key, value] : map.entries()) {
    const std::string name = key.text("a name");
    if (const auto earlier = entries.find(name); earlier != entries.end()) {
      key.fail("'" + name + "' is given twice (first on line " +
               std::to_string(earlier->second.first.where().line) + ")");
    }
    entries.emplace(name, std::pair{key, value});
  }
  return entries;
}

/// Reads one limit kind of a joint's entry into `entry`.
void readLimit(const LimitKind& kind, const KeyedEntries& keys, JointLimitsEntry& entry) {
  const auto flag = keys.find(kind.flag);
  const bool used = flag != keys.end() && flag->second.second.flag();
  for (std::size_t i = 0; i < kind.keys.size(); ++i) {
    const auto given = keys.find(kind.keys[i]);
    if (used && given == keys.end()) {
      flag->second.first.fail("is true but " + std::string(kind.keys[i]) + " is not given");
    }
    if (given == keys.end()) continue;
    const YamlValue& value = given->second.second;
    if (!used) {
      logWarning(value.where().toString() + ": " + value.path() + " is ignored: " + kind.flag + " is " +
                 (flag == keys.end() ? "absent" : "false") + " (set it to true to use the limit)");
      continue;
    }
    const double number = numberOf(value, kind.angle, entry.degreesLine);
    if (kind.positive && !(number > 0.0)) value.fail("must be positive, got " + value.text("a number"));
    entry.*kind.members[i] = number;
  }
}

bool isUnderstoodKey(const std::string& name) {
  if (ignoredKeys().count(name) > 0) return true;
  for (const LimitKind& kind : limitKinds()) {
    if (name == kind.flag) return true;
    for (const char* key : kind.keys) {
      if (name == key) return true;
    }
  }
  return false;
}

JointLimitsEntry readEntry(const YamlValue& key, const YamlValue& value) {
  JointLimitsEntry entry;
  entry.joint = key.text("a joint name");
  entry.line = key.where().line;
  if (!value.isMap()) value.fail("expected a map of limits (has_velocity_limits, max_velocity, ...)");
  const KeyedEntries keys = uniqueEntries(value);
  for (const auto& [name, item] : value.entries()) {
    const std::string text = name.text("a name");
    if (!isUnderstoodKey(text)) name.fail("unknown key '" + text + "'; a joint's keys are " + understoodKeys());
  }
  for (const LimitKind& kind : limitKinds()) readLimit(kind, keys, entry);
  if (entry.minPosition && entry.maxPosition && *entry.minPosition > *entry.maxPosition) {
    keys.at("min_position").first.fail("min_position " + numberText(*entry.minPosition) +
                                       " is above max_position " + numberText(*entry.maxPosition));
  }
  return entry;
}

std::optional<double> scalingFactor(const YamlValue& value) {
  int unusedDegreesLine = 0;
  const double factor = numberOf(value, false, unusedDegreesLine);
  if (!(factor > 0.0 && factor <= 1.0)) value.fail("must be in (0, 1], got " + value.text("a number"));
  return factor;
}

void readTopLevel(const YamlValue& root, JointLimitsFile& result) {
  (void)uniqueEntries(root);
  for (const auto& [key, value] : root.entries()) {
    const std::string name = key.text("a name");
    if (name == "default_velocity_scaling_factor") {
      result.defaultVelocityScalingFactor = scalingFactor(value);
    } else if (name == "default_acceleration_scaling_factor") {
      result.defaultAccelerationScalingFactor = scalingFactor(value);
    } else if (name != "joint_limits") {
      key.fail("unknown key '" + name +
               "'; a joint limits file has joint_limits, default_velocity_scaling_factor and "
               "default_acceleration_scaling_factor");
    }
  }
  const YamlValue joints = root.child("joint_limits");
  if (!joints.isMap()) joints.fail("expected a map from joint names to their limits");
  std::map<std::string, int> lines;
  for (const auto& [key, value] : joints.entries()) {
    const std::string joint = key.text("a joint name");
    if (const auto [earlier, added] = lines.emplace(joint, key.where().line); !added) {
      key.fail("the joint is given twice (first on line " + std::to_string(earlier->second) + ")");
    }
    result.joints.push_back(readEntry(key, value));
  }
}

std::string movableJointNames(const RobotModel& model) {
  std::string names;
  for (const Joint& joint : model.joints()) {
    if (joint.type != JointType::kFixed) names += (names.empty() ? "" : ", ") + joint.name;
  }
  return names.empty() ? "(none)" : names;
}

/// `bound` replaces the URDF's bound `urdf` when it lies in [low, high]; otherwise a warning.
double narrowed(double bound, double urdf, double low, double high, const std::string& what) {
  if (bound >= low && bound <= high) return bound;
  logWarning(what + " " + numberText(bound) + " lies outside the URDF's range: the URDF's " +
             numberText(urdf) + " is kept (a joint limits file narrows a joint's range, never widens it)");
  return urdf;
}

void narrowPositions(const JointLimitsEntry& entry, const Joint& joint, double lengthScale,
                     const std::string& where, JointLimits& limits) {
  if (!entry.minPosition || !entry.maxPosition) return;
  if (joint.type == JointType::kContinuous) {
    logWarning(where + ".has_position_limits: ignored: joint \"" + joint.name +
               "\" is continuous (it turns without limit)");
    return;
  }
  const double scale = joint.type == JointType::kPrismatic ? lengthScale : 1.0;
  const double lower = limits.lower;
  const double upper = limits.upper;
  limits.lower = std::max(lower, narrowed(scale * *entry.minPosition, lower, lower - kPositionTolerance, upper,
                                          where + ".min_position"));
  limits.upper = std::min(upper, narrowed(scale * *entry.maxPosition, upper, lower, upper + kPositionTolerance,
                                          where + ".max_position"));
}

}  // namespace

JointLimitsFile readJointLimitsFile(const std::filesystem::path& file) {
  JointLimitsFile result;
  result.source = file.string();
  moveit_yaml::readYamlFile(file, [&](const YamlValue& root) {
    // MoveIt 2 packages may write the file under the parameter it is loaded as.
    const bool wrapped = root.isMap() && root.entries().size() == 1 &&
                         root.entries().front().first.text("a name") == "robot_description_planning";
    readTopLevel(wrapped ? root.child("robot_description_planning") : root, result);
  });
  return result;
}

void applyJointLimits(const JointLimitsFile& limits, RobotModel& model, double lengthScale) {
  model.setScalingDefaults({limits.defaultVelocityScalingFactor, limits.defaultAccelerationScalingFactor});
  std::vector<std::pair<int, JointLimits>> changes;
  for (const JointLimitsEntry& entry : limits.joints) {
    const SourceLocation where{limits.source, entry.line};
    const std::string path = "joint_limits." + entry.joint;
    const std::optional<int> index = model.findJoint(entry.joint);
    if (!index || model.joints()[static_cast<std::size_t>(*index)].type == JointType::kFixed) {
      throw InputError(where, path + ": robot \"" + model.name() + "\" has no " + (index ? "movable " : "") +
                                  "joint \"" + entry.joint + "\"; its movable joints are: " + movableJointNames(model));
    }
    const Joint& joint = model.joints()[static_cast<std::size_t>(*index)];
    if (entry.degreesLine > 0 && joint.type == JointType::kPrismatic) {
      throw InputError(SourceLocation{limits.source, entry.degreesLine},
                       path + ": joint \"" + entry.joint +
                           "\" is prismatic: its limits are in metres, not !degrees");
    }
    JointLimits changed = joint.limits;
    if (entry.maxVelocity) changed.velocity = *entry.maxVelocity;
    if (entry.maxAcceleration) changed.acceleration = *entry.maxAcceleration;
    if (entry.maxJerk) changed.jerk = *entry.maxJerk;
    if (entry.maxEffort) changed.effort = *entry.maxEffort;
    narrowPositions(entry, joint, lengthScale, where.toString() + ": " + path, changed);
    changes.emplace_back(*index, changed);
  }
  for (const auto& [joint, changed] : changes) model.setJointLimits(joint, changed);
}

}  // namespace lang2manip
