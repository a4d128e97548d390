// Grasp planning on the built-in desk scenes: top / front / side grasps of the marker and the
// eraser are found and reachable, the requested direction is honoured, a too-wide or
// unreachable object is refused with a reason naming it.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "grounding_test_support.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/grounding/grasp_planner.hpp"
#include "lang2manip/grounding/object_geometry.hpp"
#include "lang2manip/kinematics/forward_kinematics.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;

GraspPlan planGrasp(const ReachabilityChecker& reach, const std::string& object, GraspDirection direction) {
  GraspRequest request;
  request.object = object;
  request.direction = direction;
  return makeGraspPlanner(defaultGraspPlannerName())->plan(reach, request);
}

void expectReachable(const ReachabilityChecker& reach, const GraspCandidate& c) {
  ASSERT_FALSE(c.graspSolutions.empty());
  ASSERT_FALSE(c.preGraspSolutions.empty());
  const Pose tcp = reach.robot().basePose * computeLinkPose(reach.model(), c.graspSolutions.front(), reach.gripper().toolFrame);
  EXPECT_LT((tcp.translation() - c.graspPose.translation()).norm(), 1e-3) << c.label;
  const Pose pre = reach.robot().basePose * computeLinkPose(reach.model(), c.preGraspSolutions.front(), reach.gripper().toolFrame);
  EXPECT_LT((pre.translation() - c.preGraspPose.translation()).norm(), 1e-3) << c.label;
  EXPECT_NEAR((c.preGraspPose.translation() - c.graspPose.translation()).norm(), 0.10, 1e-9);
  EXPECT_NEAR(c.postGraspPose.translation().z() - c.graspPose.translation().z(), 0.10, 1e-9);
  EXPECT_LE(c.opening, reach.gripper().maxOpening + 1e-12);
  EXPECT_GE(c.opening, c.objectWidth);
}

class GraspOnRobot : public ::testing::TestWithParam<std::string> {};

TEST_P(GraspOnRobot, TopGraspsOfMarkerAndEraserAreReachable) {
  const ReachabilityChecker reach = reachFor(GetParam(), deskScene(GetParam()));
  for (const std::string object : {"marker", "eraser"}) {
    const GraspPlan plan = planGrasp(reach, object, GraspDirection::kTop);
    ASSERT_TRUE(plan.success()) << object << ": " << plan.reason;
    for (const GraspCandidate& c : plan.candidates) {
      EXPECT_EQ(c.direction, GraspDirection::kTop);
      EXPECT_NEAR(c.approachDirection.z(), -1.0, 1e-9);
      EXPECT_NE(c.label.find("approach (0.00, 0.00, -1.00)"), std::string::npos) << "no signed zeros: " << c.label;
      expectReachable(reach, c);
    }
    for (std::size_t i = 1; i < plan.candidates.size(); ++i) EXPECT_GE(plan.candidates[i - 1].score, plan.candidates[i].score);
  }
}

TEST_P(GraspOnRobot, SideGraspOfStandingBoxAndFrontGraspOfMarkerAreReachable) {
  Scene scene = deskScene(GetParam());
  scene.addObject(boxObject("bottle", Vector3(0.03, 0.03, 0.10), Vector3(0.15, -0.28, 0.75)));
  const ReachabilityChecker reach = reachFor(GetParam(), scene);
  const GraspPlan side = planGrasp(reach, "bottle", GraspDirection::kSide);
  ASSERT_TRUE(side.success()) << side.reason;
  for (const GraspCandidate& c : side.candidates) {
    EXPECT_EQ(c.direction, GraspDirection::kSide);
    EXPECT_LE(c.approachDirection.z(), 1e-9);
    EXPECT_GT(std::abs(c.approachDirection.y()), 0.7 * c.approachDirection.head<2>().norm());
    expectReachable(reach, c);
  }
  // A lying marker (or the flat eraser) cannot be held level from the side: the lower finger or
  // the hand would hit the desk. From the front the fingers close across the marker's end.
  const GraspPlan front = planGrasp(reach, "marker", GraspDirection::kFront);
  ASSERT_TRUE(front.success()) << front.reason;
  for (const GraspCandidate& c : front.candidates) {
    EXPECT_EQ(c.direction, GraspDirection::kFront);
    EXPECT_GT(c.approachDirection.x(), 0.7 * c.approachDirection.head<2>().norm());
    expectReachable(reach, c);
  }
}

