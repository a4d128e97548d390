// Families of two more public benchmarks of language-conditioned manipulation, written from their
// papers and kept to what pick and place can do on a tabletop of blocks and bowls:
// - VIMA-Bench (Jiang et al. 2023): "same texture" (all objects of a container's colour into it),
//   "follow order" (a stack in a given order), "manipulate old neighbour" (a block into a bowl,
//   then the one that stood beside it before); VIMA's prompts show objects as images, here they are
//   named by colour and kind. "Pick in order then restore" ends where it starts, which a check of
//   the final world cannot tell from doing nothing: left out.
// - LIBERO (Liu et al. 2023): LIBERO-Spatial's objects of one kind told apart by where they stand
//   ("the block next to the bowl", "the block between the two bowls") and LIBERO-10's two-target
//   instructions ("put the A in the left bowl and the B in the right bowl").
// Templates, wordings and checks are this project's own.

#include <algorithm>
#include <cmath>

#include "lang2manip/cli/family_support.hpp"
#include "lang2manip/cli/tabletop_scenes.hpp"

namespace lang2manip::families {
namespace {

using R = SpatialRelation;

std::optional<Scene> drawTabletop(const Scene& desk, TabletopRequest request, Random& random) { return generateTabletop(desk, request, random); }

/// The x-y gap between two objects' boxes (base frame).
double gapBetween(const Scene& scene, const std::string& a, const std::string& b) {
  const Pose toBase = robotBaseFrame(scene, "").inverse();
  const AlignedBox3 boxA = transformedBox(scene.object(a).worldBounds(), toBase), boxB = transformedBox(scene.object(b).worldBounds(), toBase);
  const Eigen::Vector2d apart = (boxA.min().head<2>() - boxB.max().head<2>()).cwiseMax(boxB.min().head<2>() - boxA.max().head<2>()).cwiseMax(0.0);
  return apart.norm();
}

/// VIMA's "same texture": every block of the bowl's colour goes into it; blocks of other colours too.
std::optional<FamilyInstance> sameColour(const Scene& desk, Random& random) {
  TabletopRequest request;
  request.blocks = drawCount(3, 5, random);
  request.bowls = drawCount(1, 2, random);
  request.distinctColours = false;
  auto scene = drawTabletop(desk, request, random);
  if (!scene) return std::nullopt;
  const std::string bowl = drawOne(objectsOfKind(*scene, "bowl"), random);
  for (const std::string& other : objectsOfKind(*scene, "bowl")) {
    if (other != bowl && colourOf(other) == colourOf(bowl)) return std::nullopt;  // "the green bowl" would not say which
  }
  std::vector<std::string> matching;
  for (const std::string& block : objectsOfKind(*scene, "block")) {
    if (colourOf(block) == colourOf(bowl)) matching.push_back(block);
  }
  if (matching.empty() || static_cast<int>(matching.size()) > blocksHeld(*scene, bowl, 0.04)) return std::nullopt;
  const std::vector<std::string> wordings{"put all objects with the same colour as the " + spoken(bowl) + " into it",
                                          "put every object that has the same colour as the " + spoken(bowl) + " in it",
                                          "place all the objects of the same colour as the " + spoken(bowl) + " into the " + spoken(bowl)};
  std::vector<Goal> goals;
  for (const std::string& block : matching) goals.push_back(relationGoal(block, R::kIn, bowl));
  FamilyInstance result{"vima_same_colour", drawOne(wordings, random), *scene, allOf(goals), {}};
  for (const std::string& block : matching) addPickPlace(result.plan, block, R::kIn, bowl);
  return result;
}

/// VIMA's "follow order": the blocks stacked in the order named, bottom first.
std::optional<FamilyInstance> followOrder(const Scene& desk, Random& random) {
  TabletopRequest request;
  request.blocks = 3;
  request.bowls = drawCount(0, 1, random);
  auto scene = drawTabletop(desk, request, random);
  if (!scene) return std::nullopt;
  std::vector<std::string> order = objectsOfKind(*scene, "block");
  for (std::size_t i = order.size() - 1; i > 0; --i) std::swap(order[i], order[static_cast<std::size_t>(drawCount(0, static_cast<int>(i), random))]);
  const std::string a = colourOf(order[0]), b = colourOf(order[1]), c = colourOf(order[2]);
  const std::vector<std::string> wordings{"stack the blocks in this order from the bottom: " + a + ", " + b + ", " + c,
                                          "build a tower with the " + a + " block at the bottom, then the " + b + " block, then the " + c + " block on top",
                                          "stack the " + b + " block on the " + a + " block and then the " + c + " block on the " + b + " block"};
  FamilyInstance result{"vima_follow_order", drawOne(wordings, random), *scene,
                        allOf({relationGoal(order[0], R::kOn, "desk"), relationGoal(order[1], R::kOn, order[0]), relationGoal(order[2], R::kOn, order[1])}),
                        {}};
  addPickPlace(result.plan, order[1], R::kOn, order[0]);
  addPickPlace(result.plan, order[2], R::kOn, order[1]);
  return result;
}

/// VIMA's "manipulate old neighbour": a block into a bowl, then the block that stood on one side
/// of it before (the one block 2 cm or more that way, none within 2 cm of its line) into the same bowl.
std::optional<FamilyInstance> oldNeighbour(const Scene& desk, Random& random) {
  TabletopRequest request;
  request.blocks = 3;
  request.bowls = 1;
  request.blocksPerBowl = 2;
  request.roundBowlShare = 0.0;  // the square a round bowl's floor holds takes two blocks only at 22 cm across
  auto scene = drawTabletop(desk, request, random);
  if (!scene) return std::nullopt;
  const std::string bowl = objectsOfKind(*scene, "bowl").front();
  if (blocksHeld(*scene, bowl, 0.04) < 2) return std::nullopt;
  const auto blocks = objectsOfKind(*scene, "block");
  const std::string first = drawOne(blocks, random);
  const bool left = random.uniform(0.0, 1.0) < 0.5;
  std::vector<std::string> onSide;
  for (const std::string& block : blocks) {
    if (block == first) continue;
    const double along = (left ? 1.0 : -1.0) * (centreInBase(*scene, block).y() - centreInBase(*scene, first).y());
    if (along > 0.02) onSide.push_back(block);
    else if (along > -0.02) return std::nullopt;  // too close to call
  }
  if (onSide.size() != 1) return std::nullopt;
  const std::string side = left ? "left" : "right";
  const std::vector<std::string> wordings{
      "first put the " + spoken(first) + " into the " + spoken(bowl) + ", then put the object that was previously to its " + side + " into the same bowl",
      "put the " + spoken(first) + " in the " + spoken(bowl) + " and then put the block that was to its " + side + " before in the same bowl"};
  FamilyInstance result{"vima_old_neighbour", drawOne(wordings, random), *scene,
                        allOf({relationGoal(first, R::kIn, bowl), relationGoal(onSide.front(), R::kIn, bowl)}), {}};
  addPickPlace(result.plan, first, R::kIn, bowl);
  addPickPlace(result.plan, onSide.front(), R::kIn, bowl);
  return result;
}

/// LIBERO-Spatial: blocks of one colour told apart by where they stand, next to a bowl or between
/// the two bowls, the one meant clearly so (the others 4 cm farther from the bowl, or from the
/// segment between the bowls' centres).
std::optional<FamilyInstance> spatial(const Scene& desk, Random& random) {
  for (int attempt = 0; attempt < 50; ++attempt) {
    TabletopRequest request;
    request.blocks = drawCount(2, 3, random);
    request.bowls = 2;
    request.oneBlockColour = true;
    const auto scene = drawTabletop(desk, request, random);
    if (!scene) return std::nullopt;
    const auto blocks = objectsOfKind(*scene, "block");
    const auto bowls = objectsOfKind(*scene, "bowl");
    const bool between = random.uniform(0.0, 1.0) < 0.5;
    const std::string& reference = bowls[static_cast<std::size_t>(drawCount(0, 1, random))];
    std::vector<std::pair<double, std::string>> scored;  // how far each block is from what names it
    const Eigen::Vector2d a = centreInBase(*scene, bowls[0]).head<2>(), b = centreInBase(*scene, bowls[1]).head<2>();
    for (const std::string& block : blocks) {
      const Eigen::Vector2d p = centreInBase(*scene, block).head<2>();
      const double t = (p - a).dot(b - a) / (b - a).squaredNorm();
      const double offSegment = t > 0.2 && t < 0.8 ? (p - (a + t * (b - a))).norm() : 1e9;
      scored.emplace_back(between ? offSegment : gapBetween(*scene, block, reference), block);
    }
    std::sort(scored.begin(), scored.end());
    const bool clear = scored[0].first <= (between ? 0.03 : 0.06) && scored[1].first >= scored[0].first + 0.04 &&
                       (between || scored[1].first > 0.12);
    if (!clear) continue;
    const std::string& block = scored[0].second;
    const std::string target = drawOne(bowls, random);
    const std::string where = between ? "between the " + spoken(bowls[0]) + " and the " + spoken(bowls[1]) : "next to the " + spoken(reference);
    const std::string text = "pick up the " + colourOf(block) + " block " + where + " and place it in the " + spoken(target);
    FamilyInstance result{"libero_spatial", text, *scene, allOf({relationGoal(block, R::kIn, target)}), {}};
    addPickPlace(result.plan, block, R::kIn, target);
    return result;
  }
  return std::nullopt;
}

/// LIBERO-10's two targets: "put the A in the left bowl and the B in the right bowl" (left and
/// right as the robot sees them, the bowls 8 cm or more apart sideways).
std::optional<FamilyInstance> twoTargets(const Scene& desk, Random& random) {
  TabletopRequest request;
  request.blocks = drawCount(2, 3, random);
  request.bowls = 2;
  auto scene = drawTabletop(desk, request, random);
  if (!scene) return std::nullopt;
  auto bowls = objectsOfKind(*scene, "bowl");
  if (std::abs(centreInBase(*scene, bowls[0]).y() - centreInBase(*scene, bowls[1]).y()) < 0.08) return std::nullopt;
  if (centreInBase(*scene, bowls[0]).y() < centreInBase(*scene, bowls[1]).y()) std::swap(bowls[0], bowls[1]);  // left (+y) first
  const auto blocks = objectsOfKind(*scene, "block");
  const std::string first = blocks[0], second = blocks[1];
  const std::vector<std::string> wordings{"put the " + spoken(first) + " in the left bowl and put the " + spoken(second) + " in the right bowl",
                                          "put the " + spoken(first) + " in the bowl on the left and the " + spoken(second) + " in the bowl on the right"};
  FamilyInstance result{"libero_two_targets", drawOne(wordings, random), *scene,
                        allOf({relationGoal(first, R::kIn, bowls[0]), relationGoal(second, R::kIn, bowls[1])}), {}};
  addPickPlace(result.plan, first, R::kIn, bowls[0]);
  addPickPlace(result.plan, second, R::kIn, bowls[1]);
  return result;
}

}  // namespace

std::vector<InstructionFamily> peerFamilies() {
  return {{"vima_same_colour", "VIMA", notYetDone(sameColour)},
          {"vima_follow_order", "VIMA", notYetDone(followOrder)},
          {"vima_old_neighbour", "VIMA", notYetDone(oldNeighbour)},
          {"libero_spatial", "LIBERO", notYetDone(spatial)},
          {"libero_two_targets", "LIBERO", notYetDone(twoTargets)}};
}

}  // namespace lang2manip::families
