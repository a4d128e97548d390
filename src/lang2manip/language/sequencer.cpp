#include "lang2manip/language/sequencer.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "lang2manip/language/layout_geometry.hpp"
#include "lang2manip/symbolic/object_heading.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip {
namespace {

using language_detail::facingTurn;
using language_detail::footprintsOverlap;
using language_detail::freeSpots;
using language_detail::moveLayout;
using language_detail::placesTaken;
using language_detail::kRaisedPosition;
using language_detail::restingUnder;
using language_detail::shifted;
using language_detail::standingIn;
using language_detail::validatePoseGoal;

/// A goal order that does not work; the search tries another.
class SequencingFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

bool isDirectional(const Goal& goal) {
  return goal.kind == GoalKind::kRelation && goal.relation != SpatialRelation::kIn &&
         goal.relation != SpatialRelation::kOn;
}

struct World {
  SymbolicState state;
  /// Goals that geometry alone records (directional relations, displacements), done and not
  /// disturbed since.
  std::set<std::size_t> achieved;
  std::vector<SymbolicAction> actions;
  /// Where the objects stand (base frame) as the actions leave them; an object put somewhere
  /// by a relation is left out (its spot is chosen later, by the grounding).
  std::map<std::string, ObjectLayout> layout;
};

constexpr double kSamePlace = 0.01;

class Sequencer {
 public:
  Sequencer(const TaskSpecification& specification, const SymbolicState& state,
            const SequencingOptions& options)
      : specification_(specification),
        goals_(specification.steps.empty() ? specification.goals : specification.steps), initial_(state),
        options_(options) {}

  Plan run() {
    validateGoals();
    World start{initial_, {}, {}, options_.layout};
    std::vector<bool> used(goals_.size(), false);
    int budget = options_.maxOrdersTried;
    World result;
    if (!search(start, used, budget, result)) {
      std::string why = firstFailure_.empty() ? "the search gave up" : firstFailure_;
      if (budget < 0) why += " (gave up after " + std::to_string(options_.maxOrdersTried) + " tries)";
      throw PlanningError("offline planner: no order of actions achieves every goal: " + why);
    }
    Plan plan;
    plan.actions = std::move(result.actions);
    plan.reasoning = reasoning();
    return plan;
  }

 private:
  void validateGoals() const {
    for (const Goal& goal : goals_) {
      if (goal.kind == GoalKind::kAtConfiguration) continue;
      requireObject(goal.object);
      if (goal.kind == GoalKind::kRelation) requireObject(goal.target);
      if (!initial_.movable.count(goal.object) && !initiallyTrue(goal)) {
        throw PlanningError("offline planner: cannot achieve " + describeGoal(goal) + ": " + goal.object +
                            " is not movable");
      }
      if (goal.kind == GoalKind::kDisplaced && goal.displacement.norm() <= 0.0) {
        throw PlanningError("offline planner: " + describeGoal(goal) + " moves it nowhere");
      }
      if (goal.kind == GoalKind::kFacing && !goal.target.empty()) requireObject(goal.target);
      validatePoseGoal(goal, options_);
    }
  }

  void requireObject(const std::string& name) const {
    if (!initial_.hasObject(name)) {
      std::string names;
      for (const std::string& object : initial_.objects) names += (names.empty() ? "" : ", ") + object;
      throw PlanningError("offline planner: unknown object \"" + name + "\" (objects: " + names + ")");
    }
  }

  bool initiallyTrue(const Goal& goal) const {
    World world{initial_, {}, {}, options_.layout};
    return goal.kind != GoalKind::kDisplaced && goal.kind != GoalKind::kTurned && !isDirectional(goal) &&
           holds(goal, 0, world);
  }

  bool search(const World& world, std::vector<bool>& used, int& budget, World& result) {
    if (std::all_of(used.begin(), used.end(), [](bool value) { return value; })) {
      return finalStateHolds(world, result);
    }
    for (std::size_t index = 0; index < goals_.size(); ++index) {
      if (used[index] || !mayComeNext(index, used)) continue;
      if (--budget < 0) return false;
      World next = world;
      try {
        achieve(index, next);
      } catch (const SequencingFailure& failure) {
        if (firstFailure_.empty()) firstFailure_ = failure.what();
        continue;
      }
      used[index] = true;
      if (search(next, used, budget, result)) return true;
      used[index] = false;
    }
    return false;
  }

