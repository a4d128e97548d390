#include "lang2manip/symbolic/arrangement_check.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <numeric>

#include "lang2manip/core/error.hpp"
#include "lang2manip/model/scene.hpp"
#include "lang2manip/symbolic/object_heading.hpp"
#include "lang2manip/symbolic/support_surface.hpp"

namespace lang2manip {
namespace {

using Point = Eigen::Vector2d;

std::vector<Point> centresOf(const std::vector<AlignedBox3>& boxes) {
  std::vector<Point> centres;
  for (const AlignedBox3& box : boxes) centres.push_back(box.center().head<2>());
  return centres;
}

Point centroidOf(const std::vector<Point>& points) {
  Point sum = Point::Zero();
  for (const Point& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

/// `value` with `digits` decimals.
std::string fixed(double value, int digits) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
  return buffer;
}
std::string metres(double value) { return fixed(value, 3) + " m"; }
std::string degrees(double radians) { return fixed(radians * 180.0 / std::numbers::pi, 0) + " deg"; }

GoalCheck checkLine(const Goal& goal, const std::vector<Point>& points, double tolerance) {
  const Point centre = centroidOf(points);
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const Point& p : points) scatter += (p - centre) * (p - centre).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> axes(scatter);
  const Point along = axes.eigenvectors().col(1);
  const Point across(-along.y(), along.x());
  double offLine = 0.0;
  std::vector<double> positions;
  for (const Point& p : points) {
    offLine = std::max(offLine, std::abs((p - centre).dot(across)));
    positions.push_back((p - centre).dot(along));
  }
  std::sort(positions.begin(), positions.end());
  std::vector<double> spacings;
  for (std::size_t i = 1; i < positions.size(); ++i) spacings.push_back(positions[i] - positions[i - 1]);
  const double heading = std::atan2(along.y(), along.x());
  std::string explanation = "the centres lie within " + metres(offLine) + " of a line along yaw " + degrees(heading);
  bool holds = offLine <= tolerance;
  if (goal.heading) {
    const double off = std::abs(reducedAngle(heading - *goal.heading, std::numbers::pi));
    explanation += ", " + degrees(off) + " off the wanted direction";
    holds = holds && off <= kLineHeadingTolerance;
  }
  const auto [fewest, most] = std::minmax_element(spacings.begin(), spacings.end());
  explanation += ", neighbours " + fixed(*fewest, 3) + " to " + metres(*most) + " apart";
  if (goal.evenlySpaced) holds = holds && *most - *fewest <= tolerance;
  if (goal.distance) holds = holds && std::abs(*fewest - *goal.distance) <= tolerance && std::abs(*most - *goal.distance) <= tolerance;
  return {holds, explanation};
}

GoalCheck checkCircle(const std::vector<Point>& points, double tolerance) {
  const Point centre = centroidOf(points);
  std::vector<double> radii;
  std::vector<double> angles;
  for (const Point& p : points) {
    radii.push_back((p - centre).norm());
    angles.push_back(std::atan2(p.y() - centre.y(), p.x() - centre.x()));
  }
  const double radius = std::accumulate(radii.begin(), radii.end(), 0.0) / static_cast<double>(radii.size());
  double offCircle = 0.0;
  for (const double r : radii) offCircle = std::max(offCircle, std::abs(r - radius));
  std::sort(angles.begin(), angles.end());
  const double share = 2.0 * std::numbers::pi / static_cast<double>(points.size());
  double widestGap = angles.front() + 2.0 * std::numbers::pi - angles.back();
  double narrowestGap = widestGap;
  for (std::size_t i = 1; i < angles.size(); ++i) {
    widestGap = std::max(widestGap, angles[i] - angles[i - 1]);
    narrowestGap = std::min(narrowestGap, angles[i] - angles[i - 1]);
  }
  const bool holds = offCircle <= tolerance && radius >= tolerance && narrowestGap >= share / 2.0 && widestGap <= 1.5 * share;
  return {holds, "the centres lie within " + metres(offCircle) + " of a circle of radius " + metres(radius) +
                     ", neighbours " + fixed(narrowestGap * 180.0 / std::numbers::pi, 0) + " to " + degrees(widestGap) + " apart around it"};
}

/// Each point within tolerance of its own spot of the regular polygon outline fitted to them: its
/// corners are the `corners` points farthest from the centroid (side spots lie nearer), its
/// radius and rotation theirs.
GoalCheck checkPolygon(const std::vector<Point>& points, std::size_t corners, double tolerance) {
  const double n = static_cast<double>(corners);
  const std::size_t perSide = points.size() / corners;
  const Point centre = centroidOf(points);
  std::vector<Point> byDistance = points;
  std::sort(byDistance.begin(), byDistance.end(), [&](const Point& a, const Point& b) { return (a - centre).norm() > (b - centre).norm(); });
  double radius = 0.0;
  Point rotation = Point::Zero();  // the mean of n times each corner's angle: the polygon's rotation
  for (std::size_t i = 0; i < corners; ++i) {
    const Point& p = byDistance[i];
    radius += (p - centre).norm() / n;
    const double angle = std::atan2(p.y() - centre.y(), p.x() - centre.x());
    rotation += Point(std::cos(n * angle), std::sin(n * angle));
  }
  const std::vector<Point> spots = regularOutline(centre, radius, std::atan2(rotation.y(), rotation.x()) / n, corners, perSide);
  std::vector<bool> taken(spots.size(), false);
  double offSpot = 0.0;
  bool ownSpots = true;
  for (const Point& p : points) {
    std::size_t nearest = 0;
    for (std::size_t k = 1; k < spots.size(); ++k) {
      if ((p - spots[k]).norm() < (p - spots[nearest]).norm()) nearest = k;
    }
    ownSpots = ownSpots && !taken[nearest];
    taken[nearest] = true;
    offSpot = std::max(offSpot, (p - spots[nearest]).norm());
  }
  const double side = 2.0 * radius * std::sin(std::numbers::pi / n);
  const bool holds = ownSpots && offSpot <= tolerance && side / static_cast<double>(perSide) >= 2.0 * tolerance;
  const std::string where = perSide == 1 ? "the corners" : "the corners and " + std::to_string(perSide - 1) + " evenly spaced spots of each side";
  return {holds, "the centres lie within " + metres(offSpot) + " of " + where + " of a regular polygon of side " + metres(side) +
                     (ownSpots ? "" : ", two at one spot")};
}

const SceneObject& memberNamed(const Scene& scene, const std::string& name) {
  const SceneObject* object = scene.findObject(name);
  if (object != nullptr) return *object;
  std::string names;
  for (const SceneObject& o : scene.objects()) names += (names.empty() ? "" : ", ") + o.name;
  throw InputError("goal member: unknown object \"" + name + "\" (objects: " + names + ")");
}

/// The gap between two members' boxes seen from above.
double gapFromAbove(AlignedBox3 a, AlignedBox3 b) {
  a.min().z() = b.min().z() = 0.0;
  a.max().z() = b.max().z() = 0.0;
  return boxGap(a, b);
}

GoalCheck checkSpreadOut(const std::vector<AlignedBox3>& boxes, double nearDistance) {
  double closest = 1e9;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (std::size_t j = i + 1; j < boxes.size(); ++j) closest = std::min(closest, gapFromAbove(boxes[i], boxes[j]));
  }
  return {closest >= nearDistance, "the closest two are " + metres(closest) + " apart (spread out: at least " + metres(nearDistance) + ")"};
}

/// One group: grown from the first member through gaps within `nearDistance` (Prim's order), the
/// widest gap it has to cross is the one that decides.
GoalCheck checkTogether(const std::vector<AlignedBox3>& boxes, double nearDistance) {
  const std::size_t n = boxes.size();
  std::vector<bool> joined(n, false);
  std::vector<double> link(n, 1e9);
  link[0] = 0.0;
  double widest = 0.0;
  for (std::size_t step = 0; step < n; ++step) {
    std::size_t next = n;
    for (std::size_t i = 0; i < n; ++i) {
      if (!joined[i] && (next == n || link[i] < link[next])) next = i;
    }
    joined[next] = true;
    widest = std::max(widest, link[next]);
    for (std::size_t i = 0; i < n; ++i) {
      if (!joined[i]) link[i] = std::min(link[i], gapFromAbove(boxes[next], boxes[i]));
    }
  }
  return {widest <= nearDistance, "the widest gap that joins them into one group is " + metres(widest) +
                                      " (next to each other: at most " + metres(nearDistance) + ")"};
}

/// The rows of a pyramid of `members` (3, 6, 10, ...): k members at the base, then k - 1, ..., 1.
std::optional<std::size_t> pyramidBase(std::size_t members) {
  for (std::size_t k = 2, total = 3; total <= members; total += ++k) {
    if (total == members) return k;
  }
  return std::nullopt;
}

/// Row by row from the lowest bottoms up: the base in a line, each member of a higher row resting
/// on two members of the row below (bridgedSupport()).
GoalCheck checkPyramid(const std::vector<AlignedBox3>& boxes, double tolerance) {
  const std::optional<std::size_t> base = pyramidBase(boxes.size());
  if (!base) return {false, "a pyramid has 3, 6, 10, ... members (rows of k, k - 1, ..., 1), not " + std::to_string(boxes.size())};
  std::vector<AlignedBox3> byHeight = boxes;
  std::sort(byHeight.begin(), byHeight.end(), [](const AlignedBox3& a, const AlignedBox3& b) { return a.min().z() < b.min().z(); });
  const std::vector<AlignedBox3> baseRow(byHeight.begin(), byHeight.begin() + static_cast<std::ptrdiff_t>(*base));
  const double baseSpread = baseRow.back().min().z() - baseRow.front().min().z();
  if (baseSpread > tolerance) return {false, "the " + std::to_string(*base) + " lowest members' bottoms are " + metres(baseSpread) + " apart in height: no base row"};
  Goal line;
  line.shape = ArrangementShape::kLine;
  GoalCheck check = checkLine(line, centresOf(baseRow), tolerance);
  if (!check.holds) return {false, "the base row: " + check.explanation};
  std::vector<AlignedBox3> below = baseRow;
  for (std::size_t row = *base - 1, first = *base; row >= 1; first += row, --row) {
    std::vector<AlignedBox3> current(byHeight.begin() + static_cast<std::ptrdiff_t>(first), byHeight.begin() + static_cast<std::ptrdiff_t>(first + row));
    for (const AlignedBox3& box : current) {
      if (!bridgedSupport(box, below, tolerance)) {
        return {false, "the member at (" + fixed(box.center().x(), 3) + ", " + fixed(box.center().y(), 3) + ", " + metres(box.min().z()) +
                           " high) does not rest on two members of the row below"};
      }
    }
    below = std::move(current);
  }
  return {true, "a base of " + std::to_string(*base) + " within " + check.explanation.substr(std::string("the centres lie within ").size()) +
                    "; each higher member rests on two of the row below"};
}

}  // namespace

