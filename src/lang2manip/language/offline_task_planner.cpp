#include "lang2manip/language/offline_task_planner.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <set>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/symbolic/plan_validation.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"
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

/// True when the action that failed in `attempt` is a push (at whatever stage: reaching behind
/// the object, the push itself).
bool failedAPush(const PlanAttempt& attempt) {
  if (!attempt.plan || !attempt.grounding || attempt.grounding->object.empty()) return false;
  const std::size_t index = attempt.grounding->actionIndex;
  return index < attempt.plan->actions.size() && attempt.plan->actions[index].type == ActionType::kPush;
}

/// What the earlier attempts changed: the objects displaced by pick and place instead of a push.
struct Answers {
  std::set<std::string> pickedInsteadOfPushed;
};

/// Changes `specification` for every failure of the earlier attempts, as the planner answered
/// them in turn: a push that failed becomes a pick and place by the same displacement; any other
/// failure moves the failed object to its next untried grasp direction.
Answers applyEarlierAttempts(const PlanningRequest& request, TaskSpecification& specification) {
  Answers answers;
  const std::map<std::string, GraspDirection> requested = specification.grasps;
  std::map<std::string, std::vector<GraspDirection>> tried;
  const std::vector<GraspDirection> order = graspRetryOrder();
  for (const PlanAttempt& attempt : request.earlierAttempts) {
    if (failedAPush(attempt)) {
      if (!answers.pickedInsteadOfPushed.insert(attempt.grounding->object).second) {
        nothingNewToTry("pushing " + attempt.grounding->object + " and carrying it both failed", attempt.failure);
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

SequencingOptions sequencingOptionsFor(const Scene& scene) {
  SequencingOptions options;
  for (const SceneObject& object : scene.objects()) {
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
    objects = describeObjects(scene, request.robot);
  } catch (const InputError& error) {
    throw PlanningError(std::string("offline planner: ") + error.what());
  }
  TaskSpecification specification = understandInstruction(request.task, objects);
  const SymbolicState state = observeSymbolicState(scene);
  const SequencingOptions options = sequencingOptionsFor(scene);
  const Answers answers = applyEarlierAttempts(request, specification);
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
