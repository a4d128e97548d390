#include "lang2manip/grounding/placement_poses.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lang2manip/core/random.hpp"
#include "lang2manip/grounding/object_geometry.hpp"
#include "lang2manip/symbolic/support_surface.hpp"
#include "lang2manip/symbolic/surface_region.hpp"

namespace lang2manip {
namespace {


std::string sizeText(const Vector3& v) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.3f x %.3f x %.3f m)", v.x(), v.y(), v.z());
  return buffer;
}

std::string pointText(double x, double y, double z) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.3f, %.3f, %.3f)", x, y, z);
  return buffer;
}

PoseSampling failure(PlacementFailure kind, std::string reason) {
  PoseSampling sampling;
  sampling.failure = kind;
  sampling.reason = std::move(reason);
  return sampling;
}

/// The pose with rotation `q` whose bounding box is centred on (x, y) with its bottom at `bottom`.
Pose restingPose(const SceneObject& object, const Quaternion& q, double x, double y, double bottom) {
  Pose pose = Pose::Identity();
  pose.linear() = q.toRotationMatrix();
  const AlignedBox3 bounds = boundsAtPose(object, pose);
  pose.translation() = Vector3(x - bounds.center().x(), y - bounds.center().y(), bottom - bounds.min().z());
  return pose;
}

Vector3 rotatedSize(const SceneObject& object, const Quaternion& q) {
  Pose pose = Pose::Identity();
  pose.linear() = q.toRotationMatrix();
  return boundsAtPose(object, pose).sizes();
}

/// Grid coordinates over [low, high], the middle first.
std::vector<double> gridValues(double low, double high, int count) {
  if (high <= low || count < 2) return {(low + high) / 2.0};
  std::vector<double> values;
  for (int i = 0; i < count; ++i) values.push_back(low + (high - low) * i / (count - 1));
  const double middle = (low + high) / 2.0;
  std::stable_sort(values.begin(), values.end(), [&](double a, double b) { return std::abs(a - middle) < std::abs(b - middle); });
  return values;
}

/// The footprints (boxes, world) of the objects that stand in `cavity` now, `object` and
/// `container` left out.
std::vector<AlignedBox3> contentsOf(const Scene& scene, const AlignedBox3& cavity, const std::string& object, const std::string& container) {
  std::vector<AlignedBox3> contents;
  for (const SceneObject& other : scene.objects()) {
    if (other.name == object || other.name == container || other.collisions.empty()) continue;
    const AlignedBox3 box = other.worldBounds();
    if (cavity.contains(Vector3(box.center().x(), box.center().y(), std::clamp(box.min().z(), cavity.min().z(), cavity.max().z())))) {
      contents.push_back(box);
    }
  }
  return contents;
}

bool footprintsOverlap(const AlignedBox3& a, const AlignedBox3& b) {
  return a.min().x() < b.max().x() && b.min().x() < a.max().x() && a.min().y() < b.max().y() && b.min().y() < a.max().y();
}

/// How many more footprints like `placed` still fit among `taken` and `placed` at the centres
/// `xs` x `ys` (outermost first, taken greedily): the room a placement leaves for what may
/// follow it into the container.
int roomLeftFor(const AlignedBox3& placed, std::vector<AlignedBox3> taken, std::vector<double> xs, std::vector<double> ys) {
  const auto outermostFirst = [](std::vector<double>& values) { std::reverse(values.begin(), values.end()); };
  outermostFirst(xs);
  outermostFirst(ys);
  taken.push_back(placed);
  const Vector3 half = placed.sizes() / 2.0;
  int count = 0;
  for (const double x : xs) {
    for (const double y : ys) {
      const AlignedBox3 copy(Vector3(x - half.x(), y - half.y(), placed.min().z()), Vector3(x + half.x(), y + half.y(), placed.max().z()));
      if (std::none_of(taken.begin(), taken.end(), [&](const AlignedBox3& box) { return footprintsOverlap(box, copy); })) {
        taken.push_back(copy);
        ++count;
      }
    }
  }
  return count;
}

