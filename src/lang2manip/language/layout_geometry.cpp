#include "lang2manip/language/layout_geometry.hpp"

#include <algorithm>
#include <cmath>

#include "lang2manip/symbolic/object_heading.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip::language_detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

AlignedBox3 shifted(const AlignedBox3& box, const Vector3& by) { return {box.min() + by, box.max() + by}; }

/// Throws when moving the object by the goal's displacement takes its centre off every support
/// it could rest on (unknown layouts pass: the grounding decides).
void validateDisplacement(const Goal& goal, const SequencingOptions& options) {
  const auto found = options.layout.find(goal.object);
  if (found == options.layout.end() || options.supportAreas.empty()) return;
  const Vector3 from = found->second.bounds.center();
  const Vector3 to = from + goal.displacement;
  const auto contains = [](const AlignedBox3& area, const Vector3& p) {
    return p.x() >= area.min().x() && p.x() <= area.max().x() && p.y() >= area.min().y() && p.y() <= area.max().y();
  };
  for (const auto& [name, area] : options.supportAreas) {
    if (contains(area, to) || !contains(area, from)) continue;
    throw PlanningError("offline planner: cannot plan \"" + describeGoal(goal) + "\": it would take " + goal.object + " off " + name);
  }
}

void validatePoseGoal(const Goal& goal, const SequencingOptions& options) {
  if (goal.kind == GoalKind::kDisplaced) validateDisplacement(goal, options);
  if (goal.kind != GoalKind::kAtPosition && goal.kind != GoalKind::kTurned && goal.kind != GoalKind::kFacing) return;
  const std::string what = "offline planner: cannot plan \"" + describeGoal(goal) + "\": ";
  const auto found = options.layout.find(goal.object);
  if (found == options.layout.end()) throw PlanningError(what + "where " + goal.object + " stands is not known");
  const ObjectLayout& layout = found->second;
  if (goal.kind == GoalKind::kAtPosition && !goal.position) throw PlanningError(what + "it has no position");
  if (goal.kind == GoalKind::kTurned) {
    if (layout.turnSymmetry == 0.0) {
      throw PlanningError(what + "turning " + goal.object + " changes nothing: its shape is round about the vertical");
    }
    if (std::abs(reducedAngle(goal.angle, layout.turnSymmetry)) < kTurnTolerance) {
      throw PlanningError(what + "turning " + goal.object + " by " + degreesText(goal.angle) +
                          " leaves it looking the same: its shape repeats every " + degreesText(layout.turnSymmetry) +
                          " about the vertical");
    }
  }
  if (goal.kind == GoalKind::kFacing) {
    if (goal.target == goal.object) throw PlanningError(what + "an object cannot point at itself");
    if (!layout.longSideYaw) {
      throw PlanningError(what + goal.object + " has no long side to point with (its footprint is square or round)");
    }
    if (!goal.target.empty() && !options.layout.count(goal.target)) throw PlanningError(what + "where " + goal.target + " stands is not known");
  }
}

std::optional<double> facingTurn(const std::map<std::string, ObjectLayout>& layout, const Goal& goal) {
  const auto mine = layout.find(goal.object);
  if (mine == layout.end() || mine->second.placeUnknown || !mine->second.longSideYaw) return std::nullopt;
  if (goal.target.empty()) return reducedAngle(goal.angle - *mine->second.longSideYaw, kPi);  // along a heading
  const auto target = layout.find(goal.target);
  if (target == layout.end() || target->second.placeUnknown) return std::nullopt;
  const Vector3 toward = target->second.bounds.center() - mine->second.bounds.center();
  return reducedAngle(std::atan2(toward.y(), toward.x()) - *mine->second.longSideYaw, kPi);
}

std::vector<std::string> standingIn(const std::map<std::string, ObjectLayout>& layout, const AlignedBox3& spot,
                                    const std::vector<std::string>& objects, const std::vector<std::string>& ignored,
                                    const std::set<std::string>& supports) {
  std::vector<std::string> standing;
  for (const std::string& name : objects) {
    const auto at = layout.find(name);
    if (at == layout.end() || at->second.placeUnknown || supports.count(name) ||
        std::find(ignored.begin(), ignored.end(), name) != ignored.end()) {
      continue;
    }
    if (footprintsOverlap(at->second.bounds, spot, 0.0) && at->second.bounds.max().z() > spot.min().z() + kRestingContact) standing.push_back(name);
  }
  return standing;
}

