#include "lang2manip/language/offline_task_planner.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <set>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/symbolic/object_heading.hpp"
#include "lang2manip/symbolic/plan_validation.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"
#include "lang2manip/symbolic/support_surface.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"

namespace lang2manip {
namespace {

[[noreturn]] void nothingNewToTry(const std::string& why, const std::string& lastFailure) {
  throw PlanningError("offline planner: nothing new to try: " + why + " (last failure: " +
                      lastFailure + "); try an LLM backend with --llm");
}


bool picks(const Plan& plan, const std::string& object) {
  return std::any_of(plan.actions.begin(), plan.actions.end(), [&](const SymbolicAction& action) {
    return action.type == ActionType::kPick && action.object == object;
  });
}

/// The object of a failed plan whose grasp the next try changes: the one the failed action is
/// about, when the plan picks it and the failure is one another grasp may fix (not a request the
/// world does not allow, not every position taken by other objects).
const std::string& objectToRegrasp(const PlanAttempt& attempt) {
  if (!attempt.plan || !attempt.grounding) {
    nothingNewToTry("the failure is not one of executing its plan", attempt.failure);
  }
  const GroundingFailure& failure = *attempt.grounding;
  if (failure.objectUngraspable) nothingNewToTry("no grasp of " + failure.object + " exists", attempt.failure);
  if (failure.stage == "precondition") {
    nothingNewToTry("the plan asks for something the world does not allow", attempt.failure);
  }
  if (!failure.blockingObjects.empty()) {
    nothingNewToTry("every position for " + failure.object + " is taken by " + joinedNames(failure.blockingObjects),
                    attempt.failure);
  }
  if (failure.object.empty() || !picks(*attempt.plan, failure.object)) {
    nothingNewToTry("the failure is not about an object the plan picks", attempt.failure);
  }
  return failure.object;
}

/// True when the arm that executes the request's plans (any arm, when none is named) has a
/// gripper: an arm without one pushes but cannot carry.
bool armCanCarry(const PlanningRequest& request) {
  if (request.scene == nullptr || request.scene->robots().empty()) return true;
  const SceneRobot& robot = request.robot.empty() ? request.scene->robots().front() : request.scene->robot(request.robot);
  const std::vector<Manipulator>& arms = robot.model->semantics().manipulators;
  return std::any_of(arms.begin(), arms.end(), [&](const Manipulator& arm) {
    return (request.arm.empty() || arm.name == request.arm) && !arm.gripperJoints.empty();
  });
}

/// True when the action that failed in `attempt` is a push (at whatever stage: reaching behind
/// the object, the push itself).
bool failedAPush(const PlanAttempt& attempt) {
  if (!attempt.plan || !attempt.grounding || attempt.grounding->object.empty()) return false;
  const std::size_t index = attempt.grounding->actionIndex;
  return index < attempt.plan->actions.size() && attempt.plan->actions[index].type == ActionType::kPush;
}

/// The failed action of `attempt` when it is a place at an explicit position (a turn, setting an
/// object aside, putting it where another stood).
const SymbolicAction* failedPlaceAtPosition(const PlanAttempt& attempt) {
  if (!attempt.plan || !attempt.grounding) return nullptr;
  const std::size_t index = attempt.grounding->actionIndex;
  if (index >= attempt.plan->actions.size()) return nullptr;
  const SymbolicAction& action = attempt.plan->actions[index];
  return action.type == ActionType::kPlace && action.params.position ? &action : nullptr;
}

/// The objects `plan` set aside up to its action `last`: placed at a position no goal asks for.
std::vector<std::string> objectsSetAside(const Plan& plan, std::size_t last, const TaskSpecification& specification) {
  std::vector<std::string> aside;
  for (std::size_t i = 0; i <= last && i < plan.actions.size(); ++i) {
    const SymbolicAction& action = plan.actions[i];
    if (action.type != ActionType::kPlace || !action.params.position || action.params.orientation) continue;
    const std::vector<Goal>& steps = specification.steps.empty() ? specification.goals : specification.steps;
    const bool wanted = std::any_of(steps.begin(), steps.end(), [&](const Goal& goal) {
      return goal.kind == GoalKind::kAtPosition && goal.object == action.object && goal.position &&
             (*goal.position - *action.params.position).head<2>().norm() < 0.01;
    });
    if (!wanted && std::find(aside.begin(), aside.end(), action.object) == aside.end()) aside.push_back(action.object);
  }
  return aside;
}

/// What the earlier attempts changed: the objects displaced by pick and place instead of a push,
/// the free spots passed over for objects set aside, the steps a turn is split into.
struct Answers {
  std::set<std::string> pickedInsteadOfPushed;
  std::map<std::string, int> skippedSpots;
  std::map<std::string, int> turnSteps;
  /// Targets whose objects go there in the reverse order (one placed earlier blocked a later one).
  std::set<std::string> reversedTargets;
};

/// The target of the failed place of `attempt` when every position there was taken by objects
/// the plan had put there before; empty otherwise.
std::string targetFilledBeforehand(const PlanAttempt& attempt) {
  if (!attempt.plan || !attempt.grounding || attempt.grounding->blockingObjects.empty()) return {};
  const std::vector<SymbolicAction>& actions = attempt.plan->actions;
  const std::size_t index = attempt.grounding->actionIndex;
  if (index >= actions.size() || actions[index].type != ActionType::kPlace || !actions[index].params.relation) return {};
  const std::string& target = actions[index].params.target;
  for (const std::string& blocker : attempt.grounding->blockingObjects) {
    const bool placedThere = std::any_of(actions.begin(), actions.begin() + static_cast<std::ptrdiff_t>(index), [&](const SymbolicAction& a) {
      return a.type == ActionType::kPlace && a.object == blocker && a.params.target == target;
    });
    if (!placedThere) return {};
  }
  return target;
}

/// `specification` with the objects of the goals into each of `targets` in the reverse order
/// (each goal keeps its place in the list; only which object it is about changes).
void reverseOrderInto(const std::set<std::string>& targets, TaskSpecification& specification) {
  for (std::vector<Goal>* goals : {&specification.goals, &specification.steps}) {
    for (const std::string& target : targets) {
      std::vector<std::size_t> indices;
      for (std::size_t i = 0; i < goals->size(); ++i) {
        if ((*goals)[i].kind == GoalKind::kRelation && (*goals)[i].target == target) indices.push_back(i);
      }
      for (std::size_t i = 0, j = indices.size(); i + 1 < j; ++i, --j) {
        std::swap((*goals)[indices[i]].object, (*goals)[indices[j - 1]].object);
      }
    }
  }
}

constexpr int kMostSpotsSkipped = 3;
constexpr int kMostTurnSteps = 4;

/// The answer to a failed place at a position: a turn in more steps (a regrasp between them), or
/// the next free spots for the objects set aside before it. False when neither applies.
bool answerPlaceAtPosition(const PlanAttempt& attempt, const TaskSpecification& specification, Answers& answers) {
  const SymbolicAction* place = failedPlaceAtPosition(attempt);
  if (place == nullptr) return false;
  if (place->params.orientation) {
    int& steps = answers.turnSteps[place->object];
    steps = steps == 0 ? 2 : steps * 2;
    if (steps > kMostTurnSteps) {
      nothingNewToTry("turning " + place->object + " in " + std::to_string(kMostTurnSteps) + " steps failed too", attempt.failure);
    }
    return true;
  }
  const std::vector<std::string> aside = objectsSetAside(*attempt.plan, attempt.grounding->actionIndex, specification);
  for (const std::string& object : aside) {
    if (++answers.skippedSpots[object] > kMostSpotsSkipped) {
      nothingNewToTry(std::to_string(kMostSpotsSkipped + 1) + " free spots for " + object + " have failed", attempt.failure);
    }
  }
  return !aside.empty();
}

/// Changes `specification` for every failure of the earlier attempts, as the planner answered
/// them in turn: a push that failed becomes a pick and place by the same displacement; a failed
/// turn is split into more steps; a failed place at a position after objects were set aside
/// sets them aside elsewhere; any other failure moves the failed object to its next untried
/// grasp direction.
Answers applyEarlierAttempts(const PlanningRequest& request, TaskSpecification& specification) {
  Answers answers;
  const std::map<std::string, GraspDirection> requested = specification.grasps;
  std::map<std::string, std::vector<GraspDirection>> tried;
  const std::vector<GraspDirection> order = graspRetryOrder();
  for (const PlanAttempt& attempt : request.earlierAttempts) {
    if (failedAPush(attempt)) {
      if (!armCanCarry(request)) {
        nothingNewToTry("the arm has no gripper to carry " + attempt.grounding->object + " instead of pushing it", attempt.failure);
      }
      if (!answers.pickedInsteadOfPushed.insert(attempt.grounding->object).second) {
        nothingNewToTry("pushing " + attempt.grounding->object + " and carrying it both failed", attempt.failure);
      }
      continue;
    }
    if (answerPlaceAtPosition(attempt, specification, answers)) continue;
    if (const std::string target = targetFilledBeforehand(attempt); !target.empty()) {
      // Blocked by what the plan put there first: the other order, unless the user gave one.
      if (specification.orderGiven) {
        nothingNewToTry("the instruction fixes the order in which things go into " + target, attempt.failure);
      }
      if (!answers.reversedTargets.insert(target).second) {
        nothingNewToTry("both orders of putting things into " + target + " failed", attempt.failure);
      }
      continue;
    }
    const std::string& object = objectToRegrasp(attempt);
    if (requested.count(object)) {
      nothingNewToTry("the instruction asks for a " + graspDirectionName(requested.at(object)) +
                          " grasp of " + object,
                      attempt.failure);
    }
    const auto current = specification.grasps.find(object);
    tried[object].push_back(current == specification.grasps.end() ? GraspDirection::kAuto
                                                                   : current->second);
    const auto untried = std::find_if(order.begin(), order.end(), [&](GraspDirection direction) {
      const auto& done = tried[object];
      return std::find(done.begin(), done.end(), direction) == done.end();
    });
    if (untried == order.end()) {
      nothingNewToTry("every grasp direction of " + object + " has failed", attempt.failure);
    }
    specification.grasps[object] = *untried;
  }
  return answers;
}

/// `plan` with the push of each object in `picked` replaced by a pick (with the grasp of
/// `specification`) and a place at the position the push would have left it (where it stands in
/// `scene` plus the displacement, base frame).
Plan carryInsteadOfPushing(const Plan& plan, const std::set<std::string>& picked, const TaskSpecification& specification,
                           const Scene& scene, const std::string& robot) {
  if (picked.empty()) return plan;
  const Pose base = robotBaseFrame(scene, robot);
  Plan carried = plan;
  carried.actions.clear();
  for (const SymbolicAction& action : plan.actions) {
    if (action.type != ActionType::kPush || !picked.count(action.object) || !action.params.direction || !action.params.distance) {
      carried.actions.push_back(action);
      continue;
    }
    SymbolicAction pick;
    pick.type = ActionType::kPick;
    pick.object = action.object;
    pick.planner = action.planner;
    SymbolicAction place = pick;
    if (const auto grasp = specification.grasps.find(action.object); grasp != specification.grasps.end()) {
      pick.refinements.grasp = grasp->second;
    }
    place.type = ActionType::kPlace;
    place.params.position = base.inverse() * scene.object(action.object).pose.translation() +
                            *action.params.direction * *action.params.distance;
    carried.actions.push_back(pick);
    carried.actions.push_back(place);
  }
  return carried;
}

double smallestCrossSection(const SceneObject& object) {
  Vector3 size = object.dimensions();
  std::sort(size.data(), size.data() + 3);
  return size[0] * size[1];
}

}  // namespace

SequencingOptions sequencingOptionsFor(const Scene& scene, const std::string& robot) {
  SequencingOptions options;
  const Pose toBase = robotBaseFrame(scene, robot).inverse();
  for (const SceneObject& object : scene.objects()) {
    ObjectLayout layout;
    layout.origin = toBase * object.pose.translation();
    layout.orientation = Quaternion(toBase.linear() * object.pose.linear());
    layout.bounds = object.worldBounds().transformed(toBase);
    if (const auto side = longSideYaw(object, layout.orientation.toRotationMatrix())) layout.longSideYaw = *side;
    layout.turnSymmetry = turnSymmetry(object);
    options.layout[object.name] = layout;
    if (object.role == ObjectRole::kSupport) {
      if (const SupportSurface surface = supportSurface(object); surface.top) {
        options.supportAreas[object.name] = surface.top->transformed(toBase);
      }
    }
    if (object.role == ObjectRole::kContainer && object.cavity) {
      const Vector3 size = object.cavity->sizes();
      options.containerFloorArea[object.name] = size.x() * size.y();
    }
    if (object.movable) options.objectFootprint[object.name] = smallestCrossSection(object);
  }
  return options;
}

std::vector<GraspDirection> graspRetryOrder() {
  return {GraspDirection::kAuto, GraspDirection::kTop, GraspDirection::kSide,
          GraspDirection::kFront};
}

Plan OfflineTaskPlanner::plan(const PlanningRequest& request, const StopCondition& stop,
                              PlanningStatistics& statistics) {
  const auto start = std::chrono::steady_clock::now();
  if (request.scene == nullptr) throw PlanningError("offline planner: the request has no scene");
  if (stop.shouldStop()) throw PlanningError("offline planner: stopped before planning");
  const Scene& scene = *request.scene;
  std::vector<ObjectDescriptor> objects;
  try {
    objects = describeObjects(scene, request.robot, request.arm);
  } catch (const InputError& error) {
    throw PlanningError(std::string("offline planner: ") + error.what());
  }
  TaskSpecification specification = understandInstruction(request.task, objects);
  const SymbolicState state = observeSymbolicState(scene, {}, request.robot, request.arm);
  SequencingOptions options = sequencingOptionsFor(scene, request.robot);
  const Answers answers = applyEarlierAttempts(request, specification);
  reverseOrderInto(answers.reversedTargets, specification);
  options.skippedSpots = answers.skippedSpots;
  options.turnSteps = answers.turnSteps;
  Plan plan = carryInsteadOfPushing(sequenceGoals(specification, state, options), answers.pickedInsteadOfPushed,
                                    specification, scene, request.robot);
  plan.goals = specification.goals;
  // What the world does not allow (an object on a round top, one too large for the top it is
  // put on) is refused here, with the reason, rather than tried.
  if (const PlanValidation validation = validatePlan(plan, state); !validation.valid()) {
    throw PlanningError("offline planner: the instruction asks for what cannot be done: " + validation.summary());
  }
  statistics.planningSeconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return plan;
}

}  // namespace lang2manip
