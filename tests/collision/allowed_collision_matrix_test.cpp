// The allowed-collision matrix: adjacency (through fixed joints), SRDF pairs, never/always pairs.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "collision_test_support.hpp"
#include "lang2manip/collision/allowed_collision_matrix.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/log.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

TEST(AllowedCollisionMatrix, StartsWithEveryPairCheckedButTheDiagonal) {
  AllowedCollisionMatrix matrix(3);
  EXPECT_TRUE(matrix.isAllowed(1, 1));
  EXPECT_FALSE(matrix.isAllowed(0, 2));
  matrix.allow(2, 0, AllowedReason::kSrdf);
  matrix.allow(0, 2, AllowedReason::kNever);
  EXPECT_TRUE(matrix.isAllowed(0, 2));
  EXPECT_EQ(matrix.reason(0, 2), AllowedReason::kSrdf);
  EXPECT_EQ(matrix.count(AllowedReason::kSrdf), 1);
  EXPECT_EQ(allowedReasonName(AllowedReason::kAlways), "always");
}

TEST(AllowedCollisionMatrix, AdjacencyFollowsFixedJoints) {
  const RobotModelPtr panda = builtinRobot("panda");
  const std::vector<int> groups = rigidLinkGroups(*panda);
  const auto link = [&](const char* name) { return panda->linkIndex(name); };
  EXPECT_EQ(groups[static_cast<std::size_t>(link("panda_link7"))], groups[static_cast<std::size_t>(link("panda_hand"))]);
  EXPECT_TRUE(linksAdjacent(*panda, groups, link("panda_link6"), link("panda_hand")));
  EXPECT_TRUE(linksAdjacent(*panda, groups, link("panda_link8"), link("panda_leftfinger")));
  EXPECT_FALSE(linksAdjacent(*panda, groups, link("panda_link5"), link("panda_link7")));
  EXPECT_FALSE(linksAdjacent(*panda, groups, link("panda_link0"), link("panda_link2")));
}

TEST(AllowedCollisionMatrix, AdjacentPairsAreExactlyTheLinksAdjacentPairs) {
  for (const char* name : {"panda", "yumi", "ur5"}) {
    SCOPED_TRACE(name);
    const RobotModelPtr robot = builtinRobot(name);
    AllowedCollisionSettings settings;
    settings.disableDefault = settings.disableNever = settings.disableAlways = false;
    const AllowedCollisionMatrix matrix = computeAllowedCollisionMatrix(*robot, nullptr, settings);
    const std::vector<int> groups = rigidLinkGroups(*robot);
    for (int a = 0; a < matrix.linkCount(); ++a) {
      for (int b = a + 1; b < matrix.linkCount(); ++b) {
        EXPECT_EQ(matrix.reason(a, b) == AllowedReason::kAdjacent, linksAdjacent(*robot, groups, a, b)) << a << " " << b;
      }
    }
  }
}

TEST(AllowedCollisionMatrix, SamplingBeyondTheWorkBoundIsSkippedWithAWarningAndDisablesNothing) {
  const RobotModelPtr panda = builtinRobot("panda");
  const auto links = static_cast<double>(panda->links().size());
  AllowedCollisionSettings settings;
  settings.disableDefault = false;
  settings.samples = static_cast<int>(kMaxSampledPairTests / (links * links)) + 1;
  int calls = 0;
  std::vector<std::string> warnings;
  setLogSink([&](LogLevel, std::string_view message) { warnings.emplace_back(message); });
  const AllowedCollisionMatrix matrix =
      computeAllowedCollisionMatrix(*panda, [&](const VectorX&, const std::vector<char>&, std::vector<char>&) { ++calls; }, settings);
  setLogSink({});
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(matrix.count(AllowedReason::kNever) + matrix.count(AllowedReason::kAlways), 0);
  ASSERT_EQ(warnings.size(), 1U);
  EXPECT_THAT(warnings[0], HasSubstr("no pair is disabled as never or always colliding"));
}

/// A fake link test: pair (1, 2) always collides, pair (3, 4) when q[0] > 0, nothing else.
void fakeTest(int links, const VectorX& q, std::vector<char>& hits) {
  const auto set = [&](int a, int b) {
    hits[static_cast<std::size_t>(a * links + b)] = hits[static_cast<std::size_t>(b * links + a)] = 1;
  };
  set(1, 2);
  if (q[0] > 0.0) set(3, 4);
}

