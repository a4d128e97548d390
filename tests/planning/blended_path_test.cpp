#include "lang2manip/planning/blended_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/random.hpp"

namespace lang2manip::test {
namespace {

VectorX point2(double x, double y) { return (VectorX(2) << x, y).finished(); }

bool exactlyEqual(const VectorX& a, const VectorX& b) {
  return a.size() == b.size() && (a.array() == b.array()).all();
}

// The message of the InputError that `call` throws ("" when it throws none).
template <typename Call>
std::string blendedPathError(Call call) {
  try {
    call();
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(BlendedPath, CornerArcWithinTheDeviation) {
  const double deviation = 0.1;
  const BlendedPath path({point2(0, 0), point2(2, 0), point2(2, 2)}, deviation);
  ASSERT_EQ(path.segments().size(), 3u);
  EXPECT_EQ(path.segments()[1].kind, PathSegment::Kind::kArc);
  EXPECT_LT(path.length(), 4.0);
  EXPECT_TRUE(exactlyEqual(path.position(0.0), point2(0, 0)));
  EXPECT_TRUE(exactlyEqual(path.position(path.length()), point2(2, 2)));
  ASSERT_EQ(path.switchingPoints().size(), 2u);
  EXPECT_TRUE(path.stopPoints().empty());
  // The arc's middle is exactly maxDeviation from the corner it replaces.
  const PathSegment& arc = path.segments()[1];
  EXPECT_NEAR((path.position(arc.start + 0.5 * arc.length) - point2(2, 0)).norm(), deviation, 1e-12);
  // Tangent continuous and unit; curvature 1/radius on the arc, zero on the lines.
  for (const double s : path.switchingPoints()) {
    EXPECT_LT((path.tangent(s - 1e-9) - path.tangent(s + 1e-9)).norm(), 1e-6);
  }
  EXPECT_NEAR(path.tangent(arc.start + 0.3 * arc.length).norm(), 1.0, 1e-12);
  EXPECT_NEAR(path.curvature(arc.start + 0.3 * arc.length).norm(), 1.0 / arc.radius, 1e-9);
  EXPECT_TRUE(path.curvature(0.5).isZero());
}

TEST(BlendedPath, ArcUsesAtMostHalfOfEachSegment) {
  // A large deviation: the 0.2-long first segment limits the arc to 0.1 of it.
  const BlendedPath path({point2(0, 0), point2(0.2, 0), point2(0.2, 5)}, 10.0);
  const PathSegment& arc = path.segments()[1];
  ASSERT_EQ(arc.kind, PathSegment::Kind::kArc);
  EXPECT_NEAR(arc.start, 0.1, 1e-12);
  EXPECT_NEAR(path.position(arc.start + arc.length)[1], 0.1, 1e-12);
}

TEST(BlendedPath, DerivativesMatchFiniteDifferences) {
  Random random(3);
  std::vector<VectorX> waypoints;
  for (int i = 0; i < 8; ++i) waypoints.push_back(random.uniformVector(VectorX::Constant(7, -2), VectorX::Constant(7, 2)));
  const BlendedPath path(waypoints, 0.05);
  for (const PathSegment& segment : path.segments()) {
    for (const double fraction : {0.25, 0.5, 0.75}) {
      const double s = segment.start + fraction * segment.length;
      const double h = 1e-5 * std::min(1.0, segment.length);
      const VectorX first = (path.position(s + h) - path.position(s - h)) / (2.0 * h);
      const VectorX second = (path.position(s + h) - 2.0 * path.position(s) + path.position(s - h)) / (h * h);
      EXPECT_LT((first - path.tangent(s)).norm(), 1e-6);
      EXPECT_LT((second - path.curvature(s)).norm(), 1e-3 * (1.0 + path.curvature(s).norm()));
    }
  }
}

TEST(BlendedPath, RepeatedWaypointsAreDropped) {
  const VectorX a = point2(0, 0);
  const VectorX b = point2(1, 0);
  const BlendedPath path({a, a, b, b + point2(1e-12, 0), point2(1, 1), point2(1, 1)}, 0.01);
  EXPECT_EQ(path.waypoints().size(), 3u);
  EXPECT_TRUE(exactlyEqual(path.position(path.length()), point2(1, 1)));
  const BlendedPath still({a, a, a}, 0.01);
  EXPECT_EQ(still.length(), 0.0);
  EXPECT_TRUE(still.segments().empty());
  EXPECT_TRUE(exactlyEqual(still.position(1.0), a));
  EXPECT_EQ(still.sample(0.1).size(), 1u);
}

TEST(BlendedPath, ReversalsAndZeroDeviationStop) {
  // The direction turns by pi at (1, 0): no arc fits, the path stops there.
  const BlendedPath reversal({point2(0, 0), point2(1, 0), point2(0.5, 0)}, 0.01);
  ASSERT_EQ(reversal.stopPoints().size(), 1u);
  EXPECT_DOUBLE_EQ(reversal.stopPoints()[0], 1.0);
  EXPECT_TRUE(reversal.switchingPoints().empty());
  EXPECT_DOUBLE_EQ(reversal.length(), 1.5);
  // Without deviation every corner is a stop, but a straight continuation is not.
  const BlendedPath sharp({point2(0, 0), point2(1, 0), point2(2, 0), point2(2, 1)}, 0.0);
  ASSERT_EQ(sharp.stopPoints().size(), 1u);
  EXPECT_DOUBLE_EQ(sharp.stopPoints()[0], 2.0);
  EXPECT_DOUBLE_EQ(sharp.length(), 3.0);
  for (const double stop : sharp.stopPoints()) {
    EXPECT_DOUBLE_EQ(sharp.segments()[sharp.segmentIndex(stop)].start, stop);
  }
}

TEST(BlendedPath, SamplesAtMostAResolutionApart) {
  const BlendedPath path({point2(0, 0), point2(1, 0), point2(1, 1), point2(3, 0)}, 0.2);
  const std::vector<VectorX> samples = path.sample(0.05);
  ASSERT_GE(samples.size(), static_cast<std::size_t>(path.length() / 0.05));
  EXPECT_TRUE(exactlyEqual(samples.front(), point2(0, 0)));
  EXPECT_TRUE(exactlyEqual(samples.back(), point2(3, 0)));
  for (std::size_t i = 1; i < samples.size(); ++i) EXPECT_LE((samples[i] - samples[i - 1]).norm(), 0.05 + 1e-12);
}

TEST(BlendedPath, BadInputNamesTheWaypoint) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(blendedPathError([] { (void)BlendedPath({}, 0.1); }).find("empty"), std::string::npos);
  EXPECT_NE(blendedPathError([&] { (void)BlendedPath({point2(0, 0), point2(1, 0), point2(nan, 0)}, 0.1); })
                .find("waypoint 2"),
            std::string::npos);
  EXPECT_NE(blendedPathError([] { (void)BlendedPath({point2(0, 0), VectorX::Zero(3)}, 0.1); }).find("waypoint 1 has 3 values"),
            std::string::npos);
  EXPECT_NE(blendedPathError([] { (void)BlendedPath({point2(0, 0)}, -1.0); }).find("max deviation"), std::string::npos);
  EXPECT_NE(blendedPathError([] { (void)BlendedPath({VectorX()}, 0.1); }).find("waypoint 0"), std::string::npos);
  const BlendedPath path({point2(0, 0), point2(1, 0)}, 0.1);
  EXPECT_THROW((void)path.sample(0.0), InputError);
  EXPECT_THROW((void)path.sample(std::numeric_limits<double>::infinity()), InputError);
}

}  // namespace
}  // namespace lang2manip::test