TEST_P(GraspOnRobot, TooWideObjectIsRefusedWithReason) {
  Scene scene = deskScene(GetParam());
  scene.addObject(boxObject("crate", Vector3(0.12, 0.12, 0.12), Vector3(0.1, -0.3, 0.75)));
  const GraspPlan plan = planGrasp(reachFor(GetParam(), scene), "crate", GraspDirection::kAuto);
  EXPECT_FALSE(plan.success());
  EXPECT_EQ(plan.failure, GraspFailure::kTooWide);
  EXPECT_THAT(plan.reason, HasSubstr("crate"));
  EXPECT_THAT(plan.reason, HasSubstr("too wide"));
}

TEST_P(GraspOnRobot, FarAwayObjectIsRefusedAsUnreachable) {
  Scene scene = deskScene(GetParam());
  scene.object("marker").pose.translation() = Vector3(2.5, 0.0, 0.75);
  const GraspPlan plan = planGrasp(reachFor(GetParam(), scene), "marker", GraspDirection::kAuto);
  EXPECT_FALSE(plan.success());
  EXPECT_EQ(plan.failure, GraspFailure::kUnreachable);
  EXPECT_THAT(plan.reason, HasSubstr("marker"));
  EXPECT_THAT(plan.reason, HasSubstr("out of reach"));
}

TEST_P(GraspOnRobot, EveryCandidateHoldsTheObjectBetweenThePads) {
  // Flat and low objects resting on the desk: no finger passes under them (through the desk).
  Scene scene = deskScene(GetParam());
  scene.addObject(boxObject("slab", Vector3(0.14, 0.14, 0.06), Vector3(0.1, -0.3, 0.75)));
  const ReachabilityChecker reach = reachFor(GetParam(), scene);
  for (const std::string object : {"marker", "eraser", "slab"}) {
    const GraspPlan plan = planGrasp(reach, object, GraspDirection::kAuto);
    const SceneObject& o = scene.object(object);
    for (const GraspCandidate& c : plan.candidates) {
      const Vector3 closing = c.graspPose.linear() * reach.gripper().closingAxis;
      const double offCentre = std::abs((objectCentre(o, o.pose) - c.graspPose.translation()).dot(closing));
      EXPECT_LE(offCentre + c.objectWidth / 2.0, c.opening / 2.0 + 0.0031) << object << ": " << c.label;
    }
  }
  const GraspPlan slab = planGrasp(reach, "slab", GraspDirection::kAuto);
  EXPECT_FALSE(slab.success()) << slab.candidates.front().label;
}

INSTANTIATE_TEST_SUITE_P(DeskRobots, GraspOnRobot, ::testing::Values("panda", "ur5"));

TEST(GraspPlanner, AutoRanksSeveralDirectionsAndIsDeterministic) {
  // A budget no IK call reaches, even under AddressSanitizer: the order must not depend on time.
  const ReachabilityChecker reach = reachFor("panda", deskScene("panda"), {}, 2.0);
  const GraspPlan first = planGrasp(reach, "marker", GraspDirection::kAuto);
  const GraspPlan second = planGrasp(reach, "marker", GraspDirection::kAuto);
  ASSERT_TRUE(first.success()) << first.reason;
  ASSERT_EQ(first.candidates.size(), second.candidates.size());
  bool top = false, other = false;
  for (std::size_t i = 0; i < first.candidates.size(); ++i) {
    EXPECT_EQ(first.candidates[i].label, second.candidates[i].label);
    EXPECT_TRUE(first.candidates[i].graspPose.isApprox(second.candidates[i].graspPose));
    (first.candidates[i].direction == GraspDirection::kTop ? top : other) = true;
  }
  EXPECT_TRUE(top);
  EXPECT_TRUE(other);
}

TEST(GraspPlanner, FlatEraserCannotBeHeldLevelFromTheSide) {
  // Level, the lower finger would hit the desk; tilted down, the fingers close on the eraser's
  // ends with their tips above the desk and below the eraser's top.
  const ReachabilityChecker reach = reachFor("panda", deskScene("panda"));
  const GraspPlan side = planGrasp(reach, "eraser", GraspDirection::kSide);
  ASSERT_TRUE(side.success()) << side.reason;
  const AlignedBox3 eraser = reach.scene().object("eraser").worldBounds();
  for (const GraspCandidate& c : side.candidates) {
    EXPECT_LT(c.approachDirection.z(), -0.4) << c.label;
    const AlignedBox3 fingers = transformedBox(reach.gripper().fingerBounds, c.graspPose);
    EXPECT_GT(fingers.min().z(), eraser.min().z()) << c.label;
    EXPECT_LT(fingers.min().z(), eraser.max().z() - GraspSettings{}.minimumEngagement + 1e-9) << c.label;
  }
}

