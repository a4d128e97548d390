#include "lang2manip/model/robot_model.hpp"

#include <cmath>
#include <cstdio>
#include <deque>
#include <numbers>
#include <utility>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {

std::string jointTypeName(JointType type) {
  switch (type) {
    case JointType::kRevolute: return "revolute";
    case JointType::kContinuous: return "continuous";
    case JointType::kPrismatic: return "prismatic";
    case JointType::kFixed: return "fixed";
    case JointType::kFloating: return "floating";
    case JointType::kPlanar: return "planar";
  }
  return "unknown";
}

void requireLinkInRange(const Link& link, const SourceLocation& where) {
  for (std::size_t i = 0; i < link.collisions.size(); ++i) {
    requireShapeInRange(link.collisions[i], "link \"" + link.name + "\" collision " + std::to_string(i + 1), where);
  }
  for (std::size_t i = 0; i < link.visuals.size(); ++i) {
    requireShapeInRange(link.visuals[i], "link \"" + link.name + "\" visual " + std::to_string(i + 1), where);
  }
}

namespace {

bool isMovable(JointType type) {
  return type == JointType::kRevolute || type == JointType::kContinuous ||
         type == JointType::kPrismatic;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string joined;
  for (const std::string& name : names) joined += (joined.empty() ? "" : ", ") + name;
  return joined;
}

void checkPoseFinite(const Pose& pose, const std::string& what, const SourceLocation& where) {
  if (!pose.matrix().allFinite()) throw InputError(where, what + " has a non-finite value");
}

void checkJoint(Joint& joint, const SourceLocation& where) {
  const std::string what = "joint \"" + joint.name + "\"";
  checkPoseFinite(joint.origin, what + " origin", where);
  requirePositionInRange(joint.origin.translation(), what + " origin", where);
  if (!joint.axis.allFinite() || joint.axis.norm() < 1e-12) {
    throw InputError(where, what + " has a zero or non-finite axis");
  }
  joint.axis.normalize();
  if (joint.type == JointType::kFloating || joint.type == JointType::kPlanar) {
    throw NotSupportedError(where.toString() + ": " + what + ": " + jointTypeName(joint.type) +
                            " joints are not supported");
  }
  if (joint.type == JointType::kContinuous) {
    joint.limits.lower = -std::numbers::pi;
    joint.limits.upper = std::numbers::pi;
  }
  const JointLimits& limits = joint.limits;
  for (const double value : {limits.lower, limits.upper, limits.velocity, limits.effort}) {
    requireFinite(value, what + " limit", where);
  }
  if (limits.velocity < 0.0) {
    throw InputError(where, what + " velocity limit must not be negative, got " + numberText(limits.velocity) +
                                " (0 or none: no limit given)");
  }
  if (limits.velocity > 0.0 && limits.velocity < kSmallestJointVelocityLimit) {
    throw InputError(where, what + " velocity limit " + numberText(limits.velocity) + " is below " +
                                numberText(kSmallestJointVelocityLimit) +
                                " (rad/s or m/s): no motion of it could be timed");
  }
  for (const auto& [bound, name] : {std::pair{&limits.acceleration, "acceleration"}, std::pair{&limits.jerk, "jerk"}}) {
    if (*bound && !(std::isfinite(**bound) && **bound > 0.0)) {
      throw InputError(where, what + " " + name + " limit must be a positive finite number, got " + numberText(**bound));
    }
  }
  if (joint.type == JointType::kPrismatic) {
    requirePositionInRange(Vector3(limits.lower, limits.upper, 0.0), what + " limits (lower, upper, 0)", where);
  }
  if (isMovable(joint.type) && limits.lower > limits.upper) {
    throw InputError(where, what + " has lower limit " + numberText(limits.lower) +
                                " above upper limit " + numberText(limits.upper));
  }
  if (joint.mimic) {
    requireFinite(joint.mimic->multiplier, what + " mimic multiplier", where);
    requireFinite(joint.mimic->offset, what + " mimic offset", where);
  }
}

}  // namespace

