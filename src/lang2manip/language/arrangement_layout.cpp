#include "lang2manip/language/arrangement_layout.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/symbolic/arrangement_check.hpp"

namespace lang2manip::language_detail {
namespace {

/// Between neighbours, beyond the widest member (room for the fingers), metres.
constexpr double kSpacingGap = 0.04;
/// From the other objects, metres.
constexpr double kOtherClearance = 0.03;
/// Inside the area beyond half the widest member, metres (the area keeps its own margin).
constexpr double kEdgeMargin = 0.005;
/// What spread-out members keep beyond the least gap, metres (for where a place lands).
constexpr double kSpreadSlack = 0.01;
/// The least gap between neighbours of a line or ring that does not fit with kSpacingGap.
constexpr double kTightSpacingGap = 0.025;
constexpr double kGridStep = 0.02;
/// Between neighbours of a pyramid's row: a higher member rests on both, and a finger fits.
constexpr double kPyramidGap = 0.02;
/// How far (m) the heights of a pyramid row's members may differ.
constexpr double kLevelTolerance = 0.003;
/// Rotations of a circle or polygon tried, over one corner's share of the turn.
constexpr int kRotations = 6;

Vector3 flattened(const Vector3& p) { return {p.x(), p.y(), 0.0}; }

double widestOf(const std::vector<AlignedBox3>& boxes) {
  double widest = 0.0;
  for (const AlignedBox3& box : boxes) widest = std::max(widest, box.sizes().head<2>().maxCoeff());
  return widest;
}

/// Grid points over `box` (x, y), nearest to `near` first.
std::vector<Vector3> gridOver(const AlignedBox3& box, const Vector3& near) {
  std::vector<Vector3> points;
  for (double x = box.min().x(); x <= box.max().x() + 1e-9; x += kGridStep) {
    for (double y = box.min().y(); y <= box.max().y() + 1e-9; y += kGridStep) points.emplace_back(x, y, 0.0);
  }
  std::stable_sort(points.begin(), points.end(),
                   [&](const Vector3& a, const Vector3& b) { return (a - flattened(near)).squaredNorm() < (b - flattened(near)).squaredNorm(); });
  return points;
}

/// The x-y gap between two boxes.
double footprintGap(const AlignedBox3& a, const AlignedBox3& b) {
  const Eigen::Vector2d separation = (a.min().head<2>() - b.max().head<2>()).cwiseMax(b.min().head<2>() - a.max().head<2>()).cwiseMax(0.0);
  return separation.norm();
}

AlignedBox3 movedTo(const AlignedBox3& box, const Vector3& centre) {
  const Vector3 by(centre.x() - box.center().x(), centre.y() - box.center().y(), 0.0);
  return AlignedBox3(box.min() + by, box.max() + by);
}

/// What a layout keeps clear of: everything standing; the other objects (members move); or only
/// the objects that cannot move (the plan sets the others aside first).
enum class Clearance { kOfAll, kOfOthers, kOfFixed };
constexpr Clearance kClearances[] = {Clearance::kOfAll, Clearance::kOfOthers, Clearance::kOfFixed};

class Layout {
 public:
  explicit Layout(const ArrangementLayoutRequest& request) : request_(request), widest_(widestOf(request.members)) {}

  [[nodiscard]] double widest() const { return widest_; }
  [[nodiscard]] double pitch() const { return request_.spacing.value_or(widest_ + kSpacingGap); }
  /// The spacings tried: the one asked for, else the roomy one and then tighter ones.
  [[nodiscard]] std::vector<double> pitches() const {
    if (request_.spacing) return {*request_.spacing};
    return {widest_ + kSpacingGap, widest_ + (kSpacingGap + kTightSpacingGap) / 2.0, widest_ + kTightSpacingGap};
  }

