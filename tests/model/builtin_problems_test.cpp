#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>

#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "model_test_support.hpp"

namespace lang2manip {
namespace {

using ::testing::Contains;
using ::testing::HasSubstr;
using test::errorMessage;

TEST(BuiltinProblems, ListsThePaperSceneFirstAndEveryRobot) {
  const std::vector<BuiltinProblem> problems = builtinProblems();
  ASSERT_FALSE(problems.empty());
  EXPECT_EQ(problems.front().shortName, "panda_desk");
  std::vector<std::string> names;
  for (const BuiltinProblem& problem : problems) names.push_back(problem.shortName);
  for (const char* name : {"panda_desk", "ur5_desk", "iiwa14_desk", "yumi_desk", "tx90_desk"}) {
    EXPECT_THAT(names, Contains(name));
  }
  EXPECT_EQ(builtinRobotNames(), (std::vector<std::string>{"iiwa14", "panda", "tx90", "ur5", "yumi"}));
}

TEST(BuiltinProblems, ResolvesShortNamesAndPathsAndListsNamesOnError) {
  EXPECT_EQ(resolveProblem("panda_desk"), builtinProblems().front().file);
  EXPECT_EQ(resolveProblem(builtinProblems().front().file.string()), builtinProblems().front().file);
  EXPECT_THAT(errorMessage([] { resolveProblem("pandas_desk"); }),
              HasSubstr("\"pandas_desk\" is neither a problem file, a built-in problem nor a built-in robot; built-in problems: panda_desk"));
  EXPECT_THAT(errorMessage([] { resolveProblem("pandas_desk"); }), HasSubstr("built-in robots: iiwa14, panda, tx90, ur5, yumi"));
  // The robot names --robot takes name their desk problems wherever a problem is asked for.
  for (const std::string robot : {"panda", "ur5", "iiwa14", "tx90", "yumi"}) {
    EXPECT_EQ(resolveProblem(robot).filename(), robot + "_desk.xml") << robot;
  }
  EXPECT_THAT(errorMessage([] { resolveProblem("/no/such/problem.xml"); }),
              HasSubstr("/no/such/problem.xml: problem file does not exist"));
  EXPECT_THAT(errorMessage([] { builtinRobotUrdf("kuka"); }),
              HasSubstr("unknown built-in robot \"kuka\"; built-in robots: iiwa14, panda, tx90, ur5, yumi"));
}

TEST(BuiltinProblems, DataDirectoryOverrideMustExist) {
  ::setenv("LANG2MANIP_DATA", "/no/such/dir", 1);
  EXPECT_THAT(errorMessage([] { builtinDataDirectory(); }), HasSubstr("LANG2MANIP_DATA=/no/such/dir is not a directory"));
  ::unsetenv("LANG2MANIP_DATA");
  EXPECT_NO_THROW(builtinDataDirectory());
}

TEST(BuiltinProblems, PaperSceneHasRealisticObjectsWithinReach) {
  const KauthamProblem problem = readKauthamProblem(resolveProblem("panda_desk"));
  const Scene& scene = problem.scene;
  ASSERT_EQ(scene.robots().size(), 1U);
  const SceneObject& marker = scene.object("marker");
  const SceneObject& eraser = scene.object("eraser");
  const SceneObject& holder = scene.object("holder");
  EXPECT_NEAR(marker.dimensions().maxCoeff(), 0.13, 0.02);
  Vector3 eraserSize = eraser.dimensions();
  std::sort(eraserSize.data(), eraserSize.data() + 3);
  EXPECT_TRUE(eraserSize.isApprox(Vector3(0.015, 0.02, 0.05), 0.3)) << eraserSize.transpose();
  EXPECT_EQ(holder.role, ObjectRole::kContainer);
  ASSERT_TRUE(holder.cavity.has_value());
  // ~8 cm inner diameter: the cavity box lies inside the inner circle, the walls just outside it.
  EXPECT_GT(holder.cavity->sizes().x(), 0.05);
  EXPECT_LE(holder.cavity->sizes().head<2>().norm(), 0.085);
  EXPECT_NEAR(holder.dimensions().x(), 0.085, 0.01);
  EXPECT_NEAR(holder.dimensions().z(), 0.10, 0.02);
  EXPECT_TRUE(marker.movable && eraser.movable);
  EXPECT_EQ(scene.object("desk").role, ObjectRole::kSupport);
  const Vector3 base = scene.robots()[0].basePose.translation();
  for (const SceneObject* object : {&marker, &eraser, &holder}) {
    const Vector3 offset = object->pose.translation() - base;
    const double reach = offset.head<2>().norm();
    EXPECT_GT(reach, 0.3) << object->name;
    EXPECT_LT(reach, 0.65) << object->name;
    // Resting on the desk top: the object's lowest point is at the desk's highest point.
    EXPECT_NEAR(object->worldBounds().min().z(), scene.object("desk").worldBounds().max().z(), 0.002)
        << object->name;
  }
}

/// True when `link` has a visual cylinder (a joint drum) along the line through `point` in the
/// direction `axis` (both in the link's frame).
bool hasDrumOn(const Link& link, const Vector3& point, const Vector3& axis) {
  for (const Shape& shape : link.visuals) {
    if (!std::holds_alternative<Cylinder>(shape.geometry)) continue;
    const Vector3 direction = shape.origin.linear().col(2);
    const Vector3 offset = shape.origin.translation() - point;
    if (std::abs(direction.dot(axis)) > 0.999 && (offset - offset.dot(axis) * axis).norm() < 1e-3) return true;
  }
  return false;
}

TEST(BuiltinRobots, LookLikeTheArmsNotTheirCollisionCapsules) {
  for (const std::string& name : builtinRobotNames()) {
    SCOPED_TRACE(name);
    const RobotModelPtr robot = readUrdfFile(builtinRobotUrdf(name));
    std::size_t visuals = 0;
    std::size_t collisions = 0;
    for (const Link& link : robot->links()) {
      visuals += link.visuals.size();
      collisions += link.collisions.size();
      for (const Shape& shape : link.visuals) EXPECT_TRUE(shape.material.has_value()) << link.name << ": the maker's colours";
    }
    EXPECT_GT(visuals, collisions) << "drums and caps besides the tubes";
    // A drum on every revolute joint of the arm: on its axis, in the link before or after it.
    int revolute = 0;
    int drummed = 0;
    for (const Joint& joint : robot->joints()) {
      if (joint.type != JointType::kRevolute) continue;
      ++revolute;
      const Link& parent = robot->links()[static_cast<std::size_t>(robot->linkIndex(joint.parentLink))];
      const Link& child = robot->links()[static_cast<std::size_t>(robot->linkIndex(joint.childLink))];
      if (hasDrumOn(child, Vector3::Zero(), joint.axis) ||
          hasDrumOn(parent, joint.origin.translation(), joint.origin.linear() * joint.axis)) {
        ++drummed;
      }
    }
    EXPECT_GE(drummed, revolute * 3 / 4) << drummed << " of " << revolute << " joints drawn as drums";
  }
}

}  // namespace
}  // namespace lang2manip