RobotModel::RobotModel(RobotModelData data) : data_(std::move(data)) {
  const SourceLocation where{data_.source, 0};
  if (data_.links.empty()) throw InputError(where, "robot \"" + data_.name + "\" has no links");
  for (std::size_t i = 0; i < data_.links.size(); ++i) {
    if (!linkByName_.emplace(data_.links[i].name, static_cast<int>(i)).second) {
      throw InputError(where, "link \"" + data_.links[i].name + "\" is defined twice");
    }
  }
  for (const Link& link : data_.links) requireLinkInRange(link, where);
  for (Joint& joint : data_.joints) checkJoint(joint, where);
  orderTopologically();
  indexVariables();
}

void RobotModel::orderTopologically() {
  const SourceLocation where{data_.source, 0};
  const std::size_t linkCount = data_.links.size();
  std::vector<int> parentOf(linkCount, -1);
  std::vector<std::vector<int>> childJoints(linkCount);
  for (std::size_t j = 0; j < data_.joints.size(); ++j) {
    const Joint& joint = data_.joints[j];
    for (const std::string* name : {&joint.parentLink, &joint.childLink}) {
      if (!linkByName_.count(*name)) {
        throw InputError(where, "joint \"" + joint.name + "\" refers to unknown link \"" + *name +
                                    "\"");
      }
    }
    const int child = linkByName_.at(joint.childLink);
    if (parentOf[static_cast<std::size_t>(child)] >= 0) {
      throw InputError(where, "link \"" + joint.childLink + "\" has two parent joints (\"" +
                                  data_.joints[static_cast<std::size_t>(
                                      parentOf[static_cast<std::size_t>(child)])].name +
                                  "\" and \"" + joint.name + "\")");
    }
    parentOf[static_cast<std::size_t>(child)] = static_cast<int>(j);
    childJoints[static_cast<std::size_t>(linkByName_.at(joint.parentLink))].push_back(
        static_cast<int>(j));
  }
  std::vector<std::string> roots;
  int root = -1;
  for (std::size_t i = 0; i < linkCount; ++i) {
    if (parentOf[i] < 0) {
      roots.push_back(data_.links[i].name);
      root = static_cast<int>(i);
    }
  }
  if (roots.size() > 1) {
    throw InputError(where, "robot \"" + data_.name + "\" has " + std::to_string(roots.size()) +
                                " root links (" + joinNames(roots) +
                                "); a URDF must form one tree");
  }
  if (roots.empty()) {
    throw InputError(where, "robot \"" + data_.name +
                                "\" has no root link: its joints form a cycle");
  }
  std::vector<Link> orderedLinks;
  std::vector<Joint> orderedJoints;
  std::deque<int> pending{root};
  while (!pending.empty()) {
    const int link = pending.front();
    pending.pop_front();
    orderedLinks.push_back(data_.links[static_cast<std::size_t>(link)]);
    for (const int j : childJoints[static_cast<std::size_t>(link)]) {
      orderedJoints.push_back(data_.joints[static_cast<std::size_t>(j)]);
      pending.push_back(linkByName_.at(data_.joints[static_cast<std::size_t>(j)].childLink));
    }
  }
  if (orderedLinks.size() != linkCount) {
    std::vector<std::string> unreached;
    for (const Link& link : data_.links) {
      bool reached = false;
      for (const Link& ordered : orderedLinks) reached = reached || ordered.name == link.name;
      if (!reached) unreached.push_back(link.name);
    }
    throw InputError(where, "the joints of robot \"" + data_.name +
                                "\" form a cycle through links " + joinNames(unreached));
  }
  data_.links = std::move(orderedLinks);
  data_.joints = std::move(orderedJoints);
  linkByName_.clear();
  for (std::size_t i = 0; i < data_.links.size(); ++i) {
    linkByName_[data_.links[i].name] = static_cast<int>(i);
  }
  parentJoint_.assign(linkCount, -1);
  for (std::size_t j = 0; j < data_.joints.size(); ++j) {
    const Joint& joint = data_.joints[j];
    if (!jointByName_.emplace(joint.name, static_cast<int>(j)).second) {
      throw InputError(where, "joint \"" + joint.name + "\" is defined twice");
    }
    childLink_.push_back(linkByName_.at(joint.childLink));
    parentLink_.push_back(linkByName_.at(joint.parentLink));
    parentJoint_[static_cast<std::size_t>(childLink_.back())] = static_cast<int>(j);
  }
}

