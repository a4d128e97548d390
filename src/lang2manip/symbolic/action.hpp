#pragma once
/// @file The symbolic action grammar of the paper: each action is a(o, p, r, kappa) -- an
/// action type, the object it acts on, its parameters, refinements, and a preferred motion
/// planner -- and a plan is a sequence of actions. Also the goal relations an instruction asks
/// for, which the final state is checked against.

#include <optional>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/symbolic/surface_region.hpp"

namespace lang2manip {

enum class ActionType { kPick, kPlace, kMove, kPush };

/// Spatial relations between objects; left/right/front/behind are in the robot's base frame
/// (front = +x of the base, left = +y).
enum class SpatialRelation { kIn, kOn, kLeftOf, kRightOf, kInFrontOf, kBehind, kNextTo };

enum class GraspDirection { kAuto, kTop, kSide, kFront };

/// "pick", "place", "move", "push".
std::string actionTypeName(ActionType type);
/// "in", "on", "left_of", "right_of", "in_front_of", "behind", "next_to".
std::string spatialRelationName(SpatialRelation relation);
/// The relation as people write it in messages: "in", "on", "left of", "in front of", "next to".
std::string spatialRelationWords(SpatialRelation relation);
/// "auto", "top", "side", "front".
std::string graspDirectionName(GraspDirection direction);

/// Inverses of the names above; std::nullopt for an unknown name (callers report it with context).
std::optional<ActionType> actionTypeFromName(const std::string& name);
std::optional<SpatialRelation> spatialRelationFromName(const std::string& name);
std::optional<GraspDirection> graspDirectionFromName(const std::string& name);

/// The names accepted by the *FromName functions, for error messages ("pick, place, ...").
std::vector<std::string> actionTypeNames();
std::vector<std::string> spatialRelationNames();
std::vector<std::string> graspDirectionNames();

/// Parameters p of an action; which fields are meaningful depends on the action type:
/// - place: `relation` + `target` (+ optional `distance` for left_of/right_of/in_front_of/
///   behind/next_to, + optional `region` of the target's top for on), or an explicit
///   `position` (+ optional `orientation`);
/// - move: a `position` (+ `orientation`) of the tool frame, or a `configuration` name such as
///   "home" (then `object` of the action is empty);
/// - push: a `direction` (unit vector, robot base frame) and a `distance` in metres;
/// - pick: none.
struct ActionParams {
  std::optional<SpatialRelation> relation;
  std::string target;
  std::optional<double> distance;
  std::optional<Vector3> position;
  std::optional<Quaternion> orientation;
  std::string configuration;
  std::optional<Vector3> direction;
  /// For place on a support: the region of its top face ("far_left_corner", see
  /// surface_region.hpp).
  std::optional<SurfaceRegion> region{};
};

/// Refinements r: how to grasp and approach.
struct ActionRefinements {
  GraspDirection grasp = GraspDirection::kAuto;
  /// Approach direction of the gripper (unit vector, robot base frame), when requested.
  std::optional<Vector3> approach;
};

struct SymbolicAction {
  ActionType type = ActionType::kPick;
  /// The object acted on; empty for `move` to a named configuration or a pose.
  std::string object;
  ActionParams params;
  ActionRefinements refinements;
  /// A registered motion planner name (e.g. "RRTConnect", "omplRRTStar"); empty = default.
  std::string planner;
};

/// What an instruction asks to hold at the end; the final state is checked against these.
enum class GoalKind {
  /// `object` `relation` `target` (e.g. marker in pen_holder).
  kRelation,
  /// The robot holds `object`.
  kHolding,
  /// `object` moved by `displacement` (robot base frame) from where it started.
  kDisplaced,
  /// The robot is at the named `configuration` (e.g. "home").
  kAtConfiguration,
  /// The robot holds `object` out to a person at handoverToolPosition() ("hand me the marker").
  kHandedOver,
  /// `object` stands with its frame's origin at `position` (robot base frame; x and y are
  /// checked, z follows the support it rests on); `target`, when set, names the object whose
  /// place that was ("put the marker where the eraser is", "swap the marker and the eraser").
  kAtPosition,
  /// `object` turned by `angle` (rad, counter-clockwise seen from above) about the vertical from
  /// its orientation at the start, standing where it stood.
  kTurned,
  /// The long side of `object` points at `target` (either end; seen from above), or, when
  /// `target` is empty, lies along the base-frame yaw `angle` ("point it forward": 0).
  kFacing,
  /// The `members` stand together in `shape` (seen from above), each on `target` when set (and
  /// in its `region`); see checkArrangedBoxes() for what each shape means in metres.
  kArranged,
};

/// How the members of an arranged goal stand, seen from above (centres of their bounds).
enum class ArrangementShape {
  /// On one straight line (along `heading` when given), evenly spaced when asked.
  kLine,
  /// On one circle, spread around it.
  kCircle,
  /// At the corners of an equilateral triangle (three members).
  kTriangle,
  /// At the corners of a square (four members).
  kSquare,
  /// No two of them next to each other.
  kSpreadOut,
  /// Next to each other, as one group: each next_to another, and every member reached from any
  /// other through members next_to each other.
  kTogether,
  /// Rows resting on rows: a base of k members in a line, then k - 1 members each resting on two
  /// of the row below, up to one on top (3, 6, 10, ... members).
  kPyramid,
};

/// "line", "circle", "triangle", "square", "spread_out", "together", "pyramid".
std::string arrangementShapeName(ArrangementShape shape);
std::optional<ArrangementShape> arrangementShapeFromName(const std::string& name);
std::vector<std::string> arrangementShapeNames();

/// Where the robot holds an object out to a person: the tool 0.40 m in front of the robot's base
/// and 0.25 m above it (robot base frame, metres), its orientation kept.
Vector3 handoverToolPosition();

struct Goal {
  GoalKind kind = GoalKind::kRelation;
  std::string object;
  std::optional<SpatialRelation> relation;
  std::string target;
  /// For left_of/... relations with an explicit distance, metres.
  std::optional<double> distance;
  Vector3 displacement = Vector3::Zero();
  std::string configuration;
  /// kAtPosition: where the object frame's origin goes (robot base frame); kTurned: where it
  /// stands turned, when the instruction put it there first (else where it stood).
  std::optional<Vector3> position;
  /// kTurned: the turn about the vertical, rad (counter-clockwise seen from above); kFacing
  /// without a target: the heading of the long side, rad (base frame, 0 = front).
  double angle = 0.0;
  /// For an on relation: the region of the target's top face the object's centre must be in.
  std::optional<SurfaceRegion> region{};
  /// kArranged: the objects arranged (at least two), their shape, the line's base-frame heading
  /// (rad, either way along it; none = any), and whether a line is evenly spaced (`distance`,
  /// when set, is then the spacing of neighbouring centres).
  std::vector<std::string> members{};
  std::optional<ArrangementShape> shape{};
  std::optional<double> heading{};
  bool evenlySpaced = false;
};

struct Plan {
  std::vector<SymbolicAction> actions;
  /// Optional free-text reasoning the planner gave with the plan.
  std::string reasoning;
  /// The final state the planner says the plan reaches (its goal statement); empty when it gave
  /// none. Checked against the final world when the instruction is beyond the offline parser.
  std::vector<Goal> goals;
};

/// "marker in pen_holder", "holding marker", "eraser displaced by (0, 0.05, 0)", "at home".
std::string describeGoal(const Goal& goal);

}  // namespace lang2manip
