// Timing an action's motions: runs join at no stop, a blend that would collide is made smaller
// (down to the planned corner), and the verification checks the blended path, not the waypoints.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <optional>

#include "execution_test_support.hpp"
#include "lang2manip/execution/motion_timing.hpp"
#include "lang2manip/planning/blended_path.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;

constexpr double kDeviation = 0.6;

MotionSegment transit(const std::string& label, const Scene& world, const VectorX& from, const VectorX& to) {
  MotionSegment segment;
  segment.label = label;
  segment.world = world;
  segment.planner = "RRTConnect";
  segment.waypoints = {from, to};
  return segment;
}

/// Two transits meeting at a sharp corner: the base turns, then the elbow unfolds.
struct Corner {
  VectorX start, corner, end;
};

Corner cornerOf(const ArmContext& arm, const Scene& scene, double turn = 0.8, int unfoldJoint = 3, double unfold = 0.6) {
  Corner c;
  c.start = scene.robot(arm.robotName()).configuration;
  c.corner = c.start;
  c.corner[arm.armVariables()[0]] += turn;
  c.end = c.corner;
  c.end[arm.armVariables()[static_cast<std::size_t>(unfoldJoint)]] += unfold;
  return c;
}

/// The tool position halfway along the blend of the corner.
Vector3 blendMiddle(const ArmContext& arm, const Scene& scene, const Corner& c) {
  const BlendedPath blended({c.start, c.corner, c.end}, kDeviation);
  for (const PathSegment& piece : blended.segments()) {
    if (piece.kind == PathSegment::Kind::kArc) return arm.toolPose(scene, piece.position(0.5 * piece.length)).translation();
  }
  ADD_FAILURE() << "the corner was not blended";
  return Vector3::Zero();
}

/// A scene with a small post where the blend of a corner passes but neither of the corner's
/// straight legs does: the first such corner of a few turns of the base and unfoldings.
struct PostedCorner {
  Scene scene;
  Corner corner;
};

std::optional<PostedCorner> cornerWithAPostOnItsBlend(const ExecutionSettings& settings) {
  const Scene desk = deskScene("panda");
  const ArmContext bare(desk, settings);
  for (const double turn : {0.8, 1.2, 1.6}) {
    for (const int joint : {1, 3, 5}) {
      for (const double unfold : {0.6, 1.0, -0.6, -1.0}) {
        const Corner c = cornerOf(bare, desk, turn, joint, unfold);
        PostedCorner posted{desk, c};
        const Vector3 middle = blendMiddle(bare, desk, c);
        posted.scene.addObject(fixedBox("post", Vector3(0.02, 0.02, 0.02), middle - Vector3(0.0, 0.0, 0.01)));
        const ArmContext arm(posted.scene, settings);
        const bool legsFree = checkSegment(arm, transit("turn", posted.scene, c.start, c.corner), settings.verificationResolution).collision.empty() &&
                              checkSegment(arm, transit("unfold", posted.scene, c.corner, c.end), settings.verificationResolution).collision.empty();
        if (legsFree) return posted;
      }
    }
  }
  return std::nullopt;
}

TEST(MotionTiming, ABlendThatWouldCollideIsMadeSmallerAndVerificationChecksTheBlend) {
  ExecutionSettings settings = testSettings();
  settings.blendDeviation = kDeviation;
  const std::optional<PostedCorner> posted = cornerWithAPostOnItsBlend(settings);
  ASSERT_TRUE(posted.has_value()) << "no corner whose legs miss the post";
  const Corner& c = posted->corner;
  const ArmContext arm(posted->scene, settings);
  ActionExecution action;
  action.segments = {transit("turn", posted->scene, c.start, c.corner), transit("unfold", posted->scene, c.corner, c.end)};

  const ActionTiming timing = timeActionMotions(arm, action.segments);
  ASSERT_EQ(timing.runs.size(), 1u);
  EXPECT_EQ(timing.quality.reducedBlends, 1);
  EXPECT_LT(timing.runs.front().cornerDeviations[1], kDeviation);
  action.runs = timing.runs;
  EXPECT_EQ(checkTimedAction(arm, action, settings.verificationResolution).collision, "");

  action.runs.front().cornerDeviations.assign(3, kDeviation);
  EXPECT_THAT(checkTimedAction(arm, action, settings.verificationResolution).collision,
              HasSubstr("post (on the blend at waypoint 1 of the run)"));
}

TEST(MotionTiming, TransitsJoinWithoutAStopAndSegmentEndTimesFollowThePath) {
  const Scene scene = deskScene("panda");
  const ArmContext arm(scene, testSettings());
  const Corner c = cornerOf(arm, scene);
  const ActionTiming timing = timeActionMotions(arm, {transit("turn", scene, c.start, c.corner), transit("unfold", scene, c.corner, c.end)});
  ASSERT_EQ(timing.segmentEndTimes.size(), 2u);
  EXPECT_DOUBLE_EQ(timing.segmentEndTimes[1], timing.trajectory.duration());
  EXPECT_GT(timing.segmentEndTimes[0], 0.2 * timing.trajectory.duration());
  EXPECT_LT(timing.segmentEndTimes[0], 0.8 * timing.trajectory.duration());
  EXPECT_EQ(timing.quality.stopsInsideRuns, 0);
  EXPECT_EQ(timing.quality.blendedCorners, 1);
  for (std::size_t i = 1; i + 1 < timing.trajectory.points.size(); ++i) {
    EXPECT_GT(timing.trajectory.points[i].velocities.norm(), 1e-6) << "stops at " << timing.trajectory.points[i].time;
  }
}

TEST(MotionTiming, RepeatedReversedAndEmptyMotionsAreTimedWithoutError) {
  const Scene scene = deskScene("panda");
  const ArmContext arm(scene, testSettings());
  const Corner c = cornerOf(arm, scene);
  MotionSegment repeated = transit("repeated", scene, c.start, c.start);
  repeated.waypoints = {c.start, c.start, c.corner, c.corner, c.corner};
  MotionSegment back = transit("back", scene, c.corner, c.start);  // a reversal: the arm stops there
  MotionSegment empty = transit("empty", scene, c.start, c.start);
  empty.waypoints.clear();
  const ActionTiming timing = timeActionMotions(arm, {repeated, back, empty});
  ASSERT_EQ(timing.segmentEndTimes.size(), 3u);
  EXPECT_EQ(timing.quality.stopsInsideRuns, 1);
  EXPECT_LT((timing.trajectory.points.back().positions - c.start).norm(), 1e-9);
  EXPECT_EQ(checkTrajectoryLimits(arm.robotSpace(), timing.trajectory, kTimingSlack), "");
  for (std::size_t i = 1; i < timing.trajectory.points.size(); ++i) {
    EXPECT_GT(timing.trajectory.points[i].time, timing.trajectory.points[i - 1].time);
  }
}

}  // namespace
}  // namespace lang2manip::test