  [[nodiscard]] bool inside(const Vector3& p) const {
    const double margin = widest_ / 2.0 + kEdgeMargin;
    const AlignedBox3& area = request_.area;
    return p.x() >= area.min().x() + margin && p.x() <= area.max().x() - margin && p.y() >= area.min().y() + margin &&
           p.y() <= area.max().y() - margin;
  }

  /// Clear of what `clearance` keeps clear of.
  [[nodiscard]] bool clear(const Vector3& p, Clearance clearance) const {
    const double half = widest_ / 2.0 + kOtherClearance;
    const auto blocks = [&](const AlignedBox3& box) {
      return p.x() > box.min().x() - half && p.x() < box.max().x() + half && p.y() > box.min().y() - half && p.y() < box.max().y() + half;
    };
    for (std::size_t i = 0; i < request_.others.size(); ++i) {
      const bool movable = i < request_.othersMovable.size() && request_.othersMovable[i];
      if ((clearance != Clearance::kOfFixed || !movable) && blocks(request_.others[i])) return false;
    }
    return clearance != Clearance::kOfAll || std::none_of(request_.members.begin(), request_.members.end(), blocks);
  }

  [[nodiscard]] bool fits(const std::vector<Vector3>& spots, Clearance clearance) const {
    return std::all_of(spots.begin(), spots.end(), [&](const Vector3& p) { return inside(p) && clear(p, clearance); });
  }

  /// Where the shape's centre is tried, nearest to the middle of where it may be first.
  [[nodiscard]] std::vector<Vector3> centres() const {
    if (request_.around) return {flattened(request_.around->center())};
    const AlignedBox3& box = request_.centreArea.value_or(request_.area);
    return gridOver(box, box.center());
  }