void RobotModel::indexVariables() {
  const SourceLocation where{data_.source, 0};
  variableOfJoint_.assign(data_.joints.size(), -1);
  mimicSource_.assign(data_.joints.size(), -1);
  for (std::size_t j = 0; j < data_.joints.size(); ++j) {
    const Joint& joint = data_.joints[j];
    if (!isMovable(joint.type) || joint.mimic) continue;
    variableOfJoint_[j] = static_cast<int>(variables_.size());
    variables_.push_back(static_cast<int>(j));
  }
  for (std::size_t j = 0; j < data_.joints.size(); ++j) {
    const Joint& joint = data_.joints[j];
    if (!joint.mimic || !isMovable(joint.type)) continue;
    const auto source = jointByName_.find(joint.mimic->sourceJoint);
    if (source == jointByName_.end()) {
      throw InputError(where, "joint \"" + joint.name + "\" mimics unknown joint \"" +
                                  joint.mimic->sourceJoint + "\"");
    }
    const int variable = variableOfJoint_[static_cast<std::size_t>(source->second)];
    if (variable < 0) {
      throw InputError(where, "joint \"" + joint.name + "\" mimics \"" + joint.mimic->sourceJoint +
                                  "\", which is not a movable, non-mimic joint");
    }
    mimicSource_[j] = variable;
  }
  const auto count = static_cast<Eigen::Index>(variables_.size());
  lower_.resize(count);
  upper_.resize(count);
  velocity_.resize(count);
  for (Eigen::Index v = 0; v < count; ++v) {
    const JointLimits& limits = data_.joints[static_cast<std::size_t>(variables_[static_cast<std::size_t>(v)])].limits;
    lower_[v] = limits.lower;
    upper_[v] = limits.upper;
    velocity_[v] = limits.velocity;
  }
}

std::optional<double> RobotModel::accelerationLimit(int variable) const {
  return data_.joints[static_cast<std::size_t>(variables_.at(static_cast<std::size_t>(variable)))].limits.acceleration;
}

std::optional<double> RobotModel::jerkLimit(int variable) const {
  return data_.joints[static_cast<std::size_t>(variables_.at(static_cast<std::size_t>(variable)))].limits.jerk;
}

void RobotModel::setJointLimits(int joint, const JointLimits& limits) {
  Joint changed = data_.joints.at(static_cast<std::size_t>(joint));
  changed.limits = limits;
  checkJoint(changed, SourceLocation{data_.source, 0});
  data_.joints[static_cast<std::size_t>(joint)].limits = changed.limits;
  const int variable = variableOfJoint_[static_cast<std::size_t>(joint)];
  if (variable < 0) return;
  lower_[variable] = changed.limits.lower;
  upper_[variable] = changed.limits.upper;
  velocity_[variable] = changed.limits.velocity;
}

std::optional<int> RobotModel::findLink(const std::string& name) const {
  const auto found = linkByName_.find(name);
  if (found == linkByName_.end()) return std::nullopt;
  return found->second;
}

int RobotModel::linkIndex(const std::string& name) const {
  if (const auto index = findLink(name)) return *index;
  std::vector<std::string> names;
  for (const Link& link : data_.links) names.push_back(link.name);
  throw InputError("robot \"" + data_.name + "\" has no link \"" + name +
                   "\"; its links are: " + joinNames(names));
}

std::optional<int> RobotModel::findJoint(const std::string& name) const {
  const auto found = jointByName_.find(name);
  if (found == jointByName_.end()) return std::nullopt;
  return found->second;
}

int RobotModel::jointIndex(const std::string& name) const {
  if (const auto index = findJoint(name)) return *index;
  std::vector<std::string> names;
  for (const Joint& joint : data_.joints) names.push_back(joint.name);
  throw InputError("robot \"" + data_.name + "\" has no joint \"" + name +
                   "\"; its joints are: " + joinNames(names));
}

std::vector<std::string> RobotModel::variableNames() const {
  std::vector<std::string> names;
  for (const int j : variables_) names.push_back(data_.joints[static_cast<std::size_t>(j)].name);
  return names;
}