std::size_t polygonCorners(ArrangementShape shape) {
  return shape == ArrangementShape::kTriangle ? 3 : shape == ArrangementShape::kSquare ? 4 : 0;
}

std::string memberCountProblem(ArrangementShape shape, std::size_t members) {
  const std::string name = "a " + arrangementShapeName(shape);
  const std::string count = std::to_string(members);
  if (const std::size_t corners = polygonCorners(shape); corners != 0) {
    if (members >= corners && members % corners == 0) return {};
    return name + " takes " + std::to_string(corners) + ", " + std::to_string(2 * corners) + ", " + std::to_string(3 * corners) +
           ", ... members (its corners, and as many more evenly along each side), not " + count;
  }
  if (shape == ArrangementShape::kPyramid) {
    return members == 3 || members == 6 || members == 10 ? "" : name + " has 3, 6 or 10 members (rows of k, k - 1, ..., 1), not " + count;
  }
  const std::size_t least = shape == ArrangementShape::kCircle ? 3 : 2;
  return members >= least ? "" : name + " needs at least " + std::to_string(least) + " members, not " + count;
}

std::vector<Point> regularOutline(const Point& centre, double radius, double rotation, std::size_t corners, std::size_t perSide) {
  std::vector<Point> spots;
  const double share = 2.0 * std::numbers::pi / static_cast<double>(corners);
  const auto corner = [&](std::size_t k) {
    const double angle = rotation + share * static_cast<double>(k);
    return Point(centre + radius * Point(std::cos(angle), std::sin(angle)));
  };
  for (std::size_t k = 0; k < corners; ++k) {
    const Point from = corner(k), to = corner(k + 1);
    for (std::size_t j = 0; j < perSide; ++j) spots.push_back(from + (to - from) * static_cast<double>(j) / static_cast<double>(perSide));
  }
  return spots;
}