  bool finalStateHolds(const World& world, World& result) {
    for (std::size_t index = 0; index < goals_.size(); ++index) {
      if (isTransient(index) || holds(goals_[index], index, world)) continue;
      if (firstFailure_.empty()) {
        firstFailure_ = describeGoal(goals_[index]) + " no longer holds at the end";
      }
      return false;
    }
    result = world;
    return true;
  }

  /// A goal that a later goal of the instruction undoes: it only has to hold when reached.
  bool isTransient(std::size_t index) const {
    const Goal& goal = goals_[index];
    for (std::size_t later = index + 1; later < goals_.size(); ++later) {
      if (goal.kind == GoalKind::kAtConfiguration) return true;
      if (!goal.object.empty() && goals_[later].object == goal.object) return true;
      if (isDirectional(goal) && goals_[later].object == goal.target) return true;
    }
    return false;
  }

  /// Goals on the same object, and moves to a configuration, keep the instruction's order.
  bool mayComeNext(std::size_t index, const std::vector<bool>& used) const {
    for (std::size_t earlier = 0; earlier < index; ++earlier) {
      if (used[earlier]) continue;
      const Goal& first = goals_[earlier];
      const Goal& second = goals_[index];
      const bool ordered = first.kind == GoalKind::kAtConfiguration ||
                           second.kind == GoalKind::kAtConfiguration ||
                           (!first.object.empty() && first.object == second.object);
      if (ordered) return false;
    }
    return true;
  }

  bool holds(const Goal& goal, std::size_t index, const World& world) const {
    const SymbolicState& state = world.state;
    switch (goal.kind) {
      case GoalKind::kRelation:
        if (goal.relation == SpatialRelation::kIn) return lookup(state.inside, goal.object) == goal.target;
        if (goal.relation == SpatialRelation::kOn && goal.region) {
          return lookup(state.onTopOf, goal.object) == goal.target && (world.achieved.count(index) > 0 || standsInRegion(goal, world));
        }
        if (goal.relation == SpatialRelation::kOn) return lookup(state.onTopOf, goal.object) == goal.target;
        return world.achieved.count(index) > 0;
      case GoalKind::kHolding: return state.held == goal.object;
      case GoalKind::kDisplaced:
      case GoalKind::kHandedOver: return world.achieved.count(index) > 0;
      case GoalKind::kAtConfiguration: return state.atConfiguration == goal.configuration;
      case GoalKind::kAtPosition: {
        const auto at = world.layout.find(goal.object);
        return at != world.layout.end() && goal.position && world.state.held != goal.object && !at->second.placeUnknown &&
               (at->second.origin - *goal.position).head<2>().norm() <= kSamePlace;
      }
      case GoalKind::kTurned: return world.achieved.count(index) > 0;
      case GoalKind::kFacing: {
        const std::optional<double> turn = facingTurn(world.layout, goal);
        return turn && std::abs(*turn) < kTurnTolerance / 2.0;
      }
      case GoalKind::kArranged: return false;  // reached through its members' places
    }
    return false;
  }

  /// True when the object's centre stands in the goal's region of the reachable top (as the goal
  /// check measures it, without its slack).
  static bool standsInRegion(const Goal& goal, const World& world) {
    const auto at = world.layout.find(goal.object);
    const auto area = world.state.reachableTops.find(goal.target);
    if (at == world.layout.end() || at->second.placeUnknown || area == world.state.reachableTops.end()) return false;
    const AlignedBox3 box = regionBox(area->second, *goal.region);
    const Vector3 centre = at->second.bounds.center();
    return centre.x() >= box.min().x() && centre.x() <= box.max().x() && centre.y() >= box.min().y() && centre.y() <= box.max().y();
  }

  static std::string lookup(const std::map<std::string, std::string>& map, const std::string& key) {
    const auto found = map.find(key);
    return found == map.end() ? std::string() : found->second;
  }

  void achieve(std::size_t index, World& world) {
    const Goal& goal = goals_[index];
    const bool repeatable = goal.kind == GoalKind::kDisplaced || goal.kind == GoalKind::kHandedOver || goal.kind == GoalKind::kTurned;
    if (!repeatable && holds(goal, index, world)) return;
    switch (goal.kind) {
      case GoalKind::kRelation: achieveRelation(index, world); return;
      case GoalKind::kHolding: hold(world, goal.object); return;
      case GoalKind::kDisplaced: push(index, world); return;
      case GoalKind::kAtConfiguration: moveTo(world, goal.configuration); return;
      case GoalKind::kHandedOver: handOver(index, world); return;
      case GoalKind::kAtPosition: moveToPosition(goal, world); return;
      case GoalKind::kTurned: turn(goal.object, goal.angle, world); world.achieved.insert(index); return;
      case GoalKind::kFacing: turn(goal.object, turnToFace(world, goal), world); return;
      case GoalKind::kArranged:
        throw SequencingFailure("an arrangement is planned through its members' places (the specification's steps), not by itself");
    }
  }