std::optional<std::string> restingUnder(const std::map<std::string, ObjectLayout>& layout, const AlignedBox3& spot, const std::string& object) {
  std::optional<std::string> most;
  double mostArea = 0.0;
  for (const auto& [name, other] : layout) {
    if (name == object || other.placeUnknown || std::abs(other.bounds.max().z() - spot.min().z()) > kRaisedPosition) continue;
    const Eigen::AlignedBox2d overlap = Eigen::AlignedBox2d(spot.min().head<2>(), spot.max().head<2>())
                                            .intersection(Eigen::AlignedBox2d(other.bounds.min().head<2>(), other.bounds.max().head<2>()));
    if (!overlap.isEmpty() && overlap.volume() > mostArea) most = name, mostArea = overlap.volume();
  }
  return most;
}

std::vector<AlignedBox3> placesTaken(const std::map<std::string, ObjectLayout>& layout, const std::vector<Goal>& goals,
                                     const std::string& object, const std::string& held, const std::set<std::string>& supports) {
  std::vector<AlignedBox3> taken;
  for (const auto& [name, other] : layout) {
    if (name != object && name != held && !supports.count(name) && !other.placeUnknown) taken.push_back(other.bounds);
  }
  for (const Goal& goal : goals) {
    const auto owner = layout.find(goal.object);
    if (goal.kind != GoalKind::kAtPosition || !goal.position || goal.object == object || owner == layout.end()) continue;
    const Vector3& origin = owner->second.origin;
    taken.push_back(shifted(owner->second.bounds, Vector3(goal.position->x() - origin.x(), goal.position->y() - origin.y(), 0.0)));
  }
  return taken;
}

void moveLayout(std::map<std::string, ObjectLayout>& layouts, const std::string& object, const Vector3& origin,
                std::optional<double> turn) {
  const auto found = layouts.find(object);
  if (found == layouts.end()) return;
  ObjectLayout& layout = found->second;
  const Vector3 offset = layout.bounds.center() - layout.origin;
  Vector3 half = layout.bounds.sizes() / 2.0;
  Vector3 centre = origin + offset;
  if (turn) {
    const Matrix3 rotation = verticalTurn(*turn);
    centre = origin + rotation * offset;
    half = (rotation.cwiseAbs() * half).eval();
    layout.orientation = Quaternion(rotation * layout.orientation.toRotationMatrix());
    if (layout.longSideYaw) layout.longSideYaw = reducedAngle(*layout.longSideYaw + *turn - kPi / 2.0, kPi) + kPi / 2.0;
  }
  layout.origin = origin;
  layout.bounds = AlignedBox3(centre - half, centre + half);
  layout.placeUnknown = false;
}

bool footprintsOverlap(const AlignedBox3& a, const AlignedBox3& b, double gap) {
  return a.min().x() < b.max().x() + gap && b.min().x() < a.max().x() + gap && a.min().y() < b.max().y() + gap &&
         b.min().y() < a.max().y() + gap;
}

std::vector<Vector3> freeSpots(const Vector3& size, const AlignedBox3& area, const std::vector<AlignedBox3>& occupied,
                               const Vector3& near, double gap, std::size_t wanted) {
  constexpr double kStep = 0.02;
  constexpr double kSpotSpacing = 0.05;
  const Vector3 half(size.x() / 2.0, size.y() / 2.0, 0.0);
  const double lowX = area.min().x() + gap + half.x(), highX = area.max().x() - gap - half.x();
  const double lowY = area.min().y() + gap + half.y(), highY = area.max().y() - gap - half.y();
  std::vector<Vector3> spots;
  for (double x = lowX; x <= highX + 1e-9; x += kStep) {
    for (double y = lowY; y <= highY + 1e-9; y += kStep) {
      const Vector3 centre(x, y, area.max().z());
      const AlignedBox3 footprint(centre - half, centre + half);
      const bool free = std::none_of(occupied.begin(), occupied.end(),
                                     [&](const AlignedBox3& box) { return footprintsOverlap(footprint, box, gap); });
      if (free) spots.push_back(centre);
    }
  }
  std::stable_sort(spots.begin(), spots.end(), [&near](const Vector3& a, const Vector3& b) {
    return (a - near).head<2>().squaredNorm() < (b - near).head<2>().squaredNorm();
  });
  std::vector<Vector3> apart;  // a spot that fails is not followed by its neighbour 2 cm away
  for (const Vector3& spot : spots) {
    if (apart.size() >= wanted) break;
    const bool far = std::all_of(apart.begin(), apart.end(),
                                 [&](const Vector3& kept) { return (kept - spot).head<2>().norm() >= kSpotSpacing; });
    if (far) apart.push_back(spot);
  }
  return apart;
}

}  // namespace lang2manip::language_detail
