#include "lang2manip/language/offline_task_planner.hpp"

#include <algorithm>
#include <chrono>
#include <map>

#include "lang2manip/core/error.hpp"
#include "lang2manip/language/instruction.hpp"
#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/language/words.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"

namespace lang2manip {
namespace {

/// True when a failure text is about grasping or reaching an object, which another grasp
/// direction may fix.
bool isGraspRelated(const std::string& failure) {
  const Words words = tokenize(failure);
  static const std::vector<std::string> markers{"grasp", "grasps", "ik", "reach", "reachable",
                                                "unreachable", "kinematics", "approach"};
  return std::any_of(words.begin(), words.end(), [](const std::string& word) {
    return std::find(markers.begin(), markers.end(), word) != markers.end();
  });
}

/// The first picked object of `plan` named in `failure` (by position in the text).
std::string failedObject(const std::string& failure, const Plan& plan) {
  const Words words = tokenize(failure);
  std::size_t bestPosition = words.size();
  std::string best;
  for (const SymbolicAction& action : plan.actions) {
    if (action.type != ActionType::kPick) continue;
    const Words name = tokenize(action.object);
    for (std::size_t at = 0; at < bestPosition; ++at) {
      if (matchesAt(words, at, name)) {
        bestPosition = at;
        best = action.object;
        break;
      }
    }
  }
  return best;
}

[[noreturn]] void nothingNewToTry(const std::string& why, const std::string& lastFailure) {
  throw PlanningError("offline planner: nothing new to try: " + why + " (last failure: " +
                      lastFailure + "); try an LLM backend with --llm");
}

/// Changes the grasps of `specification` for every grasp failure of the earlier attempts, as
/// the planner answered them in turn: each failure moves the failed object to its next untried
/// grasp direction.
void applyEarlierAttempts(const PlanningRequest& request, TaskSpecification& specification,
                          const Plan& firstPlan) {
  const std::map<std::string, GraspDirection> requested = specification.grasps;
  std::map<std::string, std::vector<GraspDirection>> tried;
  const std::vector<GraspDirection> order = graspRetryOrder();
  for (const PlanAttempt& attempt : request.earlierAttempts) {
    const std::string object = failedObject(attempt.failure, firstPlan);
    if (object.empty() || !isGraspRelated(attempt.failure)) {
      nothingNewToTry("the failure is not about grasping an object of the plan", attempt.failure);
    }
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
  Plan plan = sequenceGoals(specification, state, options);
  if (!request.earlierAttempts.empty()) {
    applyEarlierAttempts(request, specification, plan);
    plan = sequenceGoals(specification, state, options);
  }
  statistics.planningSeconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return plan;
}

}  // namespace lang2manip