 private:
  const ArrangementLayoutRequest& request_;
  double widest_;
};

/// spots[i] for member order[i]: the spots in the members' order.
std::vector<Vector3> inMemberOrder(const std::vector<Vector3>& spots, const std::vector<std::size_t>& order) {
  std::vector<Vector3> result(spots.size());
  for (std::size_t i = 0; i < order.size(); ++i) result[order[i]] = spots[i];
  return result;
}

/// The members' indices in the order they stand along `direction`.
std::vector<std::size_t> orderAlong(const std::vector<AlignedBox3>& members, const Vector3& direction) {
  std::vector<std::size_t> order(members.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return members[a].center().dot(direction) < members[b].center().dot(direction); });
  return order;
}

/// The assignment of members to spots that moves them least in total (every order for up to seven,
/// else each member in turn to its nearest free spot).
std::vector<Vector3> leastTravel(const std::vector<AlignedBox3>& members, const std::vector<Vector3>& spots) {
  std::vector<std::size_t> order(members.size());
  std::iota(order.begin(), order.end(), 0);
  const auto travel = [&](const std::vector<std::size_t>& candidate) {
    double sum = 0.0;
    for (std::size_t i = 0; i < candidate.size(); ++i) sum += (flattened(members[candidate[i]].center()) - spots[i]).norm();
    return sum;
  };
  if (members.size() <= 7) {
    std::vector<std::size_t> best = order;
    double least = travel(order);
    while (std::next_permutation(order.begin(), order.end())) {
      if (const double t = travel(order); t < least - 1e-12) least = t, best = order;
    }
    return inMemberOrder(spots, best);
  }
  std::vector<Vector3> result(members.size());
  std::vector<bool> used(spots.size(), false);
  for (std::size_t m = 0; m < members.size(); ++m) {
    std::size_t nearest = 0;
    double distance = 1e9;
    for (std::size_t s = 0; s < spots.size(); ++s) {
      const double d = (flattened(members[m].center()) - spots[s]).norm();
      if (!used[s] && d < distance) nearest = s, distance = d;
    }
    used[nearest] = true;
    result[m] = spots[nearest];
  }
  return result;
}

/// Evenly spaced on the segment between the two objects' centres (the ends excluded), in the
/// order the members stand along it, clear of both ends and of what else stands there.
std::optional<std::vector<Vector3>> layOutBetween(const ArrangementLayoutRequest& request, const Layout& layout, std::string& why) {
  const Vector3 a = flattened(request.between->first.center()), b = flattened(request.between->second.center());
  const Vector3 direction = (b - a).normalized();
  const std::size_t n = request.members.size();
  const std::vector<std::size_t> order = orderAlong(request.members, direction);
  std::vector<Vector3> spots;
  for (std::size_t i = 0; i < n; ++i) spots.push_back(a + (b - a) * static_cast<double>(i + 1) / static_cast<double>(n + 1));
  const double pitch = (b - a).norm() / static_cast<double>(n + 1);
  if (pitch >= layout.widest() + kTightSpacingGap) {
    for (const Clearance clearance : kClearances) {
      if (layout.fits(spots, clearance)) return inMemberOrder(spots, order);
    }
  }
  why = std::to_string(n) + " objects between the two are " + std::to_string(static_cast<int>(std::round(pitch * 100.0))) +
        " cm apart, and need " + std::to_string(static_cast<int>(std::round((layout.widest() + kTightSpacingGap) * 100.0))) +
        " cm each clear of the ends and of what stands between them";
  return std::nullopt;
}

std::optional<std::vector<Vector3>> layOutLine(const ArrangementLayoutRequest& request, const Layout& layout, std::string& why) {
  if (request.between) return layOutBetween(request, layout, why);
  const Vector3 direction = flattened(request.direction).normalized();
  const std::size_t n = request.members.size();
  const double length = layout.pitch() * static_cast<double>(n - 1);
  const std::vector<std::size_t> order = orderAlong(request.members, direction);
  const std::vector<Vector3> centres = layout.centres();
  for (const double pitch : layout.pitches()) {
    const double span = pitch * static_cast<double>(n - 1);
    for (const Clearance clearance : kClearances) {
      for (const Vector3& centre : centres) {
        std::vector<Vector3> spots;
        for (std::size_t i = 0; i < n; ++i) spots.push_back(centre + direction * (-span / 2.0 + pitch * static_cast<double>(i)));
        if (layout.fits(spots, clearance)) return inMemberOrder(spots, order);
      }
    }
  }
  why = std::to_string(n) + " objects in a line need " + std::to_string(static_cast<int>(std::round((length + layout.widest()) * 100.0))) +
        " cm clear, and the reachable top has no such line free";
  return std::nullopt;
}

/// The centres of `members` in a row along `direction` about `centre`, in the order they stand
/// along it, each `gap` from the next (boxes of any size: the gaps, not the pitch, are equal).
std::vector<Vector3> rowOf(const std::vector<AlignedBox3>& members, const Vector3& direction, const Vector3& centre, double gap) {
  const std::size_t n = members.size();
  const std::vector<std::size_t> order = orderAlong(members, direction);
  const auto halfAlong = [&](const AlignedBox3& box) { return box.sizes().head<2>().dot(direction.head<2>().cwiseAbs()) / 2.0; };
  std::vector<double> offsets;
  double at = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double half = halfAlong(members[order[i]]);
    if (i > 0) at += half;
    offsets.push_back(at);
    at += half + gap;
  }
  const double middle = (offsets.front() + offsets.back()) / 2.0;
  std::vector<Vector3> spots(n);
  for (std::size_t i = 0; i < n; ++i) spots[order[i]] = centre + direction * (offsets[i] - middle);
  return spots;
}

