#include "lang2manip/cli/family_support.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "lang2manip/cli/tabletop_scenes.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/grounding/placement.hpp"
#include "lang2manip/language/words.hpp"
#include "lang2manip/symbolic/object_heading.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"

namespace lang2manip::families {
namespace {

using Kind = SurfaceRegion::Kind;

GoalCheck holds(std::string why = "") { return {true, std::move(why)}; }
GoalCheck fails(std::string why) { return {false, std::move(why)}; }

std::string location(const SymbolicState& state, const std::string& object) {
  if (const auto on = state.onTopOf.find(object); on != state.onTopOf.end()) return "on " + on->second;
  if (const auto in = state.inside.find(object); in != state.inside.end()) return "in " + in->second;
  return state.held == object ? "held" : "nowhere";
}

/// The container of `containers` that `object` is in; empty when it is in none of them.
std::string containerAmong(const SymbolicState& state, const std::string& object, const std::vector<std::string>& containers) {
  const auto in = state.inside.find(object);
  if (in == state.inside.end() || std::find(containers.begin(), containers.end(), in->second) == containers.end()) return {};
  return in->second;
}

}  // namespace

const std::vector<RegionWords>& corners() {
  static const std::vector<RegionWords> words{{"top left corner", {Kind::kCorner, 1, 1}},
                                              {"top right corner", {Kind::kCorner, 1, -1}},
                                              {"bottom left corner", {Kind::kCorner, -1, 1}},
                                              {"bottom right corner", {Kind::kCorner, -1, -1}}};
  return words;
}

const std::vector<RegionWords>& cornersAndSides() {
  static const std::vector<RegionWords> words = [] {
    std::vector<RegionWords> all = corners();
    all.push_back({"top side", {Kind::kEdge, 1, 0}});
    all.push_back({"bottom side", {Kind::kEdge, -1, 0}});
    all.push_back({"left side", {Kind::kEdge, 0, 1}});
    all.push_back({"right side", {Kind::kEdge, 0, -1}});
    return all;
  }();
  return words;
}

int drawCount(int low, int high, Random& random) {
  return std::min(high, low + static_cast<int>(random.uniform(0.0, static_cast<double>(high - low + 1))));
}

Vector3 centreInBase(const Scene& scene, const std::string& object) {
  return robotBaseFrame(scene, "").inverse() * scene.object(object).worldBounds().center();
}

int blocksHeld(const Scene& scene, const std::string& bowl, double edge) {
  constexpr double kGap = 0.01;
  const auto& cavity = scene.object(bowl).cavity;
  if (!cavity) return 0;
  // Placement keeps its wall margin from each wall.
  const double margin = 2.0 * PlacementSettings{}.wallMargin;
  const auto along = [&](double length) { return static_cast<int>(std::floor((length - margin + kGap) / (edge + kGap))); };
  return along(cavity->sizes().x()) * along(cavity->sizes().y());
}

bool bowlsClearOf(const Scene& scene, const SurfaceRegion& region) {
  const AlignedBox3 box = regionBox(deskReach(scene), region);
  const Pose toBase = robotBaseFrame(scene, "").inverse();
  for (const std::string& bowl : objectsOfKind(scene, "bowl")) {
    const AlignedBox3 footprint = scene.object(bowl).worldBounds().transformed(toBase);
    const bool overlaps = footprint.min().x() < box.max().x() && footprint.max().x() > box.min().x() &&
                          footprint.min().y() < box.max().y() && footprint.max().y() > box.min().y();
    if (overlaps) return false;
  }
  return true;
}

bool footprintClear(const Scene& scene, const Vector3& centre, const Vector3& size, double clearance,
                    const std::vector<std::string>& ignore) {
  const Pose toBase = robotBaseFrame(scene, "").inverse();
  const Vector3 half(size.x() / 2.0, size.y() / 2.0, 0.0);
  const AlignedBox3 footprint(centre - half, centre + half);
  for (const SceneObject& object : scene.objects()) {
    if (object.role == ObjectRole::kSupport || std::find(ignore.begin(), ignore.end(), object.name) != ignore.end()) continue;
    AlignedBox3 other = object.worldBounds().transformed(toBase);
    other.min().z() = footprint.min().z();
    other.max().z() = footprint.max().z();
    if (boxGap(footprint, other) < clearance) return false;
  }
  return true;
}

int blocksFitting(const Scene& scene, const SurfaceRegion& region, double edge) {
  constexpr double kSpacing = 0.02, kBowlClearance = 0.03, kStep = 0.005;
  const Vector3 size(edge, edge, 0.0);
  const std::optional<AlignedBox3> centres = regionCentres(deskReach(scene), region, size);
  if (!centres) return 0;
  std::vector<std::string> blocks = objectsOfKind(scene, "block");
  std::vector<Vector3> placed;
  for (double x = centres->min().x(); x <= centres->max().x() + 1e-9; x += kStep) {
    for (double y = centres->min().y(); y <= centres->max().y() + 1e-9; y += kStep) {
      const Vector3 spot(x, y, centres->max().z());
      const bool apart = std::all_of(placed.begin(), placed.end(), [&](const Vector3& other) {
        return std::max(std::abs(other.x() - x), std::abs(other.y() - y)) >= edge + kSpacing;
      });
      if (apart && footprintClear(scene, spot, size, kBowlClearance, blocks)) placed.push_back(spot);
    }
  }
  return static_cast<int>(placed.size());
}

std::string spoken(const std::string& object) {
  std::string words = object;
  std::replace(words.begin(), words.end(), '_', ' ');
  if (const auto digit = words.find_first_of("0123456789"); digit != std::string::npos && digit > 0) words.erase(digit - 1);
  return words;
}

Goal relationGoal(const std::string& object, SpatialRelation relation, const std::string& target, std::optional<SurfaceRegion> region) {
  Goal goal;
  goal.kind = GoalKind::kRelation;
  goal.object = object;
  goal.relation = relation;
  goal.target = target;
  goal.region = region;
  return goal;
}

Check allOf(std::vector<Goal> goals) {
  return [goals = std::move(goals)](const Scene& final, const Scene& initial) {
    GoalCheckOptions options;
    options.arm = actingArm(final);
    options.initialScene = &initial;
    for (const Goal& goal : goals) {
      const GoalCheck check = checkGoalInScene(final, goal, options);
      if (!check.holds) return fails(describeGoal(goal) + ": " + check.explanation);
    }
    return holds();
  };
}

Check tower(std::vector<std::string> objects, std::optional<SurfaceRegion> region) {
  return [objects = std::move(objects), region](const Scene& final, const Scene&) {
    const SymbolicState state = observeSymbolicState(final);
    std::map<std::string, int> carried;
    std::string bottom;
    for (const std::string& object : objects) {
      const auto on = state.onTopOf.find(object);
      if (on == state.onTopOf.end()) return fails(object + " is " + location(state, object) + ", not in the tower");
      if (on->second == "desk") {
        if (!bottom.empty()) return fails("two towers: " + bottom + " and " + object + " both stand on the desk");
        bottom = object;
      } else if (std::find(objects.begin(), objects.end(), on->second) == objects.end()) {
        return fails(object + " is on " + on->second + ", not on the tower");
      } else if (++carried[on->second] > 1) {
        return fails("two objects on " + on->second);
      }
    }
    if (bottom.empty()) return fails("no object of the tower stands on the desk");
    if (region) return allOf({relationGoal(bottom, SpatialRelation::kOn, "desk", region)})(final, final);
    return holds();
  };
}

Check differentCorners(std::vector<std::string> objects) {
  return [objects = std::move(objects)](const Scene& final, const Scene&) {
    GoalCheckOptions options;
    options.arm = actingArm(final);
    std::set<std::string> used;
    for (const std::string& object : objects) {
      std::string corner;
      for (const RegionWords& words : corners()) {
        if (checkGoalInScene(final, relationGoal(object, SpatialRelation::kOn, "desk", words.region), options).holds) corner = words.words;
      }
      if (corner.empty()) return fails(object + " is in no corner of the desk");
      if (!used.insert(corner).second) return fails("two objects in the " + corner);
    }
    return holds();
  };
}

Check mismatchedContainers(std::vector<std::string> objects, std::vector<std::string> containers) {
  return [objects = std::move(objects), containers = std::move(containers)](const Scene& final, const Scene&) {
    const SymbolicState state = observeSymbolicState(final);
    for (const std::string& object : objects) {
      const std::string container = containerAmong(state, object, containers);
      if (container.empty()) return fails(object + " is " + location(state, object) + ", in no bowl");
      if (colourOf(container) == colourOf(object)) return fails(object + " is in " + container + ", of its own colour");
    }
    return holds();
  };
}

Check inAnyOf(std::vector<std::string> objects, std::vector<std::string> containers) {
  return [objects = std::move(objects), containers = std::move(containers)](const Scene& final, const Scene&) {
    const SymbolicState state = observeSymbolicState(final);
    for (const std::string& object : objects) {
      if (containerAmong(state, object, containers).empty()) {
        return fails(object + " is " + location(state, object) + ", in none of " + joinNames(containers));
      }
    }
    return holds();
  };
}

Check inLine(std::vector<std::string> objects, double heading) {
  return [objects = std::move(objects), heading](const Scene& final, const Scene&) {
    const SymbolicState state = observeSymbolicState(final);
    std::vector<Vector3> centres;
    for (const std::string& object : objects) {
      if (location(state, object) != "on desk") return fails(object + " is " + location(state, object) + ", not on the desk");
      centres.push_back(centreInBase(final, object));
    }
    // The line through the two centres farthest apart; the others within 2 cm of it.
    std::size_t a = 0, b = 1;
    for (std::size_t i = 0; i < centres.size(); ++i) {
      for (std::size_t j = i + 1; j < centres.size(); ++j) {
        if ((centres[i] - centres[j]).head<2>().norm() > (centres[a] - centres[b]).head<2>().norm()) a = i, b = j;
      }
    }
    const Eigen::Vector2d direction = (centres[b] - centres[a]).head<2>().normalized();
    const double angle = std::abs(std::remainder(std::atan2(direction.y(), direction.x()) - heading, 3.14159265358979323846));
    if (angle > 20.0 * 3.14159265358979323846 / 180.0) return fails("the line runs " + degreesText(angle) + " off its direction");
    for (std::size_t i = 0; i < centres.size(); ++i) {
      const Eigen::Vector2d offset = (centres[i] - centres[a]).head<2>();
      const double off = std::abs(offset.x() * direction.y() - offset.y() * direction.x());
      if (off > 0.02) return fails(objects[i] + " is " + metresText(off) + " off the line");
      for (std::size_t j = 0; j < i; ++j) {
        if ((centres[i] - centres[j]).head<2>().norm() < 0.035) return fails(objects[i] + " and " + objects[j] + " overlap on the line");
      }
    }
    return holds();
  };
}

Check besideWithin(std::string object, SpatialRelation relation, std::string reference, double least, double most) {
  return [=](const Scene& final, const Scene& initial) {
    const GoalCheck side = allOf({relationGoal(object, relation, reference)})(final, initial);
    if (!side.holds) return side;
    const double gap = boxGap(final.object(object).worldBounds(), final.object(reference).worldBounds());
    if (gap < least || gap > most) {
      return fails(object + " is " + metresText(gap) + " from " + reference + " (wanted " + metresText(least) + " to " + metresText(most) + ")");
    }
    return holds();
  };
}

void addPickPlace(Plan& plan, const std::string& object, SpatialRelation relation, const std::string& target,
                  std::optional<SurfaceRegion> region) {
  plan.actions.push_back({ActionType::kPick, object, {}, {}, ""});
  SymbolicAction place{ActionType::kPlace, object, {}, {}, ""};
  place.params.relation = relation;
  place.params.target = target;
  place.params.region = region;
  plan.actions.push_back(place);
}

void addPickPlaceAt(Plan& plan, const std::string& object, const Vector3& position) {
  plan.actions.push_back({ActionType::kPick, object, {}, {}, ""});
  SymbolicAction place{ActionType::kPlace, object, {}, {}, ""};
  place.params.position = position;
  plan.actions.push_back(place);
}

std::function<std::optional<FamilyInstance>(const Scene&, Random&)> notYetDone(std::optional<FamilyInstance> (*make)(const Scene&, Random&)) {
  return [make](const Scene& desk, Random& random) -> std::optional<FamilyInstance> {
    std::optional<FamilyInstance> instance = make(desk, random);
    if (instance && instance->check(instance->scene, instance->scene).holds) return std::nullopt;
    return instance;
  };
}

}  // namespace lang2manip::families