  double turnToFace(const World& world, const Goal& goal) const {
    const std::optional<double> turn = facingTurn(world.layout, goal);
    if (!turn) throw SequencingFailure("where " + goal.object + " and " + goal.target + " stand is not known");
    return *turn;
  }

  static const ObjectLayout& layoutOf(const World& world, const std::string& object) {
    const auto found = world.layout.find(object);
    if (found == world.layout.end()) throw SequencingFailure("where " + object + " stands is not known");
    return found->second;
  }

  /// Puts the object where the goal says, setting aside first whatever stands there.
  void moveToPosition(const Goal& goal, World& world) {
    const ObjectLayout& mine = layoutOf(world, goal.object);
    // A position well above where it stands puts it onto what stands there (a pyramid's top).
    const double rise = goal.position->z() - mine.origin.z();
    const bool raised = rise > kRaisedPosition;
    const Vector3 shift(goal.position->x() - mine.origin.x(), goal.position->y() - mine.origin.y(), raised ? rise : 0.0);
    const AlignedBox3 spot = shifted(mine.bounds, shift);
    for (const std::string& other : standingIn(world.layout, spot, initial_.objects, {goal.object, world.state.held}, initial_.supports)) {
      if (!world.state.movable.count(other)) {
        throw SequencingFailure("the place for " + goal.object + " is taken by " + other + ", which is not movable");
      }
      setAside(world, other);
    }
    const std::optional<std::string> below = raised ? restingUnder(world.layout, spot, goal.object) : std::nullopt;
    const std::string support = below ? *below : supportBelow(world.state, goal.object);
    hold(world, goal.object);
    placeAt(world, goal.object, *goal.position, std::nullopt, support);
  }

  /// Places the held `object` with its origin at `origin` (base frame), turned by `turn` about
  /// the vertical when given, on `support`; the layout follows.
  void placeAt(World& world, const std::string& object, const Vector3& origin, std::optional<double> turn,
               const std::string& support) const {
    ActionParams params;
    params.position = origin;
    if (turn) params.orientation = Quaternion(verticalTurn(*turn) * layoutOf(world, object).orientation.toRotationMatrix());
    place(world, object, params, false, support);
    moveLayout(world.layout, object, origin, turn);
  }

  /// Moves `object` to the nearest free spot of its support, clear of every other object and of
  /// every place an at_position goal wants for another object.
  void setAside(World& world, const std::string& object) {
    const std::string support = supportBelow(world.state, object);
    const auto area = options_.supportAreas.find(support);
    if (area == options_.supportAreas.end()) throw SequencingFailure("no free spot is known on " + support + " to set " + object + " aside");
    const ObjectLayout layout = layoutOf(world, object);
    const std::vector<AlignedBox3> occupied = placesTaken(world.layout, goals_, object, world.state.held, initial_.supports);
    const auto skipped = options_.skippedSpots.find(object);
    const std::size_t skip = skipped == options_.skippedSpots.end() ? 0 : static_cast<std::size_t>(std::max(skipped->second, 0));
    const std::vector<Vector3> spots =
        freeSpots(layout.bounds.sizes(), area->second, occupied, layout.bounds.center(), options_.asideGap, skip + 1);
    if (spots.size() <= skip) throw SequencingFailure("no free spot on " + support + " to set " + object + " aside");
    const Vector3 spot = spots[skip];
    const Vector3 origin(layout.origin.x() + spot.x() - layout.bounds.center().x(),
                         layout.origin.y() + spot.y() - layout.bounds.center().y(), layout.origin.z());
    hold(world, object);
    placeAt(world, object, origin, std::nullopt, support);
  }

