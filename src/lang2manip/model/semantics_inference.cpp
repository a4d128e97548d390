// inferSemantics(): arms, tool frames and grippers of a robot that comes without an SRDF.
#include <algorithm>
#include <array>
#include <map>
#include <limits>
#include <set>

#include "lang2manip/model/srdf_reader.hpp"

namespace lang2manip {
namespace {

/// The most movable joints one finger of a hand has (four for the common anthropomorphic hands).
constexpr int kFingerJoints = 4;

bool isMovable(const Joint& joint) {
  return (joint.type == JointType::kRevolute || joint.type == JointType::kContinuous ||
          joint.type == JointType::kPrismatic) &&
         !joint.mimic;
}

class TreeWalker {
 public:
  explicit TreeWalker(const RobotModelData& robot) : robot_(robot) {
    for (const Link& link : robot.links) links_[link.name] = &link;
    std::set<std::string> children;
    for (const Joint& joint : robot.joints) {
      childJoints_[joint.parentLink].push_back(&joint);
      parentJoint_[joint.childLink] = &joint;
      children.insert(joint.childLink);
    }
    for (const Link& link : robot.links) {
      if (!children.count(link.name)) root_ = link.name;
    }
  }

  // A finger starts at a prismatic joint with at most one movable joint below it (a prismatic
  // joint with an arm below it is a torso or a linear axis: part of the arm), or at one of
  // several movable joints on one rigid body that an arm carries (a movable joint above it),
  // with fewer than kFingerJoints movable joints from it down (arms hold more; arms side by side
  // on a fixed body are not carried). Every movable joint at or below a finger's start belongs
  // to the gripper. Siblings are counted on the rigid body the joint hangs from (links joined
  // by fixed joints: fingers are often mounted on links of their own), mimics included (a mimic
  // finger is a finger all the same).
  bool startsFinger(const Joint& joint) const {
    if (!isMovable(joint)) return false;
    if (joint.type == JointType::kPrismatic) return movableDepthBelow(joint.childLink) <= 1;
    const std::string body = rigidRoot(joint.parentLink);
    if (parentJoint_.count(body) == 0) return false;
    return (actuatedOnBody(body) > 1 && movableDepthBelow(joint.childLink) < kFingerJoints) || isSingleJaw(joint);
  }

  // One jaw that closes against a fixed one (a revolute jaw on a servo, as on many small arms):
  // the last movable joint, turning across the direction its link reaches out from the hinge,
  // on a body whose own geometry reaches at least kFixedJawReach as far the same way beside it
  // (within the jaw's length of the line it reaches along).
  // A wrist's last joint is no jaw: the body that carries it lies behind the hinge, and a roll
  // turns about the direction its link reaches.
  bool isSingleJaw(const Joint& joint) const {
    constexpr double kLeastJawLength = 0.02;
    constexpr double kFixedJawReach = 0.6;
    constexpr double kAcrossCosine = 0.5;
    if (joint.type != JointType::kRevolute || movableDepthBelow(joint.childLink) > 0) return false;
    const std::vector<Vector3> jaw = rigidCorners(joint.childLink, joint.origin);
    const std::vector<Vector3> body = rigidCorners(rigidRoot(joint.parentLink), bodyToParent(joint.parentLink));
    if (jaw.empty() || body.empty()) return false;
    const Vector3 hinge = joint.origin.translation();
    Vector3 centre = Vector3::Zero();
    for (const Vector3& p : jaw) centre += p;
    centre /= static_cast<double>(jaw.size());
    if ((centre - hinge).norm() < 1e-6) return false;
    const Vector3 out = (centre - hinge).normalized();
    if (std::abs((joint.origin.linear() * joint.axis).normalized().dot(out)) > kAcrossCosine) return false;
    double jawReach = 0.0, bodyReach = 0.0;
    for (const Vector3& p : jaw) jawReach = std::max(jawReach, (p - hinge).dot(out));
    for (const Vector3& p : body) {
      const Vector3 offset = p - hinge;
      const double along = offset.dot(out);
      // Beside the moving jaw: no farther from the line it reaches along than it is long.
      if ((offset - along * out).norm() <= jawReach) bodyReach = std::max(bodyReach, along);
    }
    return jawReach >= kLeastJawLength && bodyReach >= kFixedJawReach * jawReach;
  }

