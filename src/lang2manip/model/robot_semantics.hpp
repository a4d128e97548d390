#pragma once
/// @file What a robot's parts are for: planning groups, end effectors, named states and disabled
/// collision pairs (SRDF), and the resolved manipulators (arm joints, tool frame, gripper).

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lang2manip/core/types.hpp"

namespace lang2manip {

/// An SRDF <group>: chains (base, tip), joints, links and subgroups, as written.
struct PlanningGroup {
  std::string name;
  std::vector<std::pair<std::string, std::string>> chains;
  std::vector<std::string> joints;
  std::vector<std::string> links;
  std::vector<std::string> subgroups;
};

/// An SRDF <end_effector>.
struct EndEffector {
  std::string name;
  std::string parentLink;
  std::string group;
  std::string parentGroup;
};

/// An SRDF <group_state>: joint values of a group under a name such as "home".
struct NamedState {
  std::string name;
  std::string group;
  std::vector<std::pair<std::string, double>> values;
};

/// An SRDF <disable_collisions> pair.
struct DisabledCollision {
  std::string link1;
  std::string link2;
  std::string reason;
};

/// One arm with its gripper, resolved from the SRDF or inferred from the kinematic tree.
struct Manipulator {
  std::string name;
  /// Joints that move the arm, root to tip.
  std::vector<std::string> armJoints;
  std::string baseLink;
  /// The frame grasps are expressed in (the tool centre point).
  std::string toolFrame;
  /// Gripper joints that are not mimics (usually one); empty for a robot without a gripper.
  std::vector<std::string> gripperJoints;
  /// Gripper joint values when open and when closed (same order as gripperJoints).
  std::vector<double> gripperOpen;
  std::vector<double> gripperClosed;
  /// Joints on the hand that turn without limits beside finger joints that have them (a servo's
  /// horn whose linkage to the fingers the URDF does not hold): no fingers, and not driven.
  std::vector<std::string> idleHandJoints;
  /// The SRDF state (e.g. "open") the open values come from, and the one of the closed values;
  /// empty when they come from the joint limits (which do not say which end is open).
  std::string gripperOpenState;
  std::string gripperClosedState;
  /// The direction (unit, in the tool frame) a grasp or push moves the tool into the object,
  /// when given (SRDF <lang2manip_approach>, --approach-axis); otherwise it is measured from
  /// the fingers (from their roots towards the pads) or, without a gripper, the tool frame's +z.
  std::optional<Vector3> approachAxis;
};

/// Everything semantic about a robot. `inferred` is true when no SRDF was read.
struct RobotSemantics {
  std::vector<PlanningGroup> groups;
  std::vector<EndEffector> endEffectors;
  std::vector<NamedState> namedStates;
  std::vector<DisabledCollision> disabledCollisions;
  /// SRDF <disable_default_collisions>: links checked against nothing (no other link, object or
  /// robot) except the pairs of enabledCollisions; e.g. a self-collision envelope.
  std::vector<std::string> defaultCollisionsDisabled;
  /// SRDF <enable_collisions> pairs (link1, link2): checked although a link's default is off.
  std::vector<std::pair<std::string, std::string>> enabledCollisions;
  std::vector<Manipulator> manipulators;
  bool inferred = true;
  /// The SRDF file read, empty when inferred.
  std::string source;
};

}  // namespace lang2manip