PoseSampling inContainer(const PoseSamplingInput& in, const SceneObject& container, const PlacementSettings& s) {
  if (container.role != ObjectRole::kContainer || !container.cavity) {
    return failure(PlacementFailure::kBadTarget, container.name + " is not a container");
  }
  const AlignedBox3 cavity = transformedBox(*container.cavity, container.pose);
  const Vector3 room = cavity.sizes() - Vector3::Constant(2.0 * s.wallMargin);
  const double floor = cavity.min().z() + s.releaseGap;
  PoseSampling sampling;
  std::vector<std::pair<Quaternion, Vector3>> fitting;
  for (const Quaternion& q : restingOrientations(in.orientation)) {
    const Vector3 size = rotatedSize(*in.object, q);
    if (size.x() <= room.x() && size.y() <= room.y() && floor + size.z() / 2.0 < cavity.max().z()) fitting.emplace_back(q, size);
  }
  if (fitting.empty()) {
    const Vector3 size = in.object->dimensions();
    return failure(PlacementFailure::kTooLarge,
                   in.object->name + " " + sizeText(size) + " is too large for the cavity of " +
                       container.name + " " + sizeText(cavity.sizes()) + " in every orientation");
  }
  const std::vector<AlignedBox3> contents = contentsOf(*in.scene, cavity, in.object->name, container.name);
  // Per resting orientation, its positions (when packing for more: those that leave the most
  // room for more objects like this one first, the middle first among equals, so that what
  // follows later still fits); then each position in every orientation before the next one.
  std::vector<std::vector<std::pair<int, PoseCandidate>>> byOrientation(fitting.size());
  for (std::size_t k = 0; k < fitting.size(); ++k) {
    const auto& [q, size] = fitting[k];
    const auto xs = gridValues(cavity.min().x() + s.wallMargin + size.x() / 2.0, cavity.max().x() - s.wallMargin - size.x() / 2.0, s.cavityGrid);
    const auto ys = gridValues(cavity.min().y() + s.wallMargin + size.y() / 2.0, cavity.max().y() - s.wallMargin - size.y() / 2.0, s.cavityGrid);
    for (const double x : xs) {
      for (const double y : ys) {
        const Pose pose = restingPose(*in.object, q, x, y, floor);
        byOrientation[k].emplace_back(roomLeftFor(boundsAtPose(*in.object, pose), contents, xs, ys),
                                      PoseCandidate{pose, container.name, "in " + container.name + " at " + pointText(x, y, floor)});
      }
    }
    if (in.packForMore) {
      std::stable_sort(byOrientation[k].begin(), byOrientation[k].end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    }
  }
  for (std::size_t rank = 0;; ++rank) {
    bool any = false;
    for (const auto& positions : byOrientation) {
      if (rank < positions.size()) sampling.poses.push_back(positions[rank].second), any = true;
    }
    if (!any) break;
  }
  return sampling;
}

std::vector<Quaternion> uprightYaws(const Quaternion& current) {
  std::vector<Quaternion> all = restingOrientations(current);
  all.resize(std::min<std::size_t>(all.size(), 4));
  return all;
}

/// The point of a region things are put nearest first: a quarter of the region in from a
/// corner's corner or an edge's midpoint (near the edge, not on it, so that the candidates after
/// it spread over the region), the centre of the rest (base frame).
Vector3 regionAnchor(const AlignedBox3& area, const SurfaceRegion& region) {
  const AlignedBox3 box = regionBox(area, region);
  Vector3 anchor = box.center();
  if (region.kind != SurfaceRegion::Kind::kCorner && region.kind != SurfaceRegion::Kind::kEdge) return anchor;
  anchor.x() += region.depth * box.sizes().x() / 4.0;
  anchor.y() += region.side * box.sizes().y() / 4.0;
  return anchor;
}

/// In `region` of the reachable top of `surface`: a 2 cm grid of the centres that keep the
/// footprint inside (regionCentres()), nearest to the region's anchor first, in the object's
/// upright yaws.
PoseSampling inRegion(const PoseSamplingInput& in, const SceneObject& surface, const SurfaceRegion& region, double height,
                      const PlacementSettings& s) {
  std::string why;
  const auto area = supportArea(*in.scene, surface.name, in.robot, &why, in.arm);
  const std::string name = surfaceRegionName(region);
  if (!area) return failure(PlacementFailure::kNoSupport, in.object->name + " cannot go in the " + name + " of " + surface.name + ": " + why);
  const Vector3 anchor = regionAnchor(area->reachable, region);
  struct Spot {
    Vector3 point;
    Quaternion orientation;
  };
  std::vector<Spot> spots;
  for (const Quaternion& q : uprightYaws(in.orientation)) {
    const Vector3 size = rotatedSize(*in.object, Quaternion(in.robotBase.linear().transpose() * q.toRotationMatrix()));
    const auto centres = regionCentres(area->reachable, region, size, s.edgeMargin);
    if (!centres) continue;
    const Vector3 extent = centres->sizes();
    const int nx = static_cast<int>(std::floor(extent.x() / 0.02)) + 1, ny = static_cast<int>(std::floor(extent.y() / 0.02)) + 1;
    for (int i = 0; i < nx; ++i) {
      for (int j = 0; j < ny; ++j) {
        const double x = nx == 1 ? centres->center().x() : centres->min().x() + extent.x() * i / (nx - 1);
        const double y = ny == 1 ? centres->center().y() : centres->min().y() + extent.y() * j / (ny - 1);
        spots.push_back({Vector3(x, y, 0.0), q});
      }
    }
  }
  std::stable_sort(spots.begin(), spots.end(), [&](const Spot& a, const Spot& b) {
    return (a.point - anchor).head<2>().squaredNorm() < (b.point - anchor).head<2>().squaredNorm();
  });
  PoseSampling sampling;
  for (const Spot& spot : spots) {
    Vector3 world = in.robotBase * spot.point;
    sampling.poses.push_back({restingPose(*in.object, spot.orientation, world.x(), world.y(), height + s.releaseGap), surface.name,
                              "on " + surface.name + " (" + name + ") at " + pointText(world.x(), world.y(), height)});
  }
  if (sampling.poses.empty()) {
    return failure(PlacementFailure::kTooLarge, in.object->name + " does not fit in the " + name + " of " + surface.name);
  }
  return sampling;
}

PoseSampling onSurface(const PoseSamplingInput& in, const SceneObject& surface, const std::optional<SurfaceRegion>& region,
                       const PlacementSettings& s) {
  const SupportSurface support = supportSurface(surface);
  if (!support.top) return failure(PlacementFailure::kNoSupport, in.object->name + " cannot rest on " + surface.name + ": " + support.why);
  if (region) return inRegion(in, surface, *region, support.top->max().z(), s);
  const AlignedBox3 top = *support.top;
  Random random(s.seed);
  std::vector<Vector3> points;
  for (int i = 0; i < s.surfaceSamples; ++i) {
    points.emplace_back(random.uniform(top.min().x(), top.max().x()), random.uniform(top.min().y(), top.max().y()), top.max().z());
  }
  std::stable_sort(points.begin(), points.end(), [&](const Vector3& a, const Vector3& b) {
    return (a - in.position).head<2>().norm() < (b - in.position).head<2>().norm();
  });
  points.insert(points.begin(), top.center());  // a top no larger than the object: centred on it
  PoseSampling sampling;
  for (const Vector3& p : points) {
    for (const Quaternion& q : uprightYaws(in.orientation)) {
      const Vector3 size = rotatedSize(*in.object, q);
      if (size.x() > top.sizes().x() + kFootprintSlack || size.y() > top.sizes().y() + kFootprintSlack) continue;  // in this yaw
      // The edge margin where the top has room for it; a top not much larger than the object takes it centred.
      const Vector3 margin = ((top.sizes() - size) / 2.0).cwiseMax(0.0).cwiseMin(s.edgeMargin);
      const Vector3 half = size / 2.0 + margin;
      const bool centred = (p - top.center()).head<2>().norm() < 1e-9;
      const bool inside = p.x() - half.x() >= top.min().x() - 1e-9 && p.x() + half.x() <= top.max().x() + 1e-9 &&
                          p.y() - half.y() >= top.min().y() - 1e-9 && p.y() + half.y() <= top.max().y() + 1e-9;
      if (!inside && !(centred && margin.head<2>().isZero())) continue;
      sampling.poses.push_back({restingPose(*in.object, q, p.x(), p.y(), top.max().z() + s.releaseGap), surface.name,
                                "on " + surface.name + " at " + pointText(p.x(), p.y(), p.z())});
    }
  }
  if (sampling.poses.empty()) return failure(PlacementFailure::kTooLarge, in.object->name + " does not fit on top of " + surface.name);
  return sampling;
}

std::vector<Vector3> sideDirections(SpatialRelation relation, const Pose& base) {
  const Vector3 x = Vector3(base.linear().col(0).x(), base.linear().col(0).y(), 0.0).normalized();
  const Vector3 y = Vector3::UnitZ().cross(x);
  switch (relation) {
    case SpatialRelation::kLeftOf: return {y};
    case SpatialRelation::kRightOf: return {-y};
    case SpatialRelation::kInFrontOf: return {x};
    case SpatialRelation::kBehind: return {-x};
    default: return {y, -y, x, -x};
  }
}

PoseSampling besideObject(const PoseSamplingInput& in, const SceneObject& reference, SpatialRelation relation,
                          std::optional<double> distance, const PlacementSettings& s) {
  const SceneObject* support = currentSupport(*in.scene, reference, kSupportTolerance);
  if (support == nullptr) return failure(PlacementFailure::kNoSupport, reference.name + " rests on nothing to place beside it");
  const AlignedBox3 standing = reference.worldBounds();
  const double floor = surfaceUnder(*support, Vector3(standing.center().x(), standing.center().y(), standing.min().z()), kSupportTolerance);
  const AlignedBox3 area = support->worldBounds();
  const Vector3 centre = reference.worldBounds().center();
  const bool nextTo = relation == SpatialRelation::kNextTo;
  PoseSampling sampling;
  // A distance is a whole offset ("10 cm to the right of"): no shifts across it.
  for (double shift : (nextTo || distance) ? std::vector<double>{0.0} : s.lateralShifts) {
    for (const Vector3& d : sideDirections(relation, in.robotBase)) {
      for (const Quaternion& q : uprightYaws(in.orientation)) {
        Pose probe = Pose::Identity();
        probe.linear() = q.toRotationMatrix();
        const double halfMine = halfExtentAlong(*in.object, probe, d);
        const double gap = distance.value_or(nextTo ? s.nextToGap : s.sideGap);
        const double offset = (distance && !nextTo) ? *distance : halfExtentAlong(reference, reference.pose, d) + halfMine + gap;
        const Vector3 p = centre + d * offset + Vector3::UnitZ().cross(d) * shift;
        const Vector3 half = rotatedSize(*in.object, q) / 2.0;
        if (p.x() - half.x() < area.min().x() || p.x() + half.x() > area.max().x() || p.y() - half.y() < area.min().y() ||
            p.y() + half.y() > area.max().y()) {
          sampling.failure = PlacementFailure::kNoSupport;
          sampling.reason = in.object->name + ": no room on " + support->name + " " + describePlacementTarget({relation, reference.name, distance, {}, {}});
          continue;
        }
        sampling.poses.push_back({restingPose(*in.object, q, p.x(), p.y(), floor + s.releaseGap), support->name,
                                  describePlacementTarget({relation, reference.name, distance, {}, {}}) + " at " + pointText(p.x(), p.y(), floor)});
      }
    }
  }
  return sampling;
}

/// The object at the target position with orientation `rotation` (world), set onto the support
/// under it; a failure when nothing is there to rest on.
PoseSampling atPoseTurned(const PoseSamplingInput& in, const PlacementTarget& target, const Matrix3& rotation, const PlacementSettings& s) {
  Pose pose = Pose::Identity();
  pose.linear() = rotation;
  pose.translation() = in.robotBase * *target.position;
  const AlignedBox3 bounds = boundsAtPose(*in.object, pose);
  const Vector3 bottom(bounds.center().x(), bounds.center().y(), bounds.min().z());
  const SceneObject* support = supportUnderBody(*in.scene, bounds, s.supportTolerance, {in.object->name});
  const double surface = support == nullptr ? 0.0 : surfaceUnder(*support, bottom, s.supportTolerance);
  if (support == nullptr || bottom.z() < surface - 1e-3) {
    return failure(PlacementFailure::kNoSupport, in.object->name + ": nothing to rest on at " + pointText(bottom.x(), bottom.y(), bottom.z()) + " (world)");
  }
  pose.translation().z() += surface + s.releaseGap - bottom.z();
  PoseSampling sampling;
  sampling.poses.push_back({pose, support->name, describePlacementTarget(target)});
  return sampling;
}

/// At an explicit position: in the requested orientation, or, when none is requested, in the
/// object's current orientation first and then its other upright yaws (the position is what was
/// asked for; the hand may need another yaw to reach it).
PoseSampling atPose(const PoseSamplingInput& in, const PlacementTarget& target, const PlacementSettings& s) {
  if (target.orientation) {
    return atPoseTurned(in, target, in.robotBase.linear() * target.orientation->normalized().toRotationMatrix(), s);
  }
  // The quarter turns first, then the eighth turns between them: at a fixed position among other
  // objects (an arrangement), the hand may fit between neighbours only diagonally.
  std::vector<Quaternion> yaws = uprightYaws(in.orientation);
  const Quaternion eighth(Eigen::AngleAxisd(M_PI / 4.0, Vector3::UnitZ()));
  for (std::size_t k = 0, quarters = yaws.size(); k < quarters; ++k) yaws.push_back(eighth * yaws[k]);
  PoseSampling sampling;
  for (const Quaternion& q : yaws) {
    PoseSampling one = atPoseTurned(in, target, q.toRotationMatrix(), s);
    if (one.poses.empty()) return one;
    sampling.poses.insert(sampling.poses.end(), one.poses.begin(), one.poses.end());
  }
  return sampling;
}

}  // namespace

PoseSampling samplePlacementPoses(const PoseSamplingInput& in, const PlacementTarget& target, const PlacementSettings& s) {
  if (!target.relation) {
    if (!target.position) return failure(PlacementFailure::kBadTarget, in.object->name + ": the placement has neither a relation nor a position");
    return atPose(in, target, s);
  }
  if (target.target == in.object->name) return failure(PlacementFailure::kBadTarget, in.object->name + " cannot be placed relative to itself");
  const SceneObject& reference = in.scene->object(target.target);
  switch (*target.relation) {
    case SpatialRelation::kIn: return inContainer(in, reference, s);
    case SpatialRelation::kOn: return onSurface(in, reference, target.region, s);
    default: {
      PoseSampling sampling = besideObject(in, reference, *target.relation, target.distance, s);
      if (!sampling.poses.empty()) sampling.failure = PlacementFailure::kNone;
      return sampling;
    }
  }
}

}  // namespace lang2manip
