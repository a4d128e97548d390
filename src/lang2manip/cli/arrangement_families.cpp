// Arrangement families of issue 23 (class 2), this project's own, in the style of the benchmarks'
// templates: lines along an edge, evenly spaced; circles (around a bowl); triangles and squares;
// blocks spread out; a pyramid of three. Each has its own check of the final world, written from what the words mean
// to a person (not from the product's arranged-goal check), and a reference plan laid out here.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "lang2manip/cli/family_support.hpp"
#include "lang2manip/cli/tabletop_scenes.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/grounding/object_geometry.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"

namespace lang2manip::families {
namespace {

using Point = Eigen::Vector2d;

GoalCheck pass() { return {true, ""}; }
GoalCheck failure(std::string why) { return {false, std::move(why)}; }

/// The blocks' centres (base frame, x-y) when every one stands on the desk; else why not.
std::optional<std::vector<Point>> centresOnDesk(const Scene& final, const std::vector<std::string>& blocks, std::string& why) {
  const SymbolicState state = observeSymbolicState(final);
  std::vector<Point> centres;
  for (const std::string& block : blocks) {
    const auto on = state.onTopOf.find(block);
    if (on == state.onTopOf.end() || on->second != "desk") {
      why = block + " does not stand on the desk";
      return std::nullopt;
    }
    centres.push_back(centreInBase(final, block).head<2>());
  }
  return centres;
}

Point meanOf(const std::vector<Point>& points) {
  Point sum = Point::Zero();
  for (const Point& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

/// On one circle about their mean (radii within 2.5 cm of each other), none closer than half an
/// even share of the turn to the next; around `centre` (within 3 cm) when given.
Check circleOf(std::vector<std::string> blocks, std::optional<std::string> around) {
  return [blocks = std::move(blocks), around](const Scene& final, const Scene&) {
    std::string why;
    const auto centres = centresOnDesk(final, blocks, why);
    if (!centres) return failure(why);
    const Point middle = meanOf(*centres);
    std::vector<double> radii, angles;
    for (const Point& p : *centres) radii.push_back((p - middle).norm()), angles.push_back(std::atan2(p.y() - middle.y(), p.x() - middle.x()));
    const auto [low, high] = std::minmax_element(radii.begin(), radii.end());
    if (*high - *low > 0.025) return failure("radii from " + metresText(*low) + " to " + metresText(*high));
    std::sort(angles.begin(), angles.end());
    const double share = 2.0 * std::numbers::pi / static_cast<double>(angles.size());
    double narrowest = angles.front() + 2.0 * std::numbers::pi - angles.back();
    for (std::size_t i = 1; i < angles.size(); ++i) narrowest = std::min(narrowest, angles[i] - angles[i - 1]);
    if (narrowest < share / 2.0) return failure("two blocks bunched on the circle");
    if (around && (middle - centreInBase(final, *around).head<2>()).norm() > 0.03) return failure("the circle is not around " + *around);
    return pass();
  };
}

/// Three blocks with equal sides, or four with four equal sides and two equal diagonals (each
/// within 3 cm), sides of at least 5 cm.
Check polygonOf(std::vector<std::string> blocks) {
  return [blocks = std::move(blocks)](const Scene& final, const Scene&) {
    std::string why;
    const auto centres = centresOnDesk(final, blocks, why);
    if (!centres) return failure(why);
    std::vector<double> distances;
    for (std::size_t i = 0; i < centres->size(); ++i) {
      for (std::size_t j = i + 1; j < centres->size(); ++j) distances.push_back(((*centres)[i] - (*centres)[j]).norm());
    }
    std::sort(distances.begin(), distances.end());
    const std::size_t sides = blocks.size() == 3 ? 3 : 4;
    if (distances.front() < 0.05) return failure("two corners " + metresText(distances.front()) + " apart");
    if (distances[sides - 1] - distances.front() > 0.03) return failure("sides from " + metresText(distances.front()) + " to " + metresText(distances[sides - 1]));
    if (sides == 4 && (std::abs(distances[4] - distances.front() * std::sqrt(2.0)) > 0.04 || distances[5] - distances[4] > 0.03)) {
      return failure("the diagonals are not those of a square");
    }
    return pass();
  };
}

AlignedBox3 footprintInBase(const Scene& scene, const std::string& object) {
  return transformedBox(scene.object(object).worldBounds(), robotBaseFrame(scene, "").inverse());
}

/// Every two blocks' boxes (seen from above) at least 10 cm apart: no two next to each other.
Check spreadOutCheck(std::vector<std::string> blocks) {
  return [blocks = std::move(blocks)](const Scene& final, const Scene&) {
    std::string why;
    if (!centresOnDesk(final, blocks, why)) return failure(why);
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      for (std::size_t j = i + 1; j < blocks.size(); ++j) {
        const AlignedBox3 a = footprintInBase(final, blocks[i]), b = footprintInBase(final, blocks[j]);
        const Point apart = (a.min().head<2>() - b.max().head<2>()).cwiseMax(b.min().head<2>() - a.max().head<2>()).cwiseMax(0.0);
        if (apart.norm() < 0.10) return failure(blocks[i] + " and " + blocks[j] + " are " + metresText(apart.norm()) + " apart");
      }
    }
    return pass();
  };
}

/// One group: every block reached from any other through blocks whose boxes (seen from above)
/// come within 10 cm of each other.
Check togetherCheck(std::vector<std::string> blocks) {
  return [blocks = std::move(blocks)](const Scene& final, const Scene&) {
    std::string why;
    if (!centresOnDesk(final, blocks, why)) return failure(why);
    std::vector<std::size_t> group{0};
    std::vector<bool> joined(blocks.size(), false);
    joined[0] = true;
    for (std::size_t k = 0; k < group.size(); ++k) {
      const AlignedBox3 a = footprintInBase(final, blocks[group[k]]);
      for (std::size_t j = 0; j < blocks.size(); ++j) {
        const AlignedBox3 b = footprintInBase(final, blocks[j]);
        const Point apart = (a.min().head<2>() - b.max().head<2>()).cwiseMax(b.min().head<2>() - a.max().head<2>()).cwiseMax(0.0);
        if (!joined[j] && apart.norm() <= 0.10) joined[j] = true, group.push_back(j);
      }
    }
    for (std::size_t j = 0; j < blocks.size(); ++j) {
      if (!joined[j]) return failure(blocks[j] + " is more than 0.10 m from every block of " + blocks[0] + "'s group");
    }
    return pass();
  };
}

/// Two blocks on the desk and the third held up by both: its bottom within 1 cm of their tops,
/// its footprint over each of them by at least 5 mm, its centre over the gap between theirs
/// (within 1.5 cm of the segment joining them, not beyond either).
Check pyramidOf(std::vector<std::string> blocks) {
  return [blocks = std::move(blocks)](const Scene& final, const Scene&) {
    std::vector<AlignedBox3> boxes;
    for (const std::string& block : blocks) boxes.push_back(footprintInBase(final, block));
    std::size_t top = 0;
    for (std::size_t i = 1; i < boxes.size(); ++i) top = boxes[i].min().z() > boxes[top].min().z() ? i : top;
    std::vector<std::string> base;
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      if (i != top) base.push_back(blocks[i]);
    }
    std::string why;
    if (!centresOnDesk(final, base, why)) return failure(why);
    const AlignedBox3& upper = boxes[top];
    std::vector<Point> under;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      if (i == top) continue;
      const AlignedBox3& lower = boxes[i];
      if (std::abs(upper.min().z() - lower.max().z()) > 0.01) return failure(blocks[top] + " does not sit on " + blocks[i]);
      const Point overlap = upper.max().head<2>().cwiseMin(lower.max().head<2>()) - upper.min().head<2>().cwiseMax(lower.min().head<2>());
      if (overlap.minCoeff() < 0.005) return failure(blocks[top] + " is not over " + blocks[i]);
      under.push_back(lower.center().head<2>());
    }
    const Point along = under[1] - under[0];
    const Point centre = upper.center().head<2>();
    const double t = (centre - under[0]).dot(along) / along.squaredNorm();
    const double off = (centre - (under[0] + t * along)).norm();
    if (t <= 0.0 || t >= 1.0 || off > 0.015) return failure(blocks[top] + " is not over the gap between the other two");
    return pass();
  };
}

/// Sideways (within 20 degrees), every centre within 2 cm of the line and in the third of the
/// reachable desk by `edge` (far: +1, near: -1), neighbours spaced alike within 2 cm.
Check lineAlongEdge(std::vector<std::string> blocks, int edge) {
  return [blocks = std::move(blocks), edge](const Scene& final, const Scene&) {
    std::string why;
    const auto centres = centresOnDesk(final, blocks, why);
    if (!centres) return failure(why);
    const AlignedBox3 reach = deskReach(final);
    const double third = reach.sizes().x() / 3.0;
    std::vector<Point> sorted = *centres;
    std::sort(sorted.begin(), sorted.end(), [](const Point& a, const Point& b) { return a.y() < b.y(); });
    const Point direction = (sorted.back() - sorted.front()).normalized();
    if (std::abs(direction.x()) > std::sin(20.0 * std::numbers::pi / 180.0)) return failure("the line does not run sideways");
    std::vector<double> spacings;
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      const Point offset = sorted[i] - sorted.front();
      if (std::abs(offset.x() * direction.y() - offset.y() * direction.x()) > 0.02) return failure("a block is off the line");
      const bool inBand = edge > 0 ? sorted[i].x() >= reach.max().x() - third - 0.01 : sorted[i].x() <= reach.min().x() + third + 0.01;
      if (!inBand) return failure("a block is not by the " + std::string(edge > 0 ? "far" : "near") + " edge");
      if (i > 0) spacings.push_back((sorted[i] - sorted[i - 1]).norm());
    }
    const auto [low, high] = std::minmax_element(spacings.begin(), spacings.end());
    if (*high - *low > 0.02 || *low < 0.045) return failure("spacings from " + metresText(*low) + " to " + metresText(*high));
    return pass();
  };
}