/// Next to each other: a row (sideways, else away from the robot) as near to where they stand
/// now as it fits, with room for the fingers between neighbours first, then tighter.
std::optional<std::vector<Vector3>> layOutTogether(const ArrangementLayoutRequest& request, const Layout& layout, std::string& why) {
  Vector3 centroid = Vector3::Zero();
  for (const AlignedBox3& member : request.members) centroid += flattened(member.center());
  centroid /= static_cast<double>(request.members.size());
  const AlignedBox3& area = request.centreArea.value_or(request.area);
  const std::vector<Vector3> centres = gridOver(area, request.centreArea ? area.center() : centroid);
  for (const double gap : {kSpacingGap, (kSpacingGap + kTightSpacingGap) / 2.0, kTightSpacingGap}) {
    for (const Clearance clearance : kClearances) {
      for (const Vector3& centre : centres) {
        for (const Vector3& direction : {Vector3(Vector3::UnitY()), Vector3(Vector3::UnitX())}) {
          std::vector<Vector3> spots = rowOf(request.members, direction, centre, gap);
          if (layout.fits(spots, clearance)) return spots;
        }
      }
    }
  }
  double length = kTightSpacingGap * static_cast<double>(request.members.size() - 1);
  for (const AlignedBox3& member : request.members) length += member.sizes().y();
  why = std::to_string(request.members.size()) + " objects next to each other need a row " +
        std::to_string(static_cast<int>(std::round(length * 100.0))) + " cm long free, and the reachable top has none";
  return std::nullopt;
}

/// The members row by row from a pyramid's base of `base` (indices): each row but the top of
/// members of one height (within kLevelTolerance), so that the row above lies level; of those,
/// the largest footprints first. None, with why, when some row has no such members.
std::optional<std::vector<std::size_t>> pyramidRows(const std::vector<AlignedBox3>& members, std::size_t base, std::string& why) {
  std::vector<std::size_t> left(members.size());
  std::iota(left.begin(), left.end(), 0);
  const auto footprint = [&](std::size_t i) { return members[i].sizes().head<2>().prod(); };
  std::stable_sort(left.begin(), left.end(), [&](std::size_t a, std::size_t b) { return footprint(a) > footprint(b); });
  std::vector<std::size_t> rows;
  for (std::size_t size = base; size >= 2; --size) {
    std::optional<std::vector<std::size_t>> best;
    double bestArea = 0.0;
    for (const std::size_t first : left) {  // the members as tall as `first`, largest first
      std::vector<std::size_t> row;
      double area = 0.0;
      for (const std::size_t other : left) {
        if (row.size() < size && std::abs(members[other].sizes().z() - members[first].sizes().z()) <= kLevelTolerance) {
          row.push_back(other);
          area += footprint(other);
        }
      }
      if (row.size() == size && area > bestArea) best = row, bestArea = area;
    }
    if (!best) {
      why = "a pyramid's row of " + std::to_string(size) + " needs " + std::to_string(size) + " objects of one height for the row above to lie level";
      return std::nullopt;
    }
    rows.insert(rows.end(), best->begin(), best->end());
    left.erase(std::remove_if(left.begin(), left.end(), [&](std::size_t i) { return std::find(best->begin(), best->end(), i) != best->end(); }),
               left.end());
  }
  rows.insert(rows.end(), left.begin(), left.end());
  return rows;
}

/// Every member's spot when the base row (`baseMembers`, members `rows[0..base)`, at `row`) stands
/// along `direction`: each higher member (the rest of `rows`, row by row) over the middle of two
/// neighbours below, z the height its bottom rises to.
std::vector<Vector3> rowsOnTop(const std::vector<AlignedBox3>& members, const std::vector<std::size_t>& rows,
                               const std::vector<AlignedBox3>& baseMembers, const std::vector<Vector3>& row, const Vector3& direction) {
  std::vector<Vector3> spots(members.size());
  std::vector<Vector3> below;  // the row below from one end, and its tops
  std::vector<double> tops;
  for (const std::size_t k : orderAlong(baseMembers, direction)) below.push_back(row[k]), tops.push_back(baseMembers[k].sizes().z());
  for (std::size_t k = 0; k < baseMembers.size(); ++k) spots[rows[k]] = row[k];
  for (std::size_t next = baseMembers.size(); next < members.size();) {
    std::vector<Vector3> above;
    std::vector<double> aboveTops;
    for (std::size_t k = 0; k + 1 < below.size(); ++k, ++next) {
      const double rise = std::max(tops[k], tops[k + 1]);
      above.push_back(Vector3((below[k].x() + below[k + 1].x()) / 2.0, (below[k].y() + below[k + 1].y()) / 2.0, rise));
      aboveTops.push_back(rise + members[rows[next]].sizes().z());
      spots[rows[next]] = above.back();
    }
    below = std::move(above);
    tops = std::move(aboveTops);
  }
  return spots;
}