GoalCheck checkArrangedBoxes(const Goal& goal, const std::vector<AlignedBox3>& boxes, const SpatialOptions& spatial) {
  if (!goal.shape) throw InputError("goal \"" + describeGoal(goal) + "\": no shape");
  if (boxes.size() < 2) throw InputError("goal \"" + describeGoal(goal) + "\": an arrangement needs at least two members");
  const std::vector<Point> centres = centresOf(boxes);
  const double tolerance = spatial.distanceTolerance;
  switch (*goal.shape) {
    case ArrangementShape::kLine: return checkLine(goal, centres, tolerance);
    case ArrangementShape::kCircle:
      if (boxes.size() < 3) return {false, "a circle needs at least three members"};
      return checkCircle(centres, tolerance);
    case ArrangementShape::kTriangle:
    case ArrangementShape::kSquare: {
      if (const std::string problem = memberCountProblem(*goal.shape, boxes.size()); !problem.empty()) return {false, problem};
      return checkPolygon(centres, polygonCorners(*goal.shape), tolerance);
    }
    case ArrangementShape::kSpreadOut: return checkSpreadOut(boxes, spatial.nearDistance);
    case ArrangementShape::kTogether: return checkTogether(boxes, spatial.nearDistance);
    case ArrangementShape::kPyramid: return checkPyramid(boxes, tolerance);
  }
  return {false, "unknown shape"};
}