  /// Picks `object` and puts it back where it stood turned by `angle` (in turnSteps steps).
  void turn(const std::string& object, double angle, World& world) {
    const auto found = options_.turnSteps.find(object);
    const int steps = found == options_.turnSteps.end() ? 1 : std::max(found->second, 1);
    for (int step = 0; step < steps; ++step) {
      const std::string support = supportBelow(world.state, object);
      hold(world, object);
      const ObjectLayout layout = layoutOf(world, object);
      if (layout.placeUnknown) throw SequencingFailure("where " + object + " stands is chosen by the grounding: it cannot be turned in place");
      placeAt(world, object, layout.origin, angle / steps, support);
    }
  }

  /// Holds the object out at the handover position (picking it first).
  void handOver(std::size_t index, World& world) {
    const Goal& goal = goals_[index];
    hold(world, goal.object);
    SymbolicAction action;
    action.type = ActionType::kMove;
    action.object = goal.object;
    action.params.position = handoverToolPosition();
    action.planner = plannerFor(goal.object);
    world.actions.push_back(action);
    world.state.atConfiguration.clear();
    world.achieved.insert(index);
  }

  void achieveRelation(std::size_t index, World& world) {
    const Goal& goal = goals_[index];
    SymbolicState& state = world.state;
    if (goal.relation == SpatialRelation::kOn && !state.supports.count(goal.target)) {
      clear(world, goal.target, 0);
    }
    if (goal.relation == SpatialRelation::kIn) makeRoom(world, goal.target, goal.object);
    hold(world, goal.object);
    if (state.held == goal.target) {
      throw SequencingFailure("cannot put " + goal.object + " relative to " + goal.target +
                              " while holding it");
    }
    ActionParams params;
    params.relation = goal.relation;
    params.target = goal.target;
    params.distance = goal.distance;
    params.region = goal.region;
    const std::string restingOn = isDirectional(goal) ? supportBelow(state, goal.target) : goal.target;
    place(world, goal.object, params, goal.relation == SpatialRelation::kIn, restingOn);
    if (isDirectional(goal) || goal.region) world.achieved.insert(index);
  }

  void push(std::size_t index, World& world) {
    const Goal& goal = goals_[index];
    const auto layout = world.layout.find(goal.object);
    if (world.state.held == goal.object && layout != world.layout.end()) {  // "lift it and move it 10 cm left": carried
      placeAt(world, goal.object, layout->second.origin + goal.displacement, std::nullopt, supportBelow(world.state, goal.object));
      world.achieved.insert(index);
      return;
    }
    freeGripper(world);
    SymbolicAction action;
    action.type = ActionType::kPush;
    action.object = goal.object;
    action.params.direction = goal.displacement.normalized();
    action.params.distance = goal.displacement.norm();
    action.planner = plannerFor(goal.object);
    world.actions.push_back(action);
    world.state.atConfiguration.clear();
    disturb(world, goal.object);
    if (const auto at = world.layout.find(goal.object); at != world.layout.end()) {
      moveLayout(world.layout, goal.object, at->second.origin + goal.displacement, std::nullopt);
    }
    world.achieved.insert(index);
  }

  void moveTo(World& world, const std::string& configuration) const {
    SymbolicAction action;
    action.type = ActionType::kMove;
    action.params.configuration = configuration;
    action.planner = plannerFor("");
    world.actions.push_back(action);
    world.state.atConfiguration = configuration;
  }

  /// Picks `object` unless it is held: frees the gripper and clears the object first.
  void hold(World& world, const std::string& object) {
    if (world.state.held == object) return;
    if (!world.state.movable.count(object)) {
      throw SequencingFailure("cannot pick " + object + ": it is not movable");
    }
    freeGripper(world);
    clear(world, object, 0);
    SymbolicAction action;
    action.type = ActionType::kPick;
    action.object = object;
    if (const auto grasp = specification_.grasps.find(object); grasp != specification_.grasps.end()) {
      action.refinements.grasp = grasp->second;
    }
    action.planner = plannerFor(object);
    world.actions.push_back(action);
    world.state.inside.erase(object);
    world.state.onTopOf.erase(object);
    world.state.held = object;
    world.state.atConfiguration.clear();
    disturb(world, object);
  }

  void place(World& world, const std::string& object, const ActionParams& params, bool inside,
             const std::string& restingOn) const {
    SymbolicAction action;
    action.type = ActionType::kPlace;
    action.object = object;
    action.params = params;
    action.planner = plannerFor(object);
    world.actions.push_back(action);
    if (inside) world.state.inside[object] = restingOn;
    else world.state.onTopOf[object] = restingOn;
    if (const auto at = world.layout.find(object); params.relation && at != world.layout.end()) {
      at->second.placeUnknown = true;  // where exactly is the grounding's choice
    }
    world.state.held.clear();
    world.state.atConfiguration.clear();
  }

