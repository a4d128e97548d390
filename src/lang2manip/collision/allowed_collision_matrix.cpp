#include "lang2manip/collision/allowed_collision_matrix.hpp"

#include <cmath>
#include <numeric>
#include <set>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/core/random.hpp"

namespace lang2manip {
namespace {

int findRoot(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

/// As linksAdjacent() for every pair, in time linear in the number of pairs allowed.
void allowAdjacent(const RobotModel& model, AllowedCollisionMatrix& matrix) {
  const std::vector<int> groups = rigidLinkGroups(model);
  std::vector<std::vector<int>> members(groups.size());
  for (std::size_t link = 0; link < groups.size(); ++link) members[static_cast<std::size_t>(groups[link])].push_back(static_cast<int>(link));
  const auto allowBetween = [&](const std::vector<int>& first, const std::vector<int>& second) {
    for (int a : first) {
      for (int b : second) {
        if (a != b) matrix.allow(a, b, AllowedReason::kAdjacent);
      }
    }
  };
  for (const std::vector<int>& group : members) allowBetween(group, group);
  for (std::size_t j = 0; j < model.joints().size(); ++j) {
    const int parent = groups[static_cast<std::size_t>(model.parentLinkOf(static_cast<int>(j)))];
    const int child = groups[static_cast<std::size_t>(model.childLinkOf(static_cast<int>(j)))];
    if (parent != child) allowBetween(members[static_cast<std::size_t>(parent)], members[static_cast<std::size_t>(child)]);
  }
}

/// enabled[a * links + b] (both orders) for the SRDF's <enable_collisions> pairs.
std::vector<char> enabledLinkPairs(const RobotModel& model) {
  const std::size_t links = model.links().size();
  std::vector<char> enabled(links * links, 0);
  for (const auto& [first, second] : model.semantics().enabledCollisions) {
    const std::optional<int> a = model.findLink(first);
    const std::optional<int> b = model.findLink(second);
    if (!a || !b) continue;
    enabled[static_cast<std::size_t>(*a) * links + static_cast<std::size_t>(*b)] = 1;
    enabled[static_cast<std::size_t>(*b) * links + static_cast<std::size_t>(*a)] = 1;
  }
  return enabled;
}

void allowSrdf(const RobotModel& model, AllowedCollisionMatrix& matrix) {
  for (const DisabledCollision& pair : model.semantics().disabledCollisions) {
    const std::optional<int> a = model.findLink(pair.link1);
    const std::optional<int> b = model.findLink(pair.link2);
    if (!a || !b) {
      throw InputError(SourceLocation{model.semantics().source, 0},
                       "disable_collisions names an unknown link '" + (a ? pair.link2 : pair.link1) +
                           "' of robot '" + model.name() + "'");
    }
    if (*a != *b) matrix.allow(*a, *b, AllowedReason::kSrdf);
  }
  const std::vector<char> quiet = linksWithDefaultCollisionsOff(model);
  const std::vector<char> enabled = enabledLinkPairs(model);
  const int links = matrix.linkCount();
  for (int a = 0; a < links; ++a) {
    for (int b = a + 1; b < links; ++b) {
      const bool off = quiet[static_cast<std::size_t>(a)] != 0 || quiet[static_cast<std::size_t>(b)] != 0;
      if (off && enabled[static_cast<std::size_t>(a * links + b)] == 0) matrix.allow(a, b, AllowedReason::kSrdf);
    }
  }
}

/// For each link: whether its own joint is one a manipulator drives (arm, gripper, or a mimic of
/// one), and whether any joint above it is.
struct PlanningMotion {
  std::vector<char> driven;
  std::vector<char> moved;
};

PlanningMotion planningMotion(const RobotModel& model) {
  std::set<std::string> planned;
  for (const Manipulator& arm : model.semantics().manipulators) {
    planned.insert(arm.armJoints.begin(), arm.armJoints.end());
    planned.insert(arm.gripperJoints.begin(), arm.gripperJoints.end());
  }
  PlanningMotion motion{std::vector<char>(model.links().size(), 0), std::vector<char>(model.links().size(), 0)};
  for (std::size_t link = 1; link < model.links().size(); ++link) {  // parents come first
    const int joint = model.parentJoint(static_cast<int>(link));
    const int source = model.mimicSource(joint);
    const std::string& followed =
        source >= 0 ? model.joints()[static_cast<std::size_t>(model.variableJoints()[static_cast<std::size_t>(source)])].name : "";
    motion.driven[link] = planned.count(model.joints()[static_cast<std::size_t>(joint)].name) != 0 || planned.count(followed) != 0 ? 1 : 0;
    motion.moved[link] = motion.driven[link] != 0 || motion.moved[static_cast<std::size_t>(model.parentLinkOf(joint))] != 0 ? 1 : 0;
  }
  return motion;
}

/// Allows the pairs that collide in the default configuration (every joint at 0, or at the limit
/// nearest 0) between a part on a movable joint no manipulator drives (a torso's bellows, which
/// the real robot moves out of the way by itself) and a link no manipulator moves.
void allowDefault(const RobotModel& model, const LinkCollisionTest& test, AllowedCollisionMatrix& matrix) {
  const std::size_t links = static_cast<std::size_t>(matrix.linkCount());
  const PlanningMotion motion = planningMotion(model);
  const auto passive = [&](std::size_t link) {
    return link > 0 && motion.driven[link] == 0 &&
           model.joints()[static_cast<std::size_t>(model.parentJoint(static_cast<int>(link)))].type != JointType::kFixed;
  };
  std::vector<char> toTest(links * links, 0);
  bool any = false;
  for (std::size_t a = 0; a < links; ++a) {
    for (std::size_t b = 0; b < links; ++b) {
      const bool candidate = a != b && ((passive(a) && motion.moved[b] == 0) || (passive(b) && motion.moved[a] == 0)) &&
                             !matrix.isAllowed(static_cast<int>(a), static_cast<int>(b));
      toTest[a * links + b] = candidate ? 1 : 0;
      any |= candidate;
    }
  }
  if (!any) return;
  std::vector<char> inCollision(links * links, 0);
  const VectorX q = VectorX::Zero(model.lowerLimits().size()).cwiseMax(model.lowerLimits()).cwiseMin(model.upperLimits());
  test(q, toTest, inCollision);
  for (std::size_t a = 0; a < links; ++a) {
    for (std::size_t b = a + 1; b < links; ++b) {
      if (inCollision[a * links + b] != 0) matrix.allow(static_cast<int>(a), static_cast<int>(b), AllowedReason::kDefault);
    }
  }
}

void allowSampled(const RobotModel& model, const LinkCollisionTest& test,
                  const AllowedCollisionSettings& settings, AllowedCollisionMatrix& matrix) {
  if (settings.samples < 1) {
    throw InputError("allowed-collision matrix: samples must be at least 1, got " +
                     std::to_string(settings.samples));
  }
  const std::size_t links = static_cast<std::size_t>(matrix.linkCount());
  if (static_cast<double>(links * links) * settings.samples > kMaxSampledPairTests) {
    logMessage(LogLevel::kWarn, "allowed-collision matrix: " + std::to_string(links) + " links over " + std::to_string(settings.samples) +
                                    " samples is more work than the bound; no pair is disabled as never or always colliding "
                                    "(every pair but adjacent ones is checked; an SRDF can disable more)");
    return;
  }
  std::vector<int> hits(links * links, 0);
  std::vector<char> inCollision(links * links, 0);
  // A pair already allowed, or seen both colliding and free, cannot become never or always:
  // it is not tested again (most of the cost on mesh robots is in such pairs).
  std::vector<char> undecided(links * links, 0);
  for (std::size_t a = 0; a < links; ++a) {
    for (std::size_t b = 0; b < links; ++b) {
      undecided[a * links + b] = matrix.isAllowed(static_cast<int>(a), static_cast<int>(b)) ? 0 : 1;
    }
  }
  if (!(settings.alwaysFraction > 0.5 && settings.alwaysFraction <= 1.0)) {
    throw InputError("allowed-collision matrix: alwaysFraction must be in (0.5, 1], got " + numberText(settings.alwaysFraction));
  }
  // A pair may still be "always" while it has missed at most this many samples.
  const int allowedMisses = static_cast<int>(std::floor((1.0 - settings.alwaysFraction) * settings.samples + 1e-9));
  Random random(settings.seed);
  for (int s = 0; s < settings.samples; ++s) {
    const VectorX q = random.uniformVector(model.lowerLimits(), model.upperLimits());
    std::fill(inCollision.begin(), inCollision.end(), 0);
    test(q, undecided, inCollision);
    for (std::size_t i = 0; i < hits.size(); ++i) {
      if (undecided[i] == 0) continue;
      hits[i] += inCollision[i] != 0 ? 1 : 0;
      const bool mayBeNever = settings.disableNever && hits[i] == 0;
      const bool mayBeAlways = settings.disableAlways && s + 1 - hits[i] <= allowedMisses;
      undecided[i] = mayBeNever || mayBeAlways ? 1 : 0;
    }
  }
  for (std::size_t a = 0; a < links; ++a) {
    for (std::size_t b = a + 1; b < links; ++b) {
      const int count = hits[a * links + b];
      const int ia = static_cast<int>(a);
      const int ib = static_cast<int>(b);
      if (count == 0 && settings.disableNever) matrix.allow(ia, ib, AllowedReason::kNever);
      if (settings.samples - count <= allowedMisses && settings.disableAlways) matrix.allow(ia, ib, AllowedReason::kAlways);
    }
  }
}

}  // namespace

std::string allowedReasonName(AllowedReason reason) {
  switch (reason) {
    case AllowedReason::kNone: return "none";
    case AllowedReason::kSameLink: return "same link";
    case AllowedReason::kAdjacent: return "adjacent";
    case AllowedReason::kSrdf: return "srdf";
    case AllowedReason::kNever: return "never";
    case AllowedReason::kAlways: return "always";
    case AllowedReason::kDefault: return "default";
  }
  return "none";
}

AllowedCollisionMatrix::AllowedCollisionMatrix(int linkCount)
    : count_(linkCount),
      reasons_(static_cast<std::size_t>(linkCount) * static_cast<std::size_t>(linkCount),
               AllowedReason::kNone) {
  for (int i = 0; i < linkCount; ++i) reasons_[index(i, i)] = AllowedReason::kSameLink;
}

void AllowedCollisionMatrix::allow(int a, int b, AllowedReason reason) noexcept {
  if (reasons_[index(a, b)] != AllowedReason::kNone) return;
  reasons_[index(a, b)] = reason;
  reasons_[index(b, a)] = reason;
}

int AllowedCollisionMatrix::count(AllowedReason reason) const noexcept {
  int total = 0;
  for (int a = 0; a < count_; ++a) {
    for (int b = a + 1; b < count_; ++b) total += reasons_[index(a, b)] == reason ? 1 : 0;
  }
  return total;
}

std::vector<char> linksWithDefaultCollisionsOff(const RobotModel& model) {
  std::vector<char> off(model.links().size(), 0);
  for (const std::string& name : model.semantics().defaultCollisionsDisabled) {
    if (const std::optional<int> link = model.findLink(name)) off[static_cast<std::size_t>(*link)] = 1;
  }
  return off;
}

std::vector<int> rigidLinkGroups(const RobotModel& model) {
  std::vector<int> parent(model.links().size());
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t j = 0; j < model.joints().size(); ++j) {
    if (model.joints()[j].type != JointType::kFixed) continue;
    const int a = findRoot(parent, model.parentLinkOf(static_cast<int>(j)));
    const int b = findRoot(parent, model.childLinkOf(static_cast<int>(j)));
    parent[static_cast<std::size_t>(b)] = a;
  }
  std::vector<int> groups(parent.size());
  for (std::size_t i = 0; i < parent.size(); ++i) groups[i] = findRoot(parent, static_cast<int>(i));
  return groups;
}

bool linksAdjacent(const RobotModel& model, const std::vector<int>& rigidGroups, int a, int b) {
  const int ga = rigidGroups[static_cast<std::size_t>(a)];
  const int gb = rigidGroups[static_cast<std::size_t>(b)];
  if (ga == gb) return true;
  for (std::size_t j = 0; j < model.joints().size(); ++j) {
    const int parent = rigidGroups[static_cast<std::size_t>(model.parentLinkOf(static_cast<int>(j)))];
    const int child = rigidGroups[static_cast<std::size_t>(model.childLinkOf(static_cast<int>(j)))];
    if ((parent == ga && child == gb) || (parent == gb && child == ga)) return true;
  }
  return false;
}

AllowedCollisionMatrix computeAllowedCollisionMatrix(const RobotModel& model,
                                                     const LinkCollisionTest& test,
                                                     const AllowedCollisionSettings& settings) {
  AllowedCollisionMatrix matrix(static_cast<int>(model.links().size()));
  allowAdjacent(model, matrix);
  allowSrdf(model, matrix);
  if (settings.disableDefault) allowDefault(model, test, matrix);
  if (settings.disableNever || settings.disableAlways) allowSampled(model, test, settings, matrix);
  return matrix;
}

bool allowsNoMoreThan(const AllowedCollisionMatrix& stored, const AllowedCollisionMatrix& reference) {
  if (stored.linkCount() != reference.linkCount()) return false;
  for (int a = 0; a < stored.linkCount(); ++a) {
    for (int b = a + 1; b < stored.linkCount(); ++b) {
      if (stored.isAllowed(a, b) && !reference.isAllowed(a, b)) return false;
    }
  }
  return true;
}

AllowedCollisionSettings confirmationSettings(const AllowedCollisionSettings& settings) {
  AllowedCollisionSettings quick = settings;
  quick.samples = std::min(settings.samples, 64);
  quick.alwaysFraction = std::min(settings.alwaysFraction, 0.6);
  return quick;
}

}  // namespace lang2manip
