// The exact checker's behaviour: attached objects, motions, batches, threads and bad input.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <thread>

#include "collision_test_support.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/random.hpp"
#include "lang2manip/kinematics/forward_kinematics.hpp"

namespace lang2manip::test {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

bool reportsPair(const CollisionReport& report, const std::string& a, const std::string& b) {
  for (const CollisionContact& contact : report.contacts) {
    if ((contact.first == a && contact.second == b) || (contact.first == b && contact.second == a)) return true;
  }
  return false;
}

bool touches(const CollisionReport& report, const std::string& body) {
  for (const CollisionContact& contact : report.contacts) {
    if (contact.first == body || contact.second == body) return true;
  }
  return false;
}

SceneObject objectWith(const std::string& name, Geometry geometry, const Pose& pose) {
  SceneObject object;
  object.name = name;
  object.kind = name;
  object.movable = true;
  object.pose = pose;
  Shape shape;
  shape.geometry = std::move(geometry);
  object.collisions.push_back(shape);
  return object;
}

/// X_WL of link `link` of the scene's first robot at `q`.
Pose worldLinkPose(const Scene& scene, const VectorX& q, const std::string& link) {
  const SceneRobot& robot = scene.robots().front();
  return robot.basePose * computeLinkPose(*robot.model, q, link);
}

VectorX pandaHome() { return builtinRobot("panda")->namedConfiguration("home"); }

VectorX withJoint(VectorX q, int variable, double value) {
  q[variable] = value;
  return q;
}

TEST(AttachedObjects, HeldObjectTouchingTheFingersIsNotReportedAgainstThem) {
  Scene scene = problemScene("panda_desk");
  const Pose X_LO(Eigen::Translation3d(0, 0, 0.09));
  const Pose X_WO = worldLinkPose(scene, pandaHome(), "panda_hand") * X_LO;
  Scene loose = scene;
  loose.addObject(objectWith("block", Box{Vector3(0.03, 0.14, 0.03)}, X_WO));
  const FclCollisionChecker looseChecker(loose);
  const CollisionReport free = looseChecker.checkState(0, pandaHome(), {}, *looseChecker.makeContext());
  EXPECT_TRUE(reportsPair(free, "block", "panda/panda_leftfinger")) << contactList(free);

  scene.addObject(objectWith("block", Box{Vector3(0.03, 0.14, 0.03)}, X_WO));
  scene.attach(Attachment{"block", "panda", "panda_hand", X_LO});
  const FclCollisionChecker checker(scene);
  const auto context = checker.makeContext();
  EXPECT_TRUE(checker.isStateValid(0, pandaHome(), *context))
      << contactList(checker.checkState(0, pandaHome(), {}, *context));
}

TEST(AttachedObjects, HeldObjectIsReportedAgainstOtherLinks) {
  Scene scene = problemScene("panda_desk");
  const Pose X_WH = worldLinkPose(scene, pandaHome(), "panda_hand");
  const Pose X_WL3 = worldLinkPose(scene, pandaHome(), "panda_link3");
  scene.addObject(objectWith("ball", Sphere{0.03}, X_WL3));
  scene.attach(Attachment{"ball", "panda", "panda_hand", X_WH.inverse() * X_WL3});
  const FclCollisionChecker checker(scene);
  const auto context = checker.makeContext();
  const CollisionReport report = checker.checkState(0, pandaHome(), {}, *context);
  EXPECT_FALSE(report.valid);
  EXPECT_TRUE(reportsPair(report, "ball", "panda/panda_link3")) << contactList(report);
}

TEST(AttachedObjects, HeldObjectMovesWithItsLink) {
  Scene scene = problemScene("panda_desk");
  const VectorX turned = withJoint(pandaHome(), 0, 1.0);
  const Pose X_LO(Eigen::Translation3d(0, 0, 0.25));
  scene.addObject(objectWith("post", Sphere{0.03}, worldLinkPose(scene, turned, "panda_hand") * X_LO));
  const FclCollisionChecker withoutBall(scene);
  EXPECT_TRUE(withoutBall.isStateValid(0, turned, *withoutBall.makeContext()));

  scene.addObject(objectWith("ball", Sphere{0.03}, Pose::Identity()));
  scene.attach(Attachment{"ball", "panda", "panda_hand", X_LO});
  const FclCollisionChecker checker(scene);
  const auto context = checker.makeContext();
  EXPECT_TRUE(checker.isStateValid(0, pandaHome(), *context));
  const CollisionReport report = checker.checkState(0, turned, {}, *context);
  EXPECT_FALSE(report.valid);
  EXPECT_TRUE(reportsPair(report, "ball", "post")) << contactList(report);
}

TEST(CollisionChecker, DisabledObjectsAreIgnored) {
  Scene scene = problemScene("panda_desk");
  SceneObject block = objectWith("block", Sphere{0.05}, worldLinkPose(scene, pandaHome(), "panda_link4"));
  scene.addObject(block);
  const FclCollisionChecker enabled(scene);
  EXPECT_FALSE(enabled.isStateValid(0, pandaHome(), *enabled.makeContext()));
  scene.object("block").collisionEnabled = false;
  const FclCollisionChecker disabled(scene);
  EXPECT_TRUE(disabled.isStateValid(0, pandaHome(), *disabled.makeContext()));
}

class MotionThroughAPillar : public ::testing::Test {
 protected:
  static Scene pillarScene() {
    Scene scene = problemScene("panda_desk");
    scene.addObject(objectWith("pillar", Sphere{0.05}, worldLinkPose(scene, pandaHome(), "panda_hand_tcp")));
    return scene;
  }
  const FclCollisionChecker checker_{pillarScene()};
  std::unique_ptr<CollisionContext> context_ = checker_.makeContext();
  VectorX left_ = withJoint(pandaHome(), 0, -0.8);
  VectorX right_ = withJoint(pandaHome(), 0, 0.8);
};

TEST_F(MotionThroughAPillar, IsInvalidThoughBothEndsAreFree) {
  EXPECT_TRUE(checker_.isStateValid(0, left_, *context_));
  EXPECT_TRUE(checker_.isStateValid(0, right_, *context_));
  EXPECT_FALSE(checker_.isStateValid(0, pandaHome(), *context_));
  EXPECT_FALSE(checker_.isMotionValid(0, left_, right_, 0.05, *context_));
  EXPECT_FALSE(checker_.isMotionValid(0, right_, left_, 0.05, *context_));
  // At a resolution coarser than the motion only the ends are checked.
  EXPECT_TRUE(checker_.isMotionValid(0, left_, right_, 10.0, *context_));
  EXPECT_TRUE(checker_.isMotionValid(0, left_, withJoint(left_, 0, -1.4), 0.05, *context_));
  EXPECT_FALSE(checker_.isMotionValid(0, pandaHome(), pandaHome(), 0.05, *context_));
}

std::vector<VectorX> randomConfigurations(const RobotModel& model, int count) {
  Random random(7);
  std::vector<VectorX> configurations;
  for (int i = 0; i < count; ++i) {
    configurations.push_back(random.uniformVector(model.lowerLimits(), model.upperLimits()));
  }
  return configurations;
}

TEST(CollisionChecker, BatchAgreesWithSingleChecksAndThreads) {
  const FclCollisionChecker checker(problemScene("panda_desk"));
  const auto configurations = randomConfigurations(*checker.scene().robots()[0].model, 300);
  const auto context = checker.makeContext();
  const std::vector<bool> batch = checker.checkStates(0, configurations, *context);
  ASSERT_EQ(batch.size(), configurations.size());
  int valid = 0;
  for (std::size_t i = 0; i < configurations.size(); ++i) {
    EXPECT_EQ(batch[i], checker.isStateValid(0, configurations[i], *context)) << i;
    EXPECT_EQ(batch[i], checker.checkState(0, configurations[i], {}, *context).valid) << i;
    valid += batch[i] ? 1 : 0;
  }
  EXPECT_GT(valid, 20);
  EXPECT_LT(valid, 280);
  std::vector<std::vector<bool>> perThread(2);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < perThread.size(); ++t) {
    threads.emplace_back([&, t] {
      const auto own = checker.makeContext();
      perThread[t] = checker.checkStates(0, configurations, *own);
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (const auto& results : perThread) EXPECT_EQ(results, batch);
}

TEST(CollisionChecker, ReportGivesDistancesAndPenetrations) {
  const FclCollisionChecker checker(problemScene("panda_desk"));
  const auto context = checker.makeContext();
  const CollisionReport free = checker.checkState(0, pandaHome(), {true}, *context);
  EXPECT_TRUE(free.valid);
  EXPECT_GT(free.minimumDistance, 0.0);
  EXPECT_LT(free.minimumDistance, 0.05);  // link0 stands 1 mm above the desk
  EXPECT_EQ(free.closestSecond, "desk");
  const CollisionReport hit = checker.checkState(0, withJoint(pandaHome(), 1, 1.7628), {true}, *context);
  EXPECT_FALSE(hit.valid);
  EXPECT_TRUE(touches(hit, "desk"));
  EXPECT_LT(hit.minimumDistance, -0.01);
  // A report does not disturb the context's scene state.
  EXPECT_TRUE(checker.isStateValid(0, pandaHome(), *context));
}

/// The smallest distance of robot 0 at `q` in `scene`, or +infinity when it collides.
double clearanceIn(const Scene& scene, const VectorX& q) {
  const FclCollisionChecker checker(scene);
  const CollisionReport report = checker.checkState(0, q, {true}, *checker.makeContext());
  return report.valid ? report.minimumDistance : std::numeric_limits<double>::infinity();
}

TEST(CollisionChecker, TheNearestPairSearchAgreesWithOneObjectAtATime) {
  // The search skips pairs whose boxes are farther apart than the best distance so far: its
  // answer must be the smallest of the scenes holding the robot with one object each.
  const Scene full = problemScene("panda_desk");
  const auto configurations = randomConfigurations(*full.robots()[0].model, 24);
  int compared = 0;
  for (const VectorX& q : configurations) {
    const double distance = clearanceIn(full, q);
    if (!std::isfinite(distance)) continue;
    ++compared;
    Scene robotOnly = full;
    for (const SceneObject& object : full.objects()) robotOnly.removeObject(object.name);
    double smallest = clearanceIn(robotOnly, q);
    for (const SceneObject& object : full.objects()) {
      Scene single = robotOnly;
      single.addObject(object);
      smallest = std::min(smallest, clearanceIn(single, q));
    }
    EXPECT_DOUBLE_EQ(distance, smallest);
  }
  EXPECT_GE(compared, 8);
}

TEST(CollisionChecker, SharedMatricesGiveTheSameResults) {
  const FclCollisionChecker first(problemScene("panda_desk"));
  FclCheckerSettings settings;
  settings.precomputedMatrices = {first.sharedAllowedCollisions(0)};
  const FclCollisionChecker second(problemScene("panda_desk"), settings);
  EXPECT_EQ(&first.allowedCollisions(0), &second.allowedCollisions(0));
  const auto configurations = randomConfigurations(*first.scene().robots()[0].model, 50);
  EXPECT_EQ(first.checkStates(0, configurations, *first.makeContext()),
            second.checkStates(0, configurations, *second.makeContext()));
  settings.precomputedMatrices = {std::make_shared<const AllowedCollisionMatrix>(3)};
  EXPECT_THAT([&] { FclCollisionChecker bad(problemScene("panda_desk"), settings); },
              ThrowsMessage<InputError>(HasSubstr("does not fit robot 'panda'")));
}

TEST(CollisionCheckerBadInput, ClearMessages) {
  const FclCollisionChecker checker(problemScene("panda_desk"));
  const auto context = checker.makeContext();
  EXPECT_THAT([&] { (void)checker.robotIndex("pr2"); },
              ThrowsMessage<InputError>(HasSubstr("unknown robot 'pr2'; valid robots: panda")));
  EXPECT_EQ(checker.robotIndex("panda"), 0);
  EXPECT_THAT([&] { (void)checker.isStateValid(2, pandaHome(), *context); },
              ThrowsMessage<InputError>(HasSubstr("no robot with index 2; valid robots: panda")));
  EXPECT_THAT([&] { (void)checker.isStateValid(0, VectorX::Zero(3), *context); },
              ThrowsMessage<InputError>(HasSubstr("has 3 values; the robot has 8 joint variables")));
  VectorX nan = pandaHome();
  nan[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT([&] { (void)checker.isStateValid(0, nan, *context); },
              ThrowsMessage<InputError>(HasSubstr("\"panda_joint3\" is not finite")));
  EXPECT_THAT([&] { (void)checker.checkStates(0, {pandaHome(), nan}, *context); },
              ThrowsMessage<InputError>(HasSubstr("configuration 1")));
  EXPECT_THAT([&] { (void)checker.isMotionValid(0, pandaHome(), pandaHome(), 0.0, *context); },
              ThrowsMessage<InputError>(HasSubstr("resolution must be positive")));
  EXPECT_THAT([&] { (void)checker.isMotionValid(0, pandaHome(), nan, 0.1, *context); },
              ThrowsMessage<InputError>(HasSubstr("motion end")));
  const FclCollisionChecker other(problemScene("panda_desk"));
  EXPECT_THAT([&] { (void)other.isStateValid(0, pandaHome(), *context); },
              ThrowsMessage<InputError>(HasSubstr("made by another checker")));
  WorldState state = checker.sceneState();
  state.basePoses.clear();
  EXPECT_THAT([&] { (void)checker.checkWorld(state, {}, *context); },
              ThrowsMessage<InputError>(HasSubstr("0 base poses; the scene has 1 robots")));
}

}  // namespace
}  // namespace lang2manip::test
