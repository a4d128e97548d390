// The families, each written from its paper's description: Code as Policies (Liang et al. 2022,
// simulated tabletop: seen and unseen instructions) and CLIPort/Ravens (Shridhar et al. 2021,
// language-conditioned tasks). Templates, wordings and checks are this project's own.

#include "lang2manip/cli/instruction_families.hpp"

#include <algorithm>
#include <cmath>

#include "lang2manip/cli/family_support.hpp"
#include "lang2manip/cli/tabletop_scenes.hpp"

namespace lang2manip {
namespace {

using namespace families;
using R = SpatialRelation;

std::optional<Scene> tabletop(const Scene& desk, int blocks, int bowls, Random& random, bool distinct = true) {
  TabletopRequest request;
  request.blocks = blocks;
  request.bowls = bowls;
  request.distinctColours = distinct;
  return generateTabletop(desk, request, random);
}

FamilyInstance instance(const std::string& family, std::string instruction, Scene scene, Check check) {
  return {family, std::move(instruction), std::move(scene), std::move(check), {}};
}

std::optional<FamilyInstance> pickPlace(const Scene& desk, Random& random) {
  auto scene = tabletop(desk, drawCount(2, 4, random), drawCount(1, 2, random), random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const auto bowls = objectsOfKind(*scene, "bowl");
  const std::string object = drawOne(blocks, random);
  const bool ontoBlock = random.uniform(0.0, 1.0) < 0.5;
  std::vector<std::string> others;
  for (const std::string& block : blocks) if (block != object) others.push_back(block);
  const std::string target = ontoBlock ? drawOne(others, random) : drawOne(bowls, random);
  const R relation = ontoBlock ? R::kOn : R::kIn;
  const std::vector<std::string> templates = {"pick up the %o and place it on the %t", "put the %o on the %t", "place the %o %p the %t"};
  std::string text = drawOne(templates, random);
  const auto replace = [&](const std::string& key, const std::string& value) {
    if (const auto at = text.find(key); at != std::string::npos) text.replace(at, key.size(), value);
  };
  replace("%o", spoken(object));
  replace("%t", spoken(target));
  replace("%p", ontoBlock ? "on top of" : "in");
  FamilyInstance result = instance("cap_pick_place", text, *scene, allOf({relationGoal(object, relation, target)}));
  addPickPlace(result.plan, object, relation, target);
  return result;
}

std::optional<FamilyInstance> stackAll(const Scene& desk, Random& random) {
  auto scene = tabletop(desk, drawCount(2, 4, random), drawCount(0, 1, random), random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const std::vector<std::string> wordings = {"stack all the blocks", "stack the blocks on top of each other",
                                             "make a tower of all the blocks", "put all the blocks on top of each other"};
  FamilyInstance result = instance("cap_stack_all", drawOne(wordings, random), *scene, tower(blocks));
  for (std::size_t i = 1; i < blocks.size(); ++i) addPickPlace(result.plan, blocks[i], R::kOn, blocks[i - 1]);
  return result;
}

std::optional<FamilyInstance> blocksToRegion(const Scene& desk, Random& random) {
  auto scene = tabletop(desk, drawCount(2, 3, random), drawCount(0, 1, random), random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const RegionWords& where = drawOne(cornersAndSides(), random);
  if (!bowlsClearOf(*scene, where.region)) return std::nullopt;
  if (blocksFitting(*scene, where.region, 0.04) < static_cast<int>(blocks.size())) return std::nullopt;  // more than the region holds
  const std::vector<std::string> wordings = {"put all the blocks in the ", "move all the blocks to the ", "put all the blocks on the "};
  std::vector<Goal> goals;
  Plan plan;
  for (const std::string& block : blocks) {
    goals.push_back(relationGoal(block, R::kOn, "desk", where.region));
    addPickPlace(plan, block, R::kOn, "desk", where.region);
  }
  FamilyInstance result = instance("cap_blocks_to_region", drawOne(wordings, random) + where.words, *scene, allOf(goals));
  result.plan = plan;
  return result;
}

std::optional<FamilyInstance> blocksInBowl(const Scene& desk, Random& random) {
  auto scene = tabletop(desk, drawCount(2, 3, random), drawCount(1, 2, random), random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const std::string bowl = drawOne(objectsOfKind(*scene, "bowl"), random);
  if (static_cast<int>(blocks.size()) > blocksHeld(*scene, bowl, 0.04)) return std::nullopt;  // more than the bowl holds
  const std::vector<std::string> wordings = {"put the blocks in the ", "put all the blocks in the ", "place every block in the "};
  std::vector<Goal> goals;
  Plan plan;
  for (const std::string& block : blocks) {
    goals.push_back(relationGoal(block, R::kIn, bowl));
    addPickPlace(plan, block, R::kIn, bowl);
  }
  FamilyInstance result = instance("cap_blocks_in_bowl", drawOne(wordings, random) + spoken(bowl), *scene, allOf(goals));
  result.plan = plan;
  return result;
}

/// Blocks and bowls of the same colours, in another order.
std::optional<Scene> pairedColours(const Scene& desk, int pairs, Random& random) {
  for (int attempt = 0; attempt < 50; ++attempt) {
    auto scene = tabletop(desk, pairs, pairs, random);
    if (!scene) return std::nullopt;
    std::vector<std::string> blockColours, bowlColours;
    for (const std::string& block : objectsOfKind(*scene, "block")) blockColours.push_back(colourOf(block));
    for (const std::string& bowl : objectsOfKind(*scene, "bowl")) bowlColours.push_back(colourOf(bowl));
    std::sort(blockColours.begin(), blockColours.end());
    std::sort(bowlColours.begin(), bowlColours.end());
    if (blockColours == bowlColours) return scene;
  }
  return std::nullopt;
}

std::optional<FamilyInstance> matchingBowls(const Scene& desk, Random& random) {
  auto scene = pairedColours(desk, drawCount(2, 3, random), random);
  if (!scene) return std::nullopt;
  const std::vector<std::string> wordings = {"put the blocks in the bowls with matching colors", "put each block in the bowl of the same color",
                                             "sort the blocks into the bowls by color"};
  std::vector<Goal> goals;
  Plan plan;
  for (const std::string& block : objectsOfKind(*scene, "block")) {
    const std::string bowl = colourOf(block) + "_bowl";
    goals.push_back(relationGoal(block, R::kIn, bowl));
    addPickPlace(plan, block, R::kIn, bowl);
  }
  FamilyInstance result = instance("cap_matching_bowls", drawOne(wordings, random), *scene, allOf(goals));
  result.plan = plan;
  return result;
}

std::optional<FamilyInstance> mismatchedBowls(const Scene& desk, Random& random) {
  auto scene = pairedColours(desk, drawCount(2, 3, random), random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const auto bowls = objectsOfKind(*scene, "bowl");
  FamilyInstance result = instance("cap_mismatched_bowls", "put the blocks in the bowls with mismatched colors", *scene,
                                   mismatchedContainers(blocks, bowls));
  for (std::size_t i = 0; i < blocks.size(); ++i) {  // each into the bowl of the next block's colour
    addPickPlace(result.plan, blocks[i], R::kIn, colourOf(blocks[(i + 1) % blocks.size()]) + "_bowl");
  }
  return result;
}

std::optional<FamilyInstance> differentCornersFamily(const Scene& desk, Random& random) {
  auto scene = tabletop(desk, drawCount(2, 4, random), 0, random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const std::vector<std::string> wordings = {"put all the blocks in different corners", "put the blocks in separate corners",
                                             "put one block in each corner"};
  const std::string text = blocks.size() == 4 ? drawOne(wordings, random) : wordings[static_cast<std::size_t>(drawCount(0, 1, random))];
  FamilyInstance result = instance("cap_different_corners", text, *scene, differentCorners(blocks));
  for (std::size_t i = 0; i < blocks.size(); ++i) addPickPlace(result.plan, blocks[i], R::kOn, "desk", corners()[i].region);
  return result;
}

std::optional<FamilyInstance> stackOnRegion(const Scene& desk, Random& random) {
  auto scene = tabletop(desk, drawCount(2, 3, random), 0, random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const RegionWords& where = drawOne(cornersAndSides(), random);
  if (!bowlsClearOf(*scene, where.region)) return std::nullopt;
  FamilyInstance result = instance("cap_stack_on_region", std::string("stack all the blocks on the ") + where.words, *scene,
                                   tower(blocks, where.region));
  addPickPlace(result.plan, blocks[0], R::kOn, "desk", where.region);
  for (std::size_t i = 1; i < blocks.size(); ++i) addPickPlace(result.plan, blocks[i], R::kOn, blocks[i - 1]);
  return result;
}

std::optional<FamilyInstance> cornerClosestToBowl(const Scene& desk, Random& random) {
  auto scene = tabletop(desk, drawCount(1, 3, random), 1, random);
  if (!scene) return std::nullopt;
  const std::string block = drawOne(objectsOfKind(*scene, "block"), random);
  const std::string bowl = objectsOfKind(*scene, "bowl").front();
  const AlignedBox3 reach = deskReach(*scene);
  const Vector3 from = centreInBase(*scene, bowl);
  double best = 1e9, second = 1e9;
  SurfaceRegion chosen;
  for (const RegionWords& corner : corners()) {
    const Vector3 point(corner.region.depth > 0 ? reach.max().x() : reach.min().x(),
                        corner.region.side > 0 ? reach.max().y() : reach.min().y(), 0.0);
    const double distance = (point - from).head<2>().norm();
    if (distance < best) second = best, best = distance, chosen = corner.region;
    else second = std::min(second, distance);
  }
  if (second - best < 0.03) return std::nullopt;  // no clear closest corner
  if (!bowlsClearOf(*scene, chosen)) return std::nullopt;  // the bowl stands in it
  FamilyInstance result = instance("cap_corner_closest_to_bowl", "put the " + spoken(block) + " in the corner closest to the " + spoken(bowl),
                                   *scene, allOf({relationGoal(block, R::kOn, "desk", chosen)}));
  addPickPlace(result.plan, block, R::kOn, "desk", chosen);
  return result;
}

std::optional<FamilyInstance> blockNearBowl(const Scene& desk, Random& random) {
  auto scene = tabletop(desk, 3, 1, random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const std::string bowl = objectsOfKind(*scene, "bowl").front();
  const bool closest = random.uniform(0.0, 1.0) < 0.5;
  std::vector<std::pair<double, std::string>> byDistance;
  for (const std::string& block : blocks) byDistance.emplace_back((centreInBase(*scene, block) - centreInBase(*scene, bowl)).head<2>().norm(), block);
  std::sort(byDistance.begin(), byDistance.end());
  if (!closest) std::reverse(byDistance.begin(), byDistance.end());
  if (std::abs(byDistance[0].first - byDistance[1].first) < 0.03) return std::nullopt;
  const RegionWords& where = drawOne(cornersAndSides(), random);
  if (!bowlsClearOf(*scene, where.region)) return std::nullopt;
  const std::string block = byDistance[0].second;
  const std::string text = std::string("pick up the block ") + (closest ? "closest to" : "farthest from") + " the " + spoken(bowl) +
                           " and place it on the " + where.words;
  FamilyInstance result = instance("cap_block_near_bowl", text, *scene, allOf({relationGoal(block, R::kOn, "desk", where.region)}));
  addPickPlace(result.plan, block, R::kOn, "desk", where.region);
  return result;
}

/// "left" (+y), "right", "top" (+x, far), "bottom": the base-frame axis and sign.
struct Direction {
  const char* word;
  int axis;
  double sign;
  R relation;
};
const std::vector<Direction>& directions() {
  static const std::vector<Direction> all{{"left", 1, 1.0, R::kLeftOf}, {"right", 1, -1.0, R::kRightOf},
                                          {"top", 0, 1.0, R::kInFrontOf}, {"bottom", 0, -1.0, R::kBehind}};
  return all;
}

std::optional<FamilyInstance> nthBlock(const Scene& desk, Random& random) {
  auto scene = tabletop(desk, 3, 0, random);
  if (!scene) return std::nullopt;
  const Direction& from = drawOne(directions(), random);
  std::vector<std::pair<double, std::string>> order;
  for (const std::string& block : objectsOfKind(*scene, "block")) order.emplace_back(-from.sign * centreInBase(*scene, block)[from.axis], block);
  std::sort(order.begin(), order.end());
  for (std::size_t i = 1; i < order.size(); ++i) {
    if (order[i].first - order[i - 1].first < 0.04) return std::nullopt;  // no clear order
  }
  const std::size_t n = static_cast<std::size_t>(drawCount(0, 2, random));
  const char* ordinals[] = {"first", "second", "third"};
  const RegionWords& where = drawOne(cornersAndSides(), random);
  if (!bowlsClearOf(*scene, where.region)) return std::nullopt;
  const std::string block = order[n].second;
  const std::string text = std::string("pick up the ") + ordinals[n] + " block from the " + from.word + " and place it on the " + where.words;
  FamilyInstance result = instance("cap_nth_block", text, *scene, allOf({relationGoal(block, R::kOn, "desk", where.region)}));
  addPickPlace(result.plan, block, R::kOn, "desk", where.region);
  return result;
}

std::optional<FamilyInstance> blockToSideOfBowl(const Scene& desk, Random& random) {
  auto scene = tabletop(desk, 3, 1, random);
  if (!scene) return std::nullopt;
  const std::string bowl = objectsOfKind(*scene, "bowl").front();
  const Direction& side = drawOne(directions(), random);
  // The one block that is on that side of the bowl (its centre 2 cm or more that way), others not.
  std::vector<std::string> onSide;
  for (const std::string& block : objectsOfKind(*scene, "block")) {
    const double along = side.sign * (centreInBase(*scene, block)[side.axis] - centreInBase(*scene, bowl)[side.axis]);
    if (along > 0.02) onSide.push_back(block);
    else if (along > -0.02) return std::nullopt;  // too close to call
  }
  if (onSide.size() != 1) return std::nullopt;
  const RegionWords& where = drawOne(cornersAndSides(), random);
  if (!bowlsClearOf(*scene, where.region)) return std::nullopt;
  const std::string text = std::string("pick up the block to the ") + side.word + " of the " + spoken(bowl) + " and place it on the " + where.words;
  FamilyInstance result = instance("cap_block_to_side_of_bowl", text, *scene, allOf({relationGoal(onSide.front(), R::kOn, "desk", where.region)}));
  addPickPlace(result.plan, onSide.front(), R::kOn, "desk", where.region);
  return result;
}

std::optional<FamilyInstance> blockBesideBowl(const Scene& desk, Random& random) {
  auto scene = tabletop(desk, drawCount(1, 3, random), 1, random);
  if (!scene) return std::nullopt;
  const std::string block = drawOne(objectsOfKind(*scene, "block"), random);
  const std::string bowl = objectsOfKind(*scene, "bowl").front();
  const Direction& side = drawOne(directions(), random);
  const bool little = random.uniform(0.0, 1.0) < 0.5;
  const std::string text = "place the " + spoken(block) + (little ? " a little" : " a lot") + " to the " + side.word + " of the " + spoken(bowl);
  // A little: within 10 cm of the bowl; a lot: 15 cm or more from it.
  FamilyInstance result = instance("cap_block_beside_bowl", text, *scene,
                                   little ? besideWithin(block, side.relation, bowl, 0.0, 0.10) : besideWithin(block, side.relation, bowl, 0.15, 1.0));
  Vector3 at = robotBaseFrame(*scene, "").inverse() * scene->object(bowl).pose.translation();
  const double half = scene->object(bowl).dimensions()[side.axis] / 2.0 + scene->object(block).dimensions()[side.axis] / 2.0;
  at[side.axis] += side.sign * (half + (little ? 0.04 : 0.18));
  const AlignedBox3 reachable = deskReach(*scene);
  if (!reachable.contains(Vector3(at.x(), at.y(), reachable.min().z()))) return std::nullopt;
  // Another object where the block is to go leaves no room there: no test of understanding.
  if (!footprintClear(*scene, at, scene->object(block).dimensions(), 0.03, {block, bowl})) return std::nullopt;
  at.head<2>() -= (centreInBase(*scene, block) - robotBaseFrame(*scene, "").inverse() * scene->object(block).pose.translation()).head<2>();
  addPickPlaceAt(result.plan, block, at);
  return result;
}

std::optional<FamilyInstance> line(const Scene& desk, Random& random) {
  auto scene = tabletop(desk, drawCount(3, 4, random), 0, random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const bool horizontal = random.uniform(0.0, 1.0) < 0.5;
  const std::string text = std::string("put all the blocks in a ") + (horizontal ? "horizontal" : "vertical") + " line";
  // Horizontal: left to right, across the desk (base y); vertical: away from the robot (base x).
  FamilyInstance result = instance("cap_line", text, *scene, inLine(blocks, horizontal ? 3.14159265358979323846 / 2.0 : 0.0));
  // The reference line: the first of a few across the reachable desk whose spots are free.
  const AlignedBox3 reachable = deskReach(*scene);
  const double spacing = 0.08;
  for (double fraction : {0.5, 0.3, 0.7, 0.2, 0.8}) {
    std::vector<Vector3> spots;
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      const double offset = (static_cast<double>(i) - static_cast<double>(blocks.size() - 1) / 2.0) * spacing;
      const Vector3 middle(horizontal ? reachable.min().x() + fraction * reachable.sizes().x() : reachable.center().x(),
                           horizontal ? reachable.center().y() : reachable.min().y() + fraction * reachable.sizes().y(), reachable.max().z());
      spots.push_back(middle + (horizontal ? Vector3(0.0, offset, 0.0) : Vector3(offset, 0.0, 0.0)));
    }
    const bool free = std::all_of(spots.begin(), spots.end(), [&](const Vector3& spot) {
      return std::all_of(blocks.begin(), blocks.end(), [&](const std::string& block) {
        return (centreInBase(*scene, block) - spot).head<2>().norm() > 0.08;
      });
    });
    if (!free) continue;
    for (std::size_t i = 0; i < blocks.size(); ++i) addPickPlaceAt(result.plan, blocks[i], spots[i]);
    return result;
  }
  return std::nullopt;
}

std::optional<FamilyInstance> ravensColourBlocksInBowl(const Scene& desk, Random& random) {
  TabletopRequest request;
  request.blocks = drawCount(3, 5, random);
  request.bowls = 2;
  request.distinctColours = false;
  auto scene = generateTabletop(desk, request, random);
  if (!scene) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const std::string colour = colourOf(drawOne(blocks, random));
  const std::string bowl = drawOne(objectsOfKind(*scene, "bowl"), random);
  std::vector<std::string> moved;
  Plan plan;
  for (const std::string& block : blocks) {
    if (colourOf(block) != colour) continue;
    moved.push_back(block);
    addPickPlace(plan, block, R::kIn, bowl);
  }
  if (static_cast<int>(moved.size()) > blocksHeld(*scene, bowl, 0.04)) return std::nullopt;  // more than the bowl holds
  // "a green bowl": any bowl of that colour.
  std::vector<std::string> ofColour;
  for (const std::string& other : objectsOfKind(*scene, "bowl")) {
    if (colourOf(other) == colourOf(bowl)) ofColour.push_back(other);
  }
  const std::string text = "put the " + colour + (moved.size() > 1 ? " blocks in a " : " block in a ") + spoken(bowl);
  FamilyInstance result = instance("ravens_colour_blocks_in_bowl", text, *scene, inAnyOf(moved, ofColour));
  result.plan = plan;
  return result;
}

/// CLIPort's spatial references: three blocks of one colour, "the left / middle / right red block".
std::optional<FamilyInstance> ravensSpatialBlock(const Scene& desk, Random& random) {
  for (int attempt = 0; attempt < 50; ++attempt) {
    TabletopRequest request;
    request.blocks = 3;
    request.bowls = 1;
    request.oneBlockColour = true;
    const auto scene = generateTabletop(desk, request, random);
    if (!scene) return std::nullopt;
    const auto named = objectsOfKind(*scene, "block");
    std::vector<std::pair<double, std::string>> byLeft;
    for (const std::string& block : named) byLeft.emplace_back(centreInBase(*scene, block).y(), block);
    std::sort(byLeft.begin(), byLeft.end());
    if (byLeft[1].first - byLeft[0].first < 0.04 || byLeft[2].first - byLeft[1].first < 0.04) continue;
    const int which = drawCount(0, 2, random);  // right, middle, left
    const char* words[] = {"right", "middle", "left"};
    const std::string block = byLeft[static_cast<std::size_t>(which)].second;
    const std::string bowl = objectsOfKind(*scene, "bowl").front();
    FamilyInstance result = instance("ravens_spatial_block", std::string("put the ") + words[which] + " " + colourOf(block) + " block in the " +
                                                                 spoken(bowl), *scene, allOf({relationGoal(block, R::kIn, bowl)}));
    addPickPlace(result.plan, block, R::kIn, bowl);
    return result;
  }
  return std::nullopt;
}

}  // namespace

const std::vector<InstructionFamily>& instructionFamilies() {
  static const std::vector<InstructionFamily> families{
      {"cap_pick_place", "CaP", notYetDone(pickPlace)},
      {"cap_stack_all", "CaP", notYetDone(stackAll)},
      {"cap_blocks_to_region", "CaP", notYetDone(blocksToRegion)},
      {"cap_blocks_in_bowl", "CaP", notYetDone(blocksInBowl)},
      {"cap_matching_bowls", "CaP", notYetDone(matchingBowls)},
      {"cap_block_near_bowl", "CaP", notYetDone(blockNearBowl)},
      {"cap_block_to_side_of_bowl", "CaP", notYetDone(blockToSideOfBowl)},
      {"cap_nth_block", "CaP", notYetDone(nthBlock)},
      {"cap_different_corners", "CaP", notYetDone(differentCornersFamily)},
      {"cap_mismatched_bowls", "CaP", notYetDone(mismatchedBowls)},
      {"cap_stack_on_region", "CaP", notYetDone(stackOnRegion)},
      {"cap_block_beside_bowl", "CaP", notYetDone(blockBesideBowl)},
      {"cap_corner_closest_to_bowl", "CaP", notYetDone(cornerClosestToBowl)},
      {"cap_line", "CaP", notYetDone(line)},
      {"ravens_colour_blocks_in_bowl", "Ravens", notYetDone(ravensColourBlocksInBowl)},
      {"ravens_spatial_block", "Ravens", notYetDone(ravensSpatialBlock)},
  };
  static const std::vector<InstructionFamily> all = [] {
    std::vector<InstructionFamily> list = families;
    for (InstructionFamily& family : peerFamilies()) list.push_back(std::move(family));
    for (InstructionFamily& family : arrangementFamilies()) list.push_back(std::move(family));
    return list;
  }();
  return all;
}

}  // namespace lang2manip
