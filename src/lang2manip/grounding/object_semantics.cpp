#include "lang2manip/grounding/object_semantics.hpp"

#include <algorithm>
#include <cstdio>
#include <optional>

#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/collision/shape_probe.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/grounding/gripper_geometry.hpp"
#include "lang2manip/grounding/object_geometry.hpp"

namespace lang2manip {
namespace {

/// A container's hollow is at least this fraction of its height deep.
constexpr double kMinimumHollowFraction = 0.4;
/// Bodies lower or narrower than this are not containers (m).
constexpr double kMinimumContainerSize = 0.02;
constexpr int kBisections = 20;

/// The largest value in [0, limit] for which `free(value)` holds, assuming it holds up to some
/// value and not beyond (0 when it never holds).
template <typename Predicate>
double largestFree(double limit, Predicate free) {
  if (free(limit)) return limit;
  double low = 0.0, high = limit;
  for (int i = 0; i < kBisections; ++i) {
    const double middle = 0.5 * (low + high);
    (free(middle) ? low : high) = middle;
  }
  return low;
}

AlignedBox3 box(const Vector3& low, const Vector3& high) { return AlignedBox3(low, high); }

/// The box of the hollow above `floor` with its footprint grown from the centre: a square first
/// (a round or tapered hollow has room along its diagonals too), then along x, then along y.
AlignedBox3 cavityBoxAbove(const ShapeProbe& probe, const Vector3& c, const Vector3& size, double floor, double top) {
  const auto free = [&](double halfX, double halfY) {
    return !probe.hits(box({c.x() - halfX, c.y() - halfY, floor + 1e-3}, {c.x() + halfX, c.y() + halfY, top}));
  };
  const double square = largestFree(0.5 * std::min(size.x(), size.y()), [&](double e) { return free(e, e); });
  const double halfX = std::max(square, largestFree(0.5 * size.x(), [&](double e) { return free(e, square); }));
  const double halfY = std::max(square, largestFree(0.5 * size.y(), [&](double e) { return free(halfX, e); }));
  return box({c.x() - halfX, c.y() - halfY, floor}, {c.x() + halfX, c.y() + halfY, top});
}

/// The cavity box of the hollow whose floor is at `floor` (its lowest point under the centre):
/// among floors raised by tenths of the depth up to half of it, the one whose box holds the most
/// (footprint area times height). Vertical walls keep the floor; a round or tapered bowl raises
/// it to where its walls are wide enough (about 0.42 of the depth for a hemisphere).
AlignedBox3 largestCavityBox(const ShapeProbe& probe, const Vector3& c, const Vector3& size, double floor, double top) {
  AlignedBox3 best = cavityBoxAbove(probe, c, size, floor, top);
  const auto volume = [](const AlignedBox3& b) { return b.sizes().prod(); };
  for (int tenth = 1; tenth <= 5; ++tenth) {
    const AlignedBox3 raised = cavityBoxAbove(probe, c, size, floor + 0.1 * tenth * (top - floor), top);
    if (volume(raised) > volume(best) * (1.0 + 1e-6)) best = raised;
  }
  return best;
}

bool isWideAndFlat(const SceneObject& object) {
  const Vector3 size = object.worldBounds().sizes();
  return size.x() >= 0.3 && size.y() >= 0.3 && size.z() <= std::max(size.x(), size.y());
}

/// The widest opening of any gripper of the scene's robots (0 when none has one).
double widestGripper(const Scene& scene) {
  double widest = 0.0;
  for (const SceneRobot& robot : scene.robots()) {
    for (const Manipulator& manipulator : robot.model->semantics().manipulators) {
      try {
        widest = std::max(widest, describeGripper(*robot.model, manipulator.name).maxOpening);
      } catch (const InputError&) {
        // A gripper that cannot grasp holds nothing; grounding reports it when a pick needs it.
      }
    }
  }
  return widest;
}

ObjectSemanticsDecision infer(const Scene& scene, SceneObject& object, double widest) {
  ObjectSemanticsDecision decision{object.name, false, ObjectRole::kNone, SemanticsSource::kInferred, {}};
  object.movable = false;
  if (const std::optional<AlignedBox3> hollow = measuredCavity(object)) {
    object.role = ObjectRole::kContainer;
    object.cavity = *hollow;
    decision.reason = "container: open hollow " + metresText(hollow->sizes().z()) + " deep";
  } else if (isWideAndFlat(object)) {
    object.role = ObjectRole::kSupport;
    decision.reason = "support: wide and flat";
  } else {
    object.role = ObjectRole::kNone;
  }
  const Vector3 size = object.worldBounds().sizes();
  const double narrowest = std::min(size.x(), size.y());
  const SceneObject* support = currentSupport(scene, object, kSupportTolerance);
  std::string why;
  if (object.role == ObjectRole::kSupport) {
    why = "fixed: a support";
  } else if (const Attachment* held = scene.findAttachment(object.name)) {
    object.movable = true;
    why = "movable: held by " + held->robot + " (InitialAttachedObstacle)";
  } else if (support == nullptr) {
    why = "fixed: it rests on nothing";
  } else if (widest <= 0.0) {
    why = "fixed: no robot has a gripper";
  } else if (narrowest > widest) {
    why = "fixed: " + metresText(narrowest) + " wide, the widest gripper opens " + metresText(widest);
  } else {
    object.movable = true;
    why = "movable: rests on " + support->name + ", " + metresText(narrowest) + " wide";
  }
  decision.reason += (decision.reason.empty() ? "" : "; ") + why;
  decision.movable = object.movable;
  decision.role = object.role;
  return decision;
}

void applyOverrides(Scene& scene, const ObjectSemanticsOverrides& overrides, std::vector<ObjectSemanticsDecision>& decisions) {
  for (const std::string& name : overrides.movable) {
    if (std::find(overrides.fixed.begin(), overrides.fixed.end(), name) != overrides.fixed.end()) {
      throw InputError("object \"" + name + "\" is named both --movable and --fixed");
    }
  }
  for (bool movable : {true, false}) {
    for (const std::string& name : movable ? overrides.movable : overrides.fixed) {
      SceneObject& object = scene.object(name);
      object.movable = movable;
      object.semantics = SemanticsSource::kUser;
      for (ObjectSemanticsDecision& decision : decisions) {
        if (decision.object != name) continue;
        decision.movable = movable;
        decision.source = SemanticsSource::kUser;
        decision.reason = movable ? "movable: --movable" : "fixed: --fixed";
      }
    }
  }
}

}  // namespace

std::optional<AlignedBox3> measuredCavity(const SceneObject& object) {
  const AlignedBox3 bounds = object.worldBounds();
  const Vector3 size = bounds.sizes();
  if (size.z() < kMinimumContainerSize || std::min(size.x(), size.y()) < kMinimumContainerSize) return std::nullopt;
  const ShapeProbe probe(object);
  const Vector3 c = bounds.center();
  const double top = bounds.max().z();
  const double r = std::max(0.002, 0.1 * std::min(size.x(), size.y()));
  const double depth = largestFree(size.z(), [&](double d) {
    return !probe.hits(box({c.x() - r, c.y() - r, top - d}, {c.x() + r, c.y() + r, top + 0.01}));
  });
  if (depth < kMinimumHollowFraction * size.z() || depth >= size.z() - 1e-6) return std::nullopt;
  const double z = top - 0.5 * depth;
  const bool walled = probe.hits(box({c.x() + r, c.y() - r, z}, {bounds.max().x() + 0.01, c.y() + r, z + 1e-3})) &&
                      probe.hits(box({bounds.min().x() - 0.01, c.y() - r, z}, {c.x() - r, c.y() + r, z + 1e-3})) &&
                      probe.hits(box({c.x() - r, c.y() + r, z}, {c.x() + r, bounds.max().y() + 0.01, z + 1e-3})) &&
                      probe.hits(box({c.x() - r, bounds.min().y() - 0.01, z}, {c.x() + r, c.y() - r, z + 1e-3}));
  if (!walled) return std::nullopt;
  const AlignedBox3 world = largestCavityBox(probe, c, size, top - depth, top);
  return transformedBox(world, object.pose.inverse());
}


std::vector<ObjectSemanticsDecision> inferObjectSemantics(Scene& scene, const ObjectSemanticsOverrides& overrides) {
  const double widest = widestGripper(scene);
  std::vector<ObjectSemanticsDecision> decisions;
  for (const SceneObject& snapshot : scene.objects()) {
    SceneObject& object = scene.object(snapshot.name);
    if (object.semantics != SemanticsSource::kInferred) {
      decisions.push_back({object.name, object.movable, object.role, object.semantics, "given by its model"});
      continue;
    }
    decisions.push_back(infer(scene, object, widest));
  }
  applyOverrides(scene, overrides, decisions);
  return decisions;
}

}  // namespace lang2manip