/// A pyramid: its base row (pyramidRows()) `kPyramidGap` apart (sideways, else away from the
/// robot), each higher member over the middle of two neighbours of the row below; z is how far its
/// bottom rises above the support's top.
std::optional<std::vector<Vector3>> layOutPyramid(const ArrangementLayoutRequest& request, const Layout& layout, std::string& why) {
  const std::size_t n = request.members.size();
  std::size_t base = 2;
  while (base * (base + 1) / 2 < n) ++base;
  const std::optional<std::vector<std::size_t>> bySize = pyramidRows(request.members, base, why);
  if (!bySize) return std::nullopt;
  std::vector<AlignedBox3> baseMembers;
  for (std::size_t i = 0; i < base; ++i) baseMembers.push_back(request.members[(*bySize)[i]]);
  for (const Clearance clearance : kClearances) {
    for (const Vector3& centre : layout.centres()) {
      for (const Vector3& direction : {flattened(request.direction).normalized(), Vector3(Vector3::UnitX())}) {
        const std::vector<Vector3> row = rowOf(baseMembers, direction, centre, kPyramidGap);
        if (!layout.fits(row, clearance)) continue;
        return rowsOnTop(request.members, *bySize, baseMembers, row, direction);
      }
    }
  }
  why = "a pyramid of " + std::to_string(n) + " objects needs a row of " + std::to_string(base) + " side by side free, and the reachable top has none";
  return std::nullopt;
}

/// A circle (its members evenly around it), or a triangle or square (its corners, and as many more
/// members evenly along each side): neighbours a pitch apart, or around the box it goes around.
std::optional<std::vector<Vector3>> layOutRing(const ArrangementLayoutRequest& request, const Layout& layout, std::string& why) {
  const std::size_t n = request.members.size();
  const std::size_t corners = polygonCorners(request.shape) != 0 ? polygonCorners(request.shape) : n;
  const std::size_t perSide = n / corners;
  const double share = 2.0 * std::numbers::pi / static_cast<double>(corners);
  double radius = static_cast<double>(perSide) * layout.pitch() / (2.0 * std::sin(std::numbers::pi / static_cast<double>(corners)));
  if (request.around) {  // clear of the box it goes around, grown as clear() grows it, at any angle
    const Eigen::Vector2d corner = request.around->sizes().head<2>() / 2.0 + Eigen::Vector2d::Constant(layout.widest() / 2.0 + kOtherClearance);
    radius = std::max(radius, corner.norm() + 1e-3);
  }
  const double first = request.shape == ArrangementShape::kSquare ? std::numbers::pi / 4.0 : 0.0;  // a square's sides along x and y
  const std::vector<Vector3> centres = layout.centres();
  for (const Clearance clearance : kClearances) {
    for (const Vector3& centre : centres) {
      for (int r = 0; r < kRotations; ++r) {
        const double rotation = first + share * static_cast<double>(r) / kRotations;
        std::vector<Vector3> spots;
        for (const Eigen::Vector2d& spot : regularOutline(centre.head<2>(), radius, rotation, corners, perSide)) {
          spots.emplace_back(spot.x(), spot.y(), centre.z());
        }
        if (layout.fits(spots, clearance)) return leastTravel(request.members, spots);
      }
    }
  }
  why = std::to_string(n) + " objects in a " + arrangementShapeName(request.shape) + " need a free circle " +
        std::to_string(static_cast<int>(std::round((2.0 * radius + layout.widest()) * 100.0))) + " cm across" +
        (request.around ? " around it" : "") + ", and the reachable top has none";
  return std::nullopt;
}