  /// The pose of link `link` in the frame of its rigid body's root (through fixed joints) is
  /// inverted: the root's pose in `link`'s frame.
  Pose bodyToParent(const std::string& link) const {
    Pose rootToLink = Pose::Identity();
    for (std::string at = link; at != rigidRoot(link);) {
      const Joint* joint = parentJoint_.at(at);
      rootToLink = joint->origin * rootToLink;
      at = joint->parentLink;
    }
    return rootToLink.inverse();
  }

  /// The corners of the collision bounds of every link rigidly attached to `link` (through fixed
  /// joints below it), in the frame X_FL places `link` in.
  std::vector<Vector3> rigidCorners(const std::string& link, const Pose& X_FL) const {
    std::vector<Vector3> corners;
    if (const auto found = links_.find(link); found != links_.end()) {
      for (const Shape& shape : found->second->collisions) {
        const AlignedBox3 box = shapeBounds(shape);
        if (box.isEmpty()) continue;
        for (int c = 0; c < 8; ++c) corners.push_back(X_FL * box.corner(static_cast<AlignedBox3::CornerType>(c)));
      }
    }
    if (const auto children = childJoints_.find(link); children != childJoints_.end()) {
      for (const Joint* child : children->second) {
        if (child->type != JointType::kFixed) continue;
        const std::vector<Vector3> more = rigidCorners(child->childLink, X_FL * child->origin);
        corners.insert(corners.end(), more.begin(), more.end());
      }
    }
    return corners;
  }

  bool isGripperJoint(const Joint& joint) const { return isMovable(joint) && fingerAtOrAbove(joint); }

  /// True when `joint` or a joint above it starts a finger (remembered: every query is linear in
  /// the tree's size overall, so trees of thousands of links are read quickly).
  bool fingerAtOrAbove(const Joint& joint) const {
    if (const auto known = fingerAtOrAbove_.find(&joint); known != fingerAtOrAbove_.end()) return known->second;
    const auto parent = parentJoint_.find(joint.parentLink);
    const bool result = startsFinger(joint) || (parent != parentJoint_.end() && fingerAtOrAbove(*parent->second));
    fingerAtOrAbove_[&joint] = result;
    return result;
  }

  int movableDepthBelow(const std::string& link) const {
    if (const auto known = movableDepthBelow_.find(link); known != movableDepthBelow_.end()) return known->second;
    int depth = 0;
    if (const auto children = childJoints_.find(link); children != childJoints_.end()) {
      for (const Joint* child : children->second) {
        depth = std::max(depth, (isMovable(*child) ? 1 : 0) + movableDepthBelow(child->childLink));
      }
    }
    movableDepthBelow_[link] = depth;
    return depth;
  }

  RobotSemantics infer() const {
    RobotSemantics semantics;
    const std::vector<const Joint*> tips = armTips();
    if (tips.size() > static_cast<std::size_t>(kMaxInferredArms)) {
      throw InputError("robot " + robot_.name + ": its tree ends in " + std::to_string(tips.size()) + " chains of movable joints (more than " +
                       std::to_string(kMaxInferredArms) + " arms): name its arms in an SRDF beside the URDF");
    }
    for (const Joint* tip : tips) semantics.manipulators.push_back(manipulatorEndingAt(*tip));
    rankManipulators(semantics.manipulators);
    if (semantics.manipulators.size() > 1) {
      for (Manipulator& arm : semantics.manipulators) arm.name = "arm_" + arm.toolFrame;
    }
    return semantics;
  }