TEST(GraspPlanner, FixedObjectAndHeldObjectAreNotGraspable) {
  Scene scene = deskScene("panda");
  const GraspPlan desk = planGrasp(reachFor("panda", scene), "desk", GraspDirection::kAuto);
  EXPECT_EQ(desk.failure, GraspFailure::kNotGraspable);
  EXPECT_THAT(desk.reason, HasSubstr("desk: not movable"));
  scene.attach({"eraser", "panda", "panda_hand_tcp", Pose::Identity()});
  const GraspPlan held = planGrasp(reachFor("panda", scene), "eraser", GraspDirection::kAuto);
  EXPECT_EQ(held.failure, GraspFailure::kNotGraspable);
  EXPECT_THAT(held.reason, HasSubstr("eraser: already held"));
}

TEST(GraspPlanner, BesideAWallTheHandLeansAwayInsteadOfGivingUp) {
  Scene scene = deskScene("panda");
  const SceneObject& marker = scene.object("marker");
  const Vector3 size = marker.dimensions();
  Eigen::Index longest = 0;
  size.maxCoeff(&longest);
  const Vector3 along = marker.pose.linear().col(longest);
  const Vector3 across = Vector3::UnitZ().cross(along).normalized();
  // A wall 10 cm from the marker's axis, as long as the marker and as high as the hand comes
  // down: straight from above, the hand (wide across the marker) touches it.
  const Vector3 centre = objectCentre(marker, marker.pose);
  SceneObject wall = boxObject("wall", Vector3(0.02, 0.16, 0.10), Vector3(centre.x(), centre.y(), 0.0) + across * 0.10);
  wall.pose.translation().z() = marker.worldBounds().min().z();
  wall.pose.linear() = Eigen::AngleAxisd(std::atan2(along.y(), along.x()) - M_PI / 2.0, Vector3::UnitZ()).toRotationMatrix();
  wall.movable = false;
  scene.addObject(wall);
  const ReachabilityChecker reach = reachFor("panda", scene);
  const GraspPlan plan = planGrasp(reach, "marker", GraspDirection::kTop);
  ASSERT_TRUE(plan.success()) << plan.reason;
  EXPECT_NEAR(plan.widenedTilt, 2.0 * M_PI / 9.0, 1e-12) << "a straight-down grasp was found beside the wall";
  for (const GraspCandidate& c : plan.candidates) {
    EXPECT_GT(c.approachDirection.z(), -0.99) << c.label;
    expectReachable(reach, c);
  }
  GraspRequest request;
  request.object = "marker";
  request.settings.widenedTopTilts = {0.3, M_PI / 2.0};
  EXPECT_THROW(static_cast<void>(makeGraspPlanner("heuristic")->plan(reach, request)), InputError);
}

TEST(GraspPlanner, BadInputThrows) {
  const ReachabilityChecker reach = reachFor("panda", deskScene("panda"));
  EXPECT_THROW(static_cast<void>(planGrasp(reach, "stapler", GraspDirection::kTop)), InputError);
  GraspRequest request;
  request.object = "marker";
  request.settings.approachDistance = -0.1;
  EXPECT_THROW(static_cast<void>(makeGraspPlanner("heuristic")->plan(reach, request)), InputError);
  try {
    static_cast<void>(makeGraspPlanner("magic"));
    FAIL() << "no exception";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("heuristic"));
  }
  EXPECT_THROW(ReachabilityChecker(nullptr, makeIkSolver("dls")), InputError);
}

TEST(GripperGeometry, OpeningAndClosingAxisFromTheModels) {
  const GripperGeometry panda = reachFor("panda", deskScene("panda")).gripper();
  EXPECT_NEAR(panda.maxOpening, 0.08, 1e-9);
  EXPECT_NEAR(std::abs(panda.closingAxis.y()), 1.0, 1e-6);
  EXPECT_GT(panda.fingertipOffset(), 0.0);
  EXPECT_GT(panda.fingerReachBehind(), 0.03);
  const GripperGeometry ur5 = reachFor("ur5", deskScene("ur5")).gripper();
  EXPECT_NEAR(ur5.maxOpening, 0.085, 1e-9);
  EXPECT_NEAR(std::abs(ur5.closingAxis.y()), 1.0, 1e-6);
  const GripperGeometry yumi = describeGripper(*deskScene("yumi").robots().front().model);
  EXPECT_NEAR(yumi.maxOpening, 0.05, 1e-9);
  EXPECT_NEAR(std::abs(yumi.closingAxis.x()), 1.0, 1e-6);
  EXPECT_EQ(yumi.fingerLinks.size(), 2u);
}

}  // namespace
}  // namespace lang2manip::test