  void putOnSupport(World& world, const std::string& object, const std::string& support) {
    hold(world, object);
    ActionParams params;
    params.relation = SpatialRelation::kOn;
    params.target = support;
    place(world, object, params, false, support);
  }

  void freeGripper(World& world) {
    if (world.state.held.empty()) return;
    putOnSupport(world, world.state.held, supportBelow(world.state, world.state.held));
  }

  /// Moves whatever rests on or in `object` to the support under it.
  void clear(World& world, const std::string& object, std::size_t depth) {
    if (depth > initial_.objects.size()) {
      throw SequencingFailure("objects rest on each other in a cycle at " + object);
    }
    for (const std::string& blocker : inSceneOrder(world.state.objectsOn(object))) {
      if (!world.state.movable.count(blocker)) {
        throw SequencingFailure("cannot clear " + object + ": " + blocker + " on it is not movable");
      }
      clear(world, blocker, depth + 1);
      putOnSupport(world, blocker, supportBelow(world.state, object));
    }
  }

  /// Takes objects out of `container` until `object` fits (when its room is known).
  void makeRoom(World& world, const std::string& container, const std::string& object) {
    const auto area = options_.containerFloorArea.find(container);
    if (area == options_.containerFloorArea.end()) return;
    const double needed = footprint(object);
    if (needed > area->second) {
      throw SequencingFailure(object + " does not fit in " + container);
    }
    std::vector<std::string> contents;
    for (const auto& [item, holder] : world.state.inside) {
      if (holder == container && item != object) contents.push_back(item);
    }
    contents = inSceneOrder(contents);
    double used = 0.0;
    for (const std::string& item : contents) used += footprint(item);
    for (const std::string& item : contents) {
      if (used + needed <= area->second) break;
      putOnSupport(world, item, supportBelow(world.state, container));
      used -= footprint(item);
    }
  }

  double footprint(const std::string& object) const {
    const auto found = options_.objectFootprint.find(object);
    return found == options_.objectFootprint.end() ? 0.0 : found->second;
  }

  /// The support at the bottom of the pile `object` is in (the first support when none).
  std::string supportBelow(const SymbolicState& state, const std::string& object) const {
    std::string current = object;
    for (std::size_t step = 0; step <= initial_.objects.size(); ++step) {
      if (state.supports.count(current)) return current;
      std::string below = lookup(state.inside, current);
      if (below.empty()) below = lookup(state.onTopOf, current);
      if (below.empty()) break;
      current = below;
    }
    for (const std::string& name : initial_.objects) {
      if (state.supports.count(name)) return name;
    }
    throw SequencingFailure("nowhere to put " + object + " down: the scene has no support");
  }

  /// Forgets goals that moving `object` undoes.
  void disturb(World& world, const std::string& object) const {
    for (std::size_t index = 0; index < goals_.size(); ++index) {
      const Goal& goal = goals_[index];
      if (goal.object == object || (isDirectional(goal) && goal.target == object)) {
        world.achieved.erase(index);
      }
    }
  }

  std::vector<std::string> inSceneOrder(const std::vector<std::string>& names) const {
    std::vector<std::string> ordered;
    for (const std::string& name : initial_.objects) {
      if (std::find(names.begin(), names.end(), name) != names.end()) ordered.push_back(name);
    }
    return ordered;
  }

  std::string plannerFor(const std::string& object) const {
    const auto found = specification_.planners.find(object);
    return found == specification_.planners.end() ? specification_.defaultPlanner : found->second;
  }

  std::string reasoning() const {
    std::string text = "offline planner; goals:";
    for (std::size_t index = 0; index < goals_.size(); ++index) {
      text += (index == 0 ? " " : "; ") + describeGoal(goals_[index]);
      if (initiallyTrue(goals_[index])) text += " (already true)";
    }
    if (!specification_.corrections.empty()) text += "; " + specification_.corrections;
    return text;
  }

  const TaskSpecification& specification_;
  const std::vector<Goal>& goals_;
  const SymbolicState& initial_;
  const SequencingOptions& options_;
  std::string firstFailure_;
};

}  // namespace

Plan sequenceGoals(const TaskSpecification& specification, const SymbolicState& state,
                   const SequencingOptions& options) {
  return Sequencer(specification, state, options).run();
}

}  // namespace lang2manip