 private:
  /// A mobile manipulator's wheels (one movable joint each, nothing held) are no arms when the
  /// robot has an arm of more joints; arms with a gripper come first, then those of more joints,
  /// so that the default arm is the one that manipulates (not a wheel or a head).
  static void rankManipulators(std::vector<Manipulator>& arms) {
    const auto joints = [](const Manipulator& arm) { return arm.armJoints.size(); };
    const bool longer = std::any_of(arms.begin(), arms.end(), [&](const Manipulator& arm) { return joints(arm) > 1; });
    if (longer) std::erase_if(arms, [&](const Manipulator& arm) { return joints(arm) <= 1 && arm.gripperJoints.empty(); });
    std::stable_sort(arms.begin(), arms.end(), [&](const Manipulator& a, const Manipulator& b) {
      if (a.gripperJoints.empty() != b.gripperJoints.empty()) return !a.gripperJoints.empty();
      return joints(a) > joints(b);
    });
  }

  /// The topmost link reached from `link` through fixed joints.
  /// The link at the top of the fixed joints above `link` (remembered for every link walked).
  std::string rigidRoot(const std::string& link) const {
    std::vector<std::string> walked;
    std::string at = link;
    for (auto parent = parentJoint_.find(at); parent != parentJoint_.end() && parent->second->type == JointType::kFixed;
         parent = parentJoint_.find(at)) {
      if (const auto known = rigidRoot_.find(at); known != rigidRoot_.end()) {
        at = known->second;
        break;
      }
      walked.push_back(at);
      at = parent->second->parentLink;
    }
    for (const std::string& below : walked) rigidRoot_[below] = at;
    return at;
  }

  /// Movable joints, mimics included, whose parent is rigidly attached to `root`.
  int actuatedOnBody(const std::string& root) const {
    if (actuatedOnBody_.empty()) {
      for (const Joint& joint : robot_.joints) {
        const bool moves = joint.type == JointType::kRevolute || joint.type == JointType::kContinuous ||
                           joint.type == JointType::kPrismatic;
        if (moves) ++actuatedOnBody_[rigidRoot(joint.parentLink)];
      }
    }
    const auto found = actuatedOnBody_.find(root);
    return found == actuatedOnBody_.end() ? 0 : found->second;
  }

  bool hasArmJointBelow(const std::string& link) const {
    if (const auto known = hasArmJointBelow_.find(link); known != hasArmJointBelow_.end()) return known->second;
    const auto children = childJoints_.find(link);
    const bool result = children != childJoints_.end() &&
                        std::any_of(children->second.begin(), children->second.end(), [&](const Joint* joint) {
                          return (isMovable(*joint) && !isGripperJoint(*joint)) || hasArmJointBelow(joint->childLink);
                        });
    hasArmJointBelow_[link] = result;
    return result;
  }

  std::vector<const Joint*> armTips() const {
    std::vector<const Joint*> tips;
    for (const Joint& joint : robot_.joints) {
      if (isMovable(joint) && !isGripperJoint(joint) && !hasArmJointBelow(joint.childLink)) {
        tips.push_back(&joint);
      }
    }
    return tips;
  }

  void collectBelow(const std::string& link, std::vector<std::string>& links) const {
    links.push_back(link);
    const auto children = childJoints_.find(link);
    if (children == childJoints_.end()) return;
    for (const Joint* joint : children->second) collectBelow(joint->childLink, links);
  }

  /// The links from `link` up to the root, `link` first.
  std::vector<std::string> ancestry(std::string link) const {
    std::vector<std::string> links{link};
    for (auto parent = parentJoint_.find(link); parent != parentJoint_.end(); parent = parentJoint_.find(link)) {
      link = parent->second->parentLink;
      links.push_back(link);
    }
    return links;
  }