/// Members far enough from the others stay; each other one goes to the free spot nearest to it
/// that is far enough from every member placed.
std::optional<std::vector<Vector3>> layOutSpread(const ArrangementLayoutRequest& request, const Layout& layout, std::string& why) {
  const std::vector<AlignedBox3>& members = request.members;
  const double gap = request.spreadGap + kSpreadSlack;
  std::vector<std::size_t> crowd(members.size(), 0);
  for (std::size_t i = 0; i < members.size(); ++i) {
    for (std::size_t j = 0; j < members.size(); ++j) crowd[i] += i != j && footprintGap(members[i], members[j]) < gap ? 1 : 0;
  }
  std::vector<std::size_t> order(members.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return crowd[a] < crowd[b]; });
  std::vector<std::optional<AlignedBox3>> placed(members.size());
  const auto farFromPlaced = [&](const AlignedBox3& box) {
    return std::all_of(placed.begin(), placed.end(), [&](const std::optional<AlignedBox3>& other) { return !other || footprintGap(box, *other) >= gap; });
  };
  // First those far enough from the rest stay and the others go to the nearest room; when that
  // leaves one without room, all of them go, the farthest room from the middle first.
  for (const bool keep : {true, false}) {
    std::fill(placed.begin(), placed.end(), std::nullopt);
    for (const std::size_t i : order) {
      if (keep && request.onSupport[i] && layout.inside(flattened(members[i].center())) && farFromPlaced(members[i])) placed[i] = members[i];
    }
    bool room = true;
    for (const std::size_t i : order) {
      if (placed[i]) continue;
      std::vector<Vector3> candidates = gridOver(request.area, members[i].center());
      if (!keep) {  // farthest from the middle first
        candidates = gridOver(request.area, request.area.center());
        std::reverse(candidates.begin(), candidates.end());
      }
      for (const Vector3& spot : candidates) {
        const AlignedBox3 box = movedTo(members[i], spot);
        if (layout.inside(spot) && layout.clear(spot, Clearance::kOfOthers) && farFromPlaced(box)) {
          placed[i] = box;
          break;
        }
      }
      room = room && placed[i].has_value();
      if (!room) break;
    }
    if (room) break;
    if (!keep) {
      why = std::to_string(members.size()) + " objects spread out need " + std::to_string(static_cast<int>(std::round(gap * 100.0))) +
            " cm between each two, and the reachable top has no room for that";
      return std::nullopt;
    }
  }
  std::vector<Vector3> spots;
  for (const std::optional<AlignedBox3>& box : placed) spots.push_back(flattened(box->center()));
  return spots;
}

}  // namespace

std::optional<std::vector<Vector3>> layOutArrangement(const ArrangementLayoutRequest& request, std::string& why) {
  const Layout layout(request);
  if (request.spacing && *request.spacing < layout.widest()) {
    why = "objects " + metresText(*request.spacing) + " apart would overlap: the widest is wider than that";
    return std::nullopt;
  }
  switch (request.shape) {
    case ArrangementShape::kLine: return layOutLine(request, layout, why);
    case ArrangementShape::kCircle:
    case ArrangementShape::kTriangle:
    case ArrangementShape::kSquare: return layOutRing(request, layout, why);
    case ArrangementShape::kSpreadOut: return layOutSpread(request, layout, why);
    case ArrangementShape::kTogether: return layOutTogether(request, layout, why);
    case ArrangementShape::kPyramid: return layOutPyramid(request, layout, why);
  }
  why = "unknown shape";
  return std::nullopt;
}

}  // namespace lang2manip::language_detail
