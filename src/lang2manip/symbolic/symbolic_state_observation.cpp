#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "lang2manip/model/scene.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"
#include "lang2manip/symbolic/surface_region.hpp"
#include "lang2manip/symbolic/resting_height.hpp"
#include "lang2manip/symbolic/support_surface.hpp"

namespace lang2manip {
namespace {

bool isInsideCavity(const SceneObject& item, const SceneObject& container,
                    const SymbolicStateTolerances& tolerances) {
  if (!container.cavity) return false;
  const Vector3 centre = container.pose.inverse() * item.worldBounds().center();
  const AlignedBox3& cavity = *container.cavity;
  return centre.x() >= cavity.min().x() && centre.x() <= cavity.max().x() &&
         centre.y() >= cavity.min().y() && centre.y() <= cavity.max().y() &&
         centre.z() >= cavity.min().z() - tolerances.cavityMargin &&
         centre.z() <= cavity.max().z();
}

std::optional<std::string> containerOf(const Scene& scene, const SceneObject& item,
                                       const SymbolicStateTolerances& tolerances) {
  for (const SceneObject& other : scene.objects()) {
    if (other.name != item.name && isInsideCavity(item, other, tolerances)) return other.name;
  }
  return std::nullopt;
}

std::optional<std::string> supportOf(const Scene& scene, const SceneObject& item,
                                     const SymbolicStateTolerances& tolerances) {
  const AlignedBox3 bounds = item.worldBounds();
  const Vector3 bottom(bounds.center().x(), bounds.center().y(), bounds.min().z());
  std::optional<std::string> best;
  double bestTop = -std::numeric_limits<double>::infinity();
  for (const SceneObject& other : scene.objects()) {
    if (other.name == item.name) continue;
    const std::optional<double> height = restingHeight(other, bottom, tolerances.contactGap);
    if (height && *height > bestTop) {
      best = other.name;
      bestTop = *height;
    }
  }
  if (best) return best;
  std::vector<AlignedBox3> below;
  std::vector<const SceneObject*> owners;
  for (const SceneObject& other : scene.objects()) {
    if (other.name == item.name) continue;
    below.push_back(other.worldBounds());
    owners.push_back(&other);
  }
  if (const auto bridged = bridgedSupport(bounds, below, tolerances.contactGap)) return owners[*bridged]->name;
  return std::nullopt;
}

bool isArmJoint(const RobotModel& model, const std::string& joint) {
  for (const Manipulator& arm : model.semantics().manipulators) {
    if (std::find(arm.armJoints.begin(), arm.armJoints.end(), joint) != arm.armJoints.end()) return true;
  }
  return false;
}

/// Names of the named states that set at least one arm joint, in SRDF order, without repeats.
std::vector<std::string> armConfigurationNames(const RobotModel& model) {
  std::vector<std::string> names;
  for (const NamedState& state : model.semantics().namedStates) {
    const bool setsArm = std::any_of(state.values.begin(), state.values.end(),
                                     [&](const auto& value) { return isArmJoint(model, value.first); });
    if (setsArm && std::find(names.begin(), names.end(), state.name) == names.end()) {
      names.push_back(state.name);
    }
  }
  return names;
}

bool matchesNamedState(const SceneRobot& robot, const std::string& name, double tolerance) {
  const RobotModel& model = *robot.model;
  for (const NamedState& state : model.semantics().namedStates) {
    if (state.name != name) continue;
    for (const auto& [joint, value] : state.values) {
      const auto index = model.findJoint(joint);
      if (!index || !isArmJoint(model, joint)) continue;
      const int variable = model.variableOfJoint(*index);
      if (variable < 0) continue;
      if (std::abs(robot.configuration[variable] - value) > tolerance) return false;
    }
  }
  return true;
}

void observeConfiguration(const SceneRobot& robot, const SymbolicStateTolerances& tolerances,
                          SymbolicState& state) {
  for (const std::string& name : armConfigurationNames(*robot.model)) {
    state.namedConfigurations.insert(name);
    if (state.atConfiguration.empty() && matchesNamedState(robot, name, tolerances.configurationTolerance)) {
      state.atConfiguration = name;
    }
  }
}

}  // namespace

SymbolicState observeSymbolicState(const Scene& scene, const SymbolicStateTolerances& tolerances,
                                   const std::string& robot, const std::string& arm) {
  SymbolicState state;
  for (const SceneObject& object : scene.objects()) {
    state.objects.push_back(object.name);
    if (object.movable) state.movable.insert(object.name);
    if (object.role == ObjectRole::kContainer) state.containers.insert(object.name);
    if (object.role == ObjectRole::kSupport) state.supports.insert(object.name);
    if (object.movable) {
      const bool upright = std::abs(object.pose.linear()(2, 2)) > 0.996;  // its frame's z within 5 deg of vertical
      state.sizes[object.name] = upright ? object.dimensions() : object.worldBounds().sizes();
    }
    const SupportSurface surface = supportSurface(object);
    if (surface.top) state.flatTops[object.name] = *surface.top;
    else state.noFlatTop[object.name] = surface.why;
    if (object.role == ObjectRole::kSupport && surface.top) {
      if (const auto area = supportArea(scene, object.name, robot, nullptr, arm)) state.reachableTops[object.name] = area->reachable;
    }
  }
  if (!robot.empty()) {
    observeConfiguration(scene.robot(robot), tolerances, state);
  } else if (!scene.robots().empty()) {
    observeConfiguration(scene.robots().front(), tolerances, state);
  }
  for (const Attachment& attachment : scene.attachments()) {
    if (robot.empty() || attachment.robot == robot) state.held = attachment.object;
  }
  for (const SceneObject& object : scene.objects()) {
    if (object.name == state.held) continue;
    if (auto container = containerOf(scene, object, tolerances)) {
      state.inside[object.name] = *container;
    } else if (auto support = supportOf(scene, object, tolerances)) {
      state.onTopOf[object.name] = *support;
    }
  }
  return state;
}

}  // namespace lang2manip