  /// The deepest link every finger joint hangs from (the palm of a hand with fingers on mounts).
  std::string commonAncestorOfFingers(const std::vector<std::string>& fingers) const {
    std::vector<std::string> common;
    for (const Joint& joint : robot_.joints) {
      if (std::find(fingers.begin(), fingers.end(), joint.name) == fingers.end()) continue;
      const std::vector<std::string> mine = ancestry(joint.parentLink);
      if (common.empty()) {
        common = mine;
        continue;
      }
      std::erase_if(common, [&](const std::string& link) { return std::find(mine.begin(), mine.end(), link) == mine.end(); });
    }
    return common.front();
  }

  // Prefer a link named like a tool centre point; else the link the fingers hang from; else the
  // end of the fixed chain below the last arm joint.
  std::string toolFrameBelow(const std::string& link, const std::vector<std::string>& fingers) const {
    std::vector<std::string> links;
    collectBelow(link, links);
    static const std::array<const char*, 6> kHints{"tcp", "tool", "grasp", "end_effector", "ee",
                                                   "flange"};
    for (const char* hint : kHints) {
      for (const std::string& candidate : links) {
        if (candidate.find(hint) != std::string::npos) return candidate;
      }
    }
    if (!fingers.empty()) return commonAncestorOfFingers(fingers);
    std::string end = link;
    while (childJoints_.count(end) && childJoints_.at(end).size() == 1) {
      end = childJoints_.at(end).front()->childLink;
    }
    return end;
  }

  /// A joint that turns without limits among gripper joints that have them moves no finger the
  /// way the others do (a servo horn): it is left out of the gripper.
  void setIdleHandJoints(Manipulator& arm) const {
    const auto turnsFreely = [&](const std::string& name) {
      return std::any_of(robot_.joints.begin(), robot_.joints.end(),
                         [&](const Joint& joint) { return joint.name == name && joint.type == JointType::kContinuous; });
    };
    const auto limited = std::count_if(arm.gripperJoints.begin(), arm.gripperJoints.end(), [&](const std::string& name) { return !turnsFreely(name); });
    if (limited == 0) return;
    for (std::size_t i = arm.gripperJoints.size(); i-- > 0;) {
      if (!turnsFreely(arm.gripperJoints[i])) continue;
      arm.idleHandJoints.insert(arm.idleHandJoints.begin(), arm.gripperJoints[i]);
      arm.gripperJoints.erase(arm.gripperJoints.begin() + static_cast<std::ptrdiff_t>(i));
      arm.gripperOpen.erase(arm.gripperOpen.begin() + static_cast<std::ptrdiff_t>(i));
      arm.gripperClosed.erase(arm.gripperClosed.begin() + static_cast<std::ptrdiff_t>(i));
    }
  }

  Manipulator manipulatorEndingAt(const Joint& tip) const {
    Manipulator arm;
    arm.name = "arm";
    arm.baseLink = root_;
    for (const Joint* joint = &tip; joint != nullptr;) {
      if (isMovable(*joint) && !isGripperJoint(*joint)) arm.armJoints.push_back(joint->name);
      const auto parent = parentJoint_.find(joint->parentLink);
      joint = parent == parentJoint_.end() ? nullptr : parent->second;
    }
    std::reverse(arm.armJoints.begin(), arm.armJoints.end());
    std::vector<std::string> below;
    collectBelow(tip.childLink, below);
    for (const Joint& joint : robot_.joints) {
      if (isGripperJoint(joint) &&
          std::find(below.begin(), below.end(), joint.parentLink) != below.end()) {
        arm.gripperJoints.push_back(joint.name);
        arm.gripperOpen.push_back(joint.limits.upper);
        arm.gripperClosed.push_back(joint.limits.lower);
      }
    }
    setIdleHandJoints(arm);
    arm.toolFrame = toolFrameBelow(tip.childLink, arm.gripperJoints);
    return arm;
  }