TEST(AllowedCollisionMatrix, SampledPairsWithAFakeTest) {
  const RobotModelPtr panda = builtinRobot("panda");
  const int links = static_cast<int>(panda->links().size());
  int calls = 0;
  AllowedCollisionSettings settings;
  settings.samples = 300;
  const auto test = [&](const VectorX& q, const std::vector<char>&, std::vector<char>& hits) {
    ++calls;
    fakeTest(links, q, hits);
  };
  const AllowedCollisionMatrix matrix = computeAllowedCollisionMatrix(*panda, test, settings);
  EXPECT_EQ(calls, 300);
  // Links 1 and 2 are adjacent (adjacency is recorded first); 3 and 4 sometimes collide.
  EXPECT_EQ(matrix.reason(1, 2), AllowedReason::kAdjacent);
  EXPECT_EQ(matrix.reason(3, 4), AllowedReason::kAdjacent);
  EXPECT_EQ(matrix.reason(0, 5), AllowedReason::kNever);

  settings.disableNever = false;
  const auto far = [&](const VectorX& q, const std::vector<char>&, std::vector<char>& hits) {
    hits[static_cast<std::size_t>(0 * links + 5)] = hits[static_cast<std::size_t>(5 * links + 0)] = 1;
    if (q[0] > 0.0) hits[static_cast<std::size_t>(1 * links + 6)] = hits[static_cast<std::size_t>(6 * links + 1)] = 1;
  };
  const AllowedCollisionMatrix sampled = computeAllowedCollisionMatrix(*panda, far, settings);
  EXPECT_EQ(sampled.reason(0, 5), AllowedReason::kAlways);
  EXPECT_EQ(sampled.reason(1, 6), AllowedReason::kNone);
  EXPECT_EQ(sampled.count(AllowedReason::kNever), 0);
  settings.samples = 0;
  EXPECT_THAT([&] { (void)computeAllowedCollisionMatrix(*panda, far, settings); },
              ThrowsMessage<InputError>(HasSubstr("samples must be at least 1")));
}

/// Index (a * links + b) of the pairs neither adjacent nor disabled by the SRDF of `model`.
std::vector<std::size_t> pairsLeftToSample(const RobotModel& model) {
  AllowedCollisionSettings none;
  none.disableNever = none.disableAlways = false;
  const AllowedCollisionMatrix fixed =
      computeAllowedCollisionMatrix(model, [](const VectorX&, const std::vector<char>&, std::vector<char>&) {}, none);
  std::vector<std::size_t> pairs;
  const int links = fixed.linkCount();
  for (int a = 0; a < links; ++a) {
    for (int b = a + 1; b < links; ++b) {
      if (!fixed.isAllowed(a, b)) pairs.push_back(static_cast<std::size_t>(a * links + b));
    }
  }
  return pairs;
}

TEST(AllowedCollisionMatrix, PairsSeenCollidingAndFreeAreNotTestedAgain) {
  const RobotModelPtr panda = builtinRobot("panda");
  const std::size_t links = panda->links().size();
  const std::vector<std::size_t> pairs = pairsLeftToSample(*panda);
  ASSERT_GE(pairs.size(), 3U);
  const std::size_t sometimes = pairs[0];
  const std::size_t always = pairs[1];
  const std::size_t never = pairs[2];
  const auto mirror = [links](std::size_t i) { return (i % links) * links + i / links; };
  AllowedCollisionSettings settings;
  settings.samples = 200;
  std::vector<int> asked(links * links, 0);
  const auto test = [&](const VectorX& q, const std::vector<char>& pairsToTest, std::vector<char>& hits) {
    for (std::size_t i = 0; i < asked.size(); ++i) asked[i] += pairsToTest[i] != 0 ? 1 : 0;
    if (q[0] > 0.0) hits[sometimes] = hits[mirror(sometimes)] = 1;
    hits[always] = hits[mirror(always)] = 1;
  };
  const AllowedCollisionMatrix matrix = computeAllowedCollisionMatrix(*panda, test, settings);
  const auto reason = [&](std::size_t i) {
    return matrix.reason(static_cast<int>(i / links), static_cast<int>(i % links));
  };
  EXPECT_EQ(reason(sometimes), AllowedReason::kNone);
  EXPECT_EQ(reason(always), AllowedReason::kAlways);
  EXPECT_EQ(reason(never), AllowedReason::kNever);
  EXPECT_LT(asked[sometimes], 50);  // until it has collided once and been free in over 5 % of the samples
  EXPECT_GT(asked[sometimes], 10);
  EXPECT_EQ(asked[always], 200);
  EXPECT_EQ(asked[never], 200);
  EXPECT_EQ(asked[0 * links + 1], 0);  // adjacent: allowed before sampling
}