int RobotModel::variableIndex(const std::string& name) const {
  const auto joint = findJoint(name);
  if (joint && variableOfJoint_[static_cast<std::size_t>(*joint)] >= 0) {
    return variableOfJoint_[static_cast<std::size_t>(*joint)];
  }
  throw InputError("robot \"" + data_.name + "\" has no joint variable \"" + name +
                   "\"; its variables are: " + joinNames(variableNames()));
}

double RobotModel::jointValue(int joint, const VectorX& q) const noexcept {
  const auto j = static_cast<std::size_t>(joint);
  if (variableOfJoint_[j] >= 0) return q[variableOfJoint_[j]];
  if (mimicSource_[j] >= 0) {
    const JointMimic& mimic = *data_.joints[j].mimic;
    return mimic.multiplier * q[mimicSource_[j]] + mimic.offset;
  }
  return 0.0;
}

Pose RobotModel::jointTransform(int joint, double value) const noexcept {
  const Joint& j = data_.joints[static_cast<std::size_t>(joint)];
  Pose transform = j.origin;
  if (j.type == JointType::kRevolute || j.type == JointType::kContinuous) {
    transform.linear() = transform.linear() * Eigen::AngleAxisd(value, j.axis).toRotationMatrix();
  } else if (j.type == JointType::kPrismatic) {
    transform.translation() += transform.linear() * (value * j.axis);
  }
  return transform;
}

std::vector<Pose> RobotModel::linkPoses(const VectorX& q) const {
  checkConfiguration(q, "configuration");
  std::vector<Pose> poses(data_.links.size(), Pose::Identity());
  for (std::size_t j = 0; j < data_.joints.size(); ++j) {
    const int joint = static_cast<int>(j);
    poses[static_cast<std::size_t>(childLink_[j])] =
        poses[static_cast<std::size_t>(parentLink_[j])] * jointTransform(joint, jointValue(joint, q));
  }
  return poses;
}

VectorX RobotModel::middleConfiguration() const { return 0.5 * (lower_ + upper_); }

void RobotModel::checkConfiguration(const VectorX& q, const std::string& what) const {
  if (q.size() != variableCount()) {
    throw InputError(what + " for robot \"" + data_.name + "\" has " + std::to_string(q.size()) +
                     " values; the robot has " + std::to_string(variableCount()) +
                     " joint variables (" + joinNames(variableNames()) + ")");
  }
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    if (!std::isfinite(q[i])) {
      throw InputError(what + " for robot \"" + data_.name + "\": value of joint \"" +
                       variableNames()[static_cast<std::size_t>(i)] + "\" is not finite");
    }
  }
}

std::vector<std::string> RobotModel::limitViolations(const VectorX& q, double tolerance) const {
  checkConfiguration(q, "configuration");
  std::vector<std::string> violations;
  for (int v = 0; v < variableCount(); ++v) {
    const Joint& joint = data_.joints[static_cast<std::size_t>(variables_[static_cast<std::size_t>(v)])];
    if (joint.type == JointType::kContinuous) continue;
    const double value = q[v];
    const bool below = value < lower_[v] - tolerance;
    if (!below && value <= upper_[v] + tolerance) continue;
    char text[160];
    std::snprintf(text, sizeof text, " = %.6g is %s its %s limit %.6g", value, below ? "below" : "above",
                  below ? "lower" : "upper", below ? lower_[v] : upper_[v]);
    violations.push_back(joint.name + text);
  }
  return violations;
}

VectorX RobotModel::namedConfiguration(const std::string& name) const {
  VectorX q = middleConfiguration();
  bool found = false;
  std::vector<std::string> names;
  for (const NamedState& state : data_.semantics.namedStates) {
    names.push_back(state.name);
    if (state.name != name) continue;
    found = true;
    for (const auto& [joint, value] : state.values) {
      const auto index = findJoint(joint);
      if (index && variableOfJoint_[static_cast<std::size_t>(*index)] >= 0) {
        q[variableOfJoint_[static_cast<std::size_t>(*index)]] = value;
      }
    }
  }
  if (!found) {
    throw InputError("robot \"" + data_.name + "\" has no named state \"" + name +
                     "\"; its named states are: " + (names.empty() ? "(none)" : joinNames(names)));
  }
  return q;
}

}  // namespace lang2manip