  const RobotModelData& robot_;
  std::map<std::string, const Link*> links_;
  std::map<std::string, std::vector<const Joint*>> childJoints_;
  std::map<std::string, const Joint*> parentJoint_;
  mutable std::map<std::string, int> movableDepthBelow_;
  mutable std::map<std::string, std::string> rigidRoot_;
  mutable std::map<std::string, int> actuatedOnBody_;
  mutable std::map<std::string, bool> hasArmJointBelow_;
  mutable std::map<const Joint*, bool> fingerAtOrAbove_;
  std::string root_;
};

/// Bounds of a link's collision shapes in its own frame (empty without any).
AlignedBox3 collisionBounds(const Link& link) {
  AlignedBox3 bounds;
  for (const Shape& shape : link.collisions) bounds.extend(shapeBounds(shape));
  return bounds;
}

/// `box` (in a child frame) in its parent's frame, `X_PC` the child frame in the parent's.
AlignedBox3 inParentFrame(const AlignedBox3& box, const Pose& X_PC) {
  AlignedBox3 moved;
  for (int corner = 0; corner < 8; ++corner) moved.extend(X_PC * box.corner(static_cast<AlignedBox3::CornerType>(corner)));
  return moved;
}

/// Joints on the tree path between two links.
int jointsBetween(const std::map<std::string, const Joint*>& parentJoint, const std::string& a, const std::string& b) {
  std::map<std::string, int> upFromA;
  int steps = 0;
  for (std::string link = a;; ++steps) {
    upFromA[link] = steps;
    const auto parent = parentJoint.find(link);
    if (parent == parentJoint.end()) break;
    link = parent->second->parentLink;
  }
  steps = 0;
  for (std::string link = b;; ++steps) {
    if (const auto common = upFromA.find(link); common != upFromA.end()) return common->second + steps;
    const auto parent = parentJoint.find(link);
    if (parent == parentJoint.end()) break;
    link = parent->second->parentLink;
  }
  return std::numeric_limits<int>::max();
}

}  // namespace

std::vector<std::string> selfCollisionEnvelopes(const RobotModelData& robot) {
  constexpr double kLeastCover = 0.5;
  std::map<std::string, const Link*> links;
  for (const Link& link : robot.links) links[link.name] = &link;
  std::vector<std::string> envelopes;
  for (const Joint& joint : robot.joints) {
    if (joint.type != JointType::kFixed) continue;
    const Link* envelope = links.count(joint.childLink) ? links.at(joint.childLink) : nullptr;
    const Link* parent = links.count(joint.parentLink) ? links.at(joint.parentLink) : nullptr;
    if (envelope == nullptr || parent == nullptr || !envelope->visuals.empty() || envelope->collisions.empty()) continue;
    const AlignedBox3 inner = collisionBounds(*parent);
    const AlignedBox3 outer = inParentFrame(collisionBounds(*envelope), joint.origin);
    if (inner.isEmpty() || outer.isEmpty()) continue;
    const double covered = inner.intersection(outer).isEmpty() ? 0.0 : inner.intersection(outer).volume() / inner.volume();
    if (covered >= kLeastCover && outer.volume() > inner.volume()) envelopes.push_back(envelope->name);
  }
  return envelopes;
}

RobotSemantics inferSemantics(const RobotModelData& robot) {
  RobotSemantics semantics = TreeWalker(robot).infer();
  semantics.inferred = true;
  addSelfCollisionEnvelopes(robot, semantics);
  return semantics;
}

void addSelfCollisionEnvelopes(const RobotModelData& robot, RobotSemantics& semantics) {
  constexpr int kLeastJointsApart = 3;
  const std::vector<std::string> envelopes = selfCollisionEnvelopes(robot);
  std::map<std::string, const Joint*> parentJoint;
  for (const Joint& joint : robot.joints) parentJoint[joint.childLink] = &joint;
  for (std::size_t i = 0; i < envelopes.size(); ++i) {
    semantics.defaultCollisionsDisabled.push_back(envelopes[i]);
    for (std::size_t j = 0; j < i; ++j) {
      if (jointsBetween(parentJoint, envelopes[i], envelopes[j]) >= kLeastJointsApart + 2) {
        semantics.enabledCollisions.emplace_back(envelopes[j], envelopes[i]);
      }
    }
  }
}

}  // namespace lang2manip