GoalCheck checkArranged(const Scene& scene, const Goal& goal, const GoalCheckOptions& options) {
  const Pose toBase = robotBaseFrame(scene, options.robot).inverse();
  std::vector<AlignedBox3> boxes;
  double lowest = std::numeric_limits<double>::infinity();
  for (const std::string& member : goal.members) {
    const SceneObject& object = memberNamed(scene, member);
    if (scene.findAttachment(member) != nullptr) return {false, member + " is held, not standing in the arrangement"};
    AlignedBox3 box;
    const AlignedBox3 world = object.worldBounds();
    for (int corner = 0; corner < 8; ++corner) box.extend(toBase * world.corner(static_cast<AlignedBox3::CornerType>(corner)));
    boxes.push_back(box);
    lowest = std::min(lowest, box.min().z());
  }
  for (std::size_t i = 0; i < goal.members.size() && !goal.target.empty(); ++i) {
    // A pyramid's higher rows rest on its members, not on the target.
    if (goal.shape == ArrangementShape::kPyramid && boxes[i].min().z() > lowest + options.spatial.distanceTolerance) continue;
    Goal resting;
    resting.object = goal.members[i];
    resting.relation = SpatialRelation::kOn;
    resting.target = goal.target;
    resting.region = goal.region;
    const GoalCheck on = checkGoalInScene(scene, resting, options);
    if (!on.holds) return on;
  }
  GoalCheck check = checkArrangedBoxes(goal, boxes, options.spatial);
  check.explanation = describeGoal(goal) + ": " + check.explanation;
  return check;
}

}  // namespace lang2manip