TEST(AllowedCollisionMatrix, APairCollidingInNinetyFivePercentOfTheSamplesIsAlways) {
  // As MoveIt's setup assistant: touching faces flicker between colliding and free, so a pair
  // colliding in 97 % of the samples is "always"; one colliding in 90 % is checked.
  const RobotModelPtr panda = builtinRobot("panda");
  const std::size_t links = panda->links().size();
  const std::vector<std::size_t> pairs = pairsLeftToSample(*panda);
  ASSERT_GE(pairs.size(), 2U);
  const auto mirror = [links](std::size_t i) { return (i % links) * links + i / links; };
  AllowedCollisionSettings settings;
  settings.samples = 200;
  int sample = 0;
  const auto test = [&](const VectorX&, const std::vector<char>&, std::vector<char>& hits) {
    const int s = sample++;
    if (s % 33 != 0) hits[pairs[0]] = hits[mirror(pairs[0])] = 1;  // misses 7 of 200
    if (s % 10 != 0) hits[pairs[1]] = hits[mirror(pairs[1])] = 1;  // misses 20 of 200
  };
  const AllowedCollisionMatrix matrix = computeAllowedCollisionMatrix(*panda, test, settings);
  EXPECT_EQ(matrix.reason(static_cast<int>(pairs[0] / links), static_cast<int>(pairs[0] % links)), AllowedReason::kAlways);
  EXPECT_EQ(matrix.reason(static_cast<int>(pairs[1] / links), static_cast<int>(pairs[1] % links)), AllowedReason::kNone);
  settings.alwaysFraction = 0.2;
  EXPECT_THROW((void)computeAllowedCollisionMatrix(*panda, test, settings), InputError);
}

TEST(AllowedCollisionMatrix, SkippingDecidedPairsChangesNothing) {
  const RobotModelPtr panda = builtinRobot("panda");
  const RobotModel& model = *panda;
  const std::size_t links = model.links().size();
  AllowedCollisionSettings settings;
  settings.samples = 300;
  // Link origins closer than 12 cm "collide": some pairs always, some never, some sometimes.
  const auto collides = [&](const VectorX& q, std::vector<char>& hits) {
    const std::vector<Pose> X_RL = model.linkPoses(q);
    for (std::size_t a = 0; a < links; ++a) {
      for (std::size_t b = a + 1; b < links; ++b) {
        const double gap = (X_RL[a].translation() - X_RL[b].translation()).norm();
        if (gap < 0.12) hits[a * links + b] = hits[b * links + a] = 1;
      }
    }
  };
  const auto pruned = [&](const VectorX& q, const std::vector<char>& pairsToTest, std::vector<char>& hits) {
    std::vector<char> all(links * links, 0);
    collides(q, all);
    for (std::size_t i = 0; i < all.size(); ++i) hits[i] = pairsToTest[i] != 0 ? all[i] : 0;
  };
  const auto full = [&](const VectorX& q, const std::vector<char>&, std::vector<char>& hits) { collides(q, hits); };
  const AllowedCollisionMatrix a = computeAllowedCollisionMatrix(model, pruned, settings);
  const AllowedCollisionMatrix b = computeAllowedCollisionMatrix(model, full, settings);
  for (int i = 0; i < static_cast<int>(links); ++i) {
    for (int j = 0; j < static_cast<int>(links); ++j) EXPECT_EQ(a.reason(i, j), b.reason(i, j)) << i << " " << j;
  }
  EXPECT_GT(a.count(AllowedReason::kNever) + a.count(AllowedReason::kAlways), 0);
}

TEST(AllowedCollisionMatrix, ComputedForThePandaWithFcl) {
  const FclCollisionChecker checker(robotOnlyScene("panda"));
  const AllowedCollisionMatrix& matrix = checker.allowedCollisions(0);
  const RobotModel& panda = *checker.scene().robots()[0].model;
  const auto reason = [&](const char* a, const char* b) {
    return matrix.reason(panda.linkIndex(a), panda.linkIndex(b));
  };
  EXPECT_EQ(reason("panda_link1", "panda_link2"), AllowedReason::kAdjacent);
  EXPECT_EQ(reason("panda_link6", "panda_hand"), AllowedReason::kAdjacent);
  // SRDF pairs that are not adjacent: "Never" pairs of the SRDF, and the fingers.
  EXPECT_EQ(reason("panda_link0", "panda_link2"), AllowedReason::kSrdf);
  EXPECT_EQ(reason("panda_leftfinger", "panda_rightfinger"), AllowedReason::kSrdf);
  for (const DisabledCollision& pair : panda.semantics().disabledCollisions) {
    EXPECT_TRUE(matrix.isAllowed(panda.linkIndex(pair.link1), panda.linkIndex(pair.link2)))
        << pair.link1 << " " << pair.link2;
  }
  // Link 5 and link 7 collide in some configurations (joint 6 at its lower limit): kept.
  EXPECT_EQ(reason("panda_link5", "panda_link7"), AllowedReason::kNone);
  EXPECT_EQ(reason("panda_link0", "panda_hand"), AllowedReason::kNone);
  // Deterministic: the same seed gives the same matrix.
  const FclCollisionChecker again(robotOnlyScene("panda"));
  for (int a = 0; a < matrix.linkCount(); ++a) {
    for (int b = 0; b < matrix.linkCount(); ++b) {
      ASSERT_EQ(matrix.reason(a, b), again.allowedCollisions(0).reason(a, b));
    }
  }
}

}  // namespace
}  // namespace lang2manip::test