/// Spots (base frame) at `offsets` from a centre tried over the reachable desk, each 3 cm clear
/// of every object's box and 4 cm inside the reach; none when no centre works.
std::optional<std::vector<Vector3>> freeSpots(const Scene& scene, const std::vector<Point>& offsets, const AlignedBox3& centres) {
  const AlignedBox3 reach = deskReach(scene);
  std::vector<AlignedBox3> taken;
  for (const SceneObject& object : scene.objects()) {
    const AlignedBox3 box = footprintInBase(scene, object.name);
    if (object.name != "desk" && box.max().z() > reach.max().z() + 0.005) taken.push_back(box);
  }
  const auto free = [&](const Point& p) {
    if (p.x() < reach.min().x() + 0.04 || p.x() > reach.max().x() - 0.04 || p.y() < reach.min().y() + 0.04 || p.y() > reach.max().y() - 0.04) return false;
    return std::none_of(taken.begin(), taken.end(), [&](const AlignedBox3& box) {
      return p.x() > box.min().x() - 0.05 && p.x() < box.max().x() + 0.05 && p.y() > box.min().y() - 0.05 && p.y() < box.max().y() + 0.05;
    });
  };
  for (double x = centres.min().x(); x <= centres.max().x(); x += 0.03) {
    for (double y = centres.min().y(); y <= centres.max().y(); y += 0.03) {
      std::vector<Vector3> spots;
      for (const Point& offset : offsets) spots.emplace_back(x + offset.x(), y + offset.y(), reach.max().z());
      if (std::all_of(spots.begin(), spots.end(), [&](const Vector3& s) { return free(s.head<2>()); })) return spots;
    }
  }
  return std::nullopt;
}

std::vector<Point> ringOffsets(std::size_t n, double radius, double first) {
  std::vector<Point> offsets;
  for (std::size_t k = 0; k < n; ++k) {
    const double angle = first + 2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n);
    offsets.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
  }
  return offsets;
}

std::optional<FamilyInstance> withPlan(FamilyInstance instance, const std::vector<std::string>& blocks, const std::optional<std::vector<Vector3>>& spots) {
  if (!spots) return std::nullopt;
  for (std::size_t i = 0; i < blocks.size(); ++i) addPickPlaceAt(instance.plan, blocks[i], (*spots)[i]);
  return instance;
}

std::optional<Scene> blocksAndBowls(const Scene& desk, int blocks, int bowls, Random& random) {
  TabletopRequest request;
  request.blocks = blocks;
  request.bowls = bowls;
  return generateTabletop(desk, request, random);
}

std::optional<FamilyInstance> lineAlongAnEdge(const Scene& desk, Random& random) {
  auto scene = blocksAndBowls(desk, drawCount(3, 4, random), drawCount(0, 1, random), random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const int edge = random.uniform(0.0, 1.0) < 0.5 ? 1 : -1;
  const std::string side = edge > 0 ? drawOne(std::vector<std::string>{"top", "far"}, random) : drawOne(std::vector<std::string>{"bottom", "near"}, random);
  const std::vector<std::string> wordings{"put the blocks in an evenly spaced line along the " + side + " edge",
                                          "line up all the blocks along the " + side + " edge",
                                          "arrange the blocks in a row along the " + side + " edge, evenly spaced",
                                          "put all the blocks in a horizontal line along the " + side + " edge"};
  FamilyInstance result{"own_line_along_edge", drawOne(wordings, random), *scene, lineAlongEdge(blocks, edge), {}};
  const AlignedBox3 reach = deskReach(*scene);
  const double third = reach.sizes().x() / 3.0;
  AlignedBox3 band = reach;
  if (edge > 0) band.min().x() = reach.max().x() - third + 0.03;
  else band.max().x() = reach.min().x() + third - 0.03;
  std::vector<Point> offsets;
  for (std::size_t i = 0; i < blocks.size(); ++i) offsets.emplace_back(0.0, 0.08 * (static_cast<double>(i) - static_cast<double>(blocks.size() - 1) / 2.0));
  return withPlan(result, blocks, freeSpots(*scene, offsets, band));
}

std::optional<FamilyInstance> circle(const Scene& desk, Random& random) {
  const bool aroundBowl = random.uniform(0.0, 1.0) < 0.4;
  auto scene = blocksAndBowls(desk, drawCount(3, 5, random), aroundBowl ? 1 : drawCount(0, 1, random), random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  std::optional<std::string> bowl;
  if (aroundBowl) bowl = objectsOfKind(*scene, "bowl").front();
  const std::vector<std::string> wordings =
      aroundBowl ? std::vector<std::string>{"arrange the blocks in a circle around the " + spoken(*bowl), "put the blocks in a ring around the " + spoken(*bowl)}
                 : std::vector<std::string>{"arrange the blocks in a circle", "make a circle with all the blocks", "put the blocks in a ring",
                                            "form a circle out of the blocks"};
  FamilyInstance result{"own_circle", drawOne(wordings, random), *scene, circleOf(blocks, bowl), {}};
  if (!bowl) {
    const double radius = 0.08 / (2.0 * std::sin(std::numbers::pi / static_cast<double>(blocks.size())));
    return withPlan(result, blocks, freeSpots(*scene, ringOffsets(blocks.size(), radius, 0.0), deskReach(*scene)));
  }
  // Around the bowl: the blocks clear of its rim, the circle centred on it (its own box is not free).
  const Vector3 centre = centreInBase(*scene, *bowl);
  const double radius = scene->object(*bowl).dimensions().head<2>().maxCoeff() / 2.0 * std::sqrt(2.0) + 0.06;
  std::vector<Vector3> spots;
  for (const Point& offset : ringOffsets(blocks.size(), radius, std::numbers::pi / 2.0)) spots.emplace_back(centre.x() + offset.x(), centre.y() + offset.y(), centre.z());
  const AlignedBox3 reach = deskReach(*scene);
  for (const Vector3& spot : spots) {
    if (spot.x() < reach.min().x() + 0.03 || spot.x() > reach.max().x() - 0.03 || spot.y() < reach.min().y() + 0.03 || spot.y() > reach.max().y() - 0.03) return std::nullopt;
  }
  return withPlan(result, blocks, spots);
}

std::optional<FamilyInstance> polygon(const Scene& desk, Random& random) {
  const bool triangle = random.uniform(0.0, 1.0) < 0.5;
  auto scene = blocksAndBowls(desk, triangle ? 3 : 4, drawCount(0, 1, random), random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const std::vector<std::string> wordings =
      triangle ? std::vector<std::string>{"make a triangle with the blocks", "put the three blocks in a triangle", "arrange the blocks in a triangular formation"}
               : std::vector<std::string>{"put the four blocks in a square", "arrange the blocks in the shape of a square", "make a square out of the blocks"};
  FamilyInstance result{"own_triangle_square", drawOne(wordings, random), *scene, polygonOf(blocks), {}};
  const double radius = 0.09 / (2.0 * std::sin(std::numbers::pi / static_cast<double>(blocks.size())));
  return withPlan(result, blocks, freeSpots(*scene, ringOffsets(blocks.size(), radius, triangle ? 0.0 : std::numbers::pi / 4.0), deskReach(*scene)));
}

std::optional<FamilyInstance> spreadOut(const Scene& desk, Random& random) {
  TabletopRequest request;
  request.blocks = drawCount(3, 4, random);
  request.gap = 0.02;  // drawn close together: some are next to each other
  auto scene = generateTabletop(desk, request, random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const std::vector<std::string> wordings{"spread out the blocks", "spread the blocks out on the table", "scatter the blocks", "space the blocks out",
                                          "put the blocks far apart from each other"};
  FamilyInstance result{"own_spread_out", drawOne(wordings, random), *scene, spreadOutCheck(blocks), {}};
  // The reference: a wide square of spots about the middle of the reach, as many as there are blocks.
  const AlignedBox3 reach = deskReach(*scene);
  const double half = std::min(reach.sizes().x(), reach.sizes().y()) / 2.0 - 0.05;
  if (half < 0.09) return std::nullopt;
  std::vector<Point> offsets{{-half, -half}, {half, half}, {-half, half}, {half, -half}};
  offsets.resize(blocks.size());
  const Vector3 shift(0.03, 0.03, 0.0);
  return withPlan(result, blocks, freeSpots(*scene, offsets, AlignedBox3(reach.center() - shift, reach.center() + shift)));
}

std::optional<FamilyInstance> together(const Scene& desk, Random& random) {
  TabletopRequest request;
  request.blocks = drawCount(2, 4, random);
  request.gap = 0.12;  // drawn apart: none next to another
  auto scene = generateTabletop(desk, request, random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const std::vector<std::string> wordings{"put the blocks next to each other", "place the blocks side by side on the table", "gather the blocks",
                                          "group the blocks together", "bring all the blocks close together", "put the blocks close to one another"};
  FamilyInstance result{"own_together", drawOne(wordings, random), *scene, togetherCheck(blocks), {}};
  std::vector<Point> offsets;
  for (std::size_t i = 0; i < blocks.size(); ++i) offsets.emplace_back(0.0, 0.085 * (static_cast<double>(i) - static_cast<double>(blocks.size() - 1) / 2.0));
  return withPlan(result, blocks, freeSpots(*scene, offsets, deskReach(*scene)));
}

std::optional<FamilyInstance> pyramid(const Scene& desk, Random& random) {
  auto scene = blocksAndBowls(desk, 3, drawCount(0, 1, random), random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const std::vector<std::string> wordings{"build a pyramid with the three blocks", "stack the blocks into a pyramid", "make a pyramid out of the blocks",
                                          "arrange the blocks in a pyramid", "put the blocks in a pyramid shape"};
  FamilyInstance result{"own_pyramid", drawOne(wordings, random), *scene, pyramidOf(blocks), {}};
  // The reference: two side by side 2 cm apart (room for the fingers), the third on both.
  std::optional<std::vector<Vector3>> spots = freeSpots(*scene, {{0.0, -0.03}, {0.0, 0.03}, {0.0, 0.0}}, deskReach(*scene));
  if (spots) (*spots)[2].z() += scene->object(blocks[0]).dimensions().z();
  return withPlan(result, blocks, spots);
}

}  // namespace

std::vector<InstructionFamily> arrangementFamilies() {
  return {{"own_line_along_edge", "own", notYetDone(lineAlongAnEdge)},
          {"own_circle", "own", notYetDone(circle)},
          {"own_triangle_square", "own", notYetDone(polygon)},
          {"own_spread_out", "own", notYetDone(spreadOut)},
          {"own_together", "own", notYetDone(together)},
          {"own_pyramid", "own", notYetDone(pyramid)}};
}

}  // namespace lang2manip::families
