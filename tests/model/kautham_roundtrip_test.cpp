#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lang2manip/core/rotation.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "model_test_support.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;

void expectSamePose(const Pose& a, const Pose& b, const std::string& what) {
  EXPECT_TRUE(a.translation().isApprox(b.translation(), 1e-9) ||
              (a.translation() - b.translation()).norm() < 1e-12)
      << what << ": " << a.translation().transpose() << " vs " << b.translation().transpose();
  EXPECT_TRUE(a.linear().isApprox(b.linear(), 1e-9)) << what;
}

void expectSameShapes(const std::vector<Shape>& a, const std::vector<Shape>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(geometryKindName(a[i].geometry), geometryKindName(b[i].geometry)) << what;
    expectSamePose(a[i].origin, b[i].origin, what + " shape " + std::to_string(i));
    EXPECT_TRUE(shapeBounds(a[i]).min().isApprox(shapeBounds(b[i]).min(), 1e-9) ||
                (shapeBounds(a[i]).min() - shapeBounds(b[i]).min()).norm() < 1e-12)
        << what;
    EXPECT_EQ(a[i].material.has_value(), b[i].material.has_value()) << what;
  }
}

// The Scene read back must equal the Scene written: robots, objects, attachments.
void expectSameScene(const Scene& written, const Scene& read) {
  ASSERT_EQ(written.robots().size(), read.robots().size());
  for (std::size_t r = 0; r < written.robots().size(); ++r) {
    const SceneRobot& a = written.robots()[r];
    const SceneRobot& b = read.robots()[r];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.model->variableNames(), b.model->variableNames());
    expectSamePose(a.basePose, b.basePose, "robot " + a.name);
    EXPECT_TRUE(a.configuration.isApprox(b.configuration, 1e-9))
        << a.configuration.transpose() << "\nvs\n" << b.configuration.transpose();
  }
  ASSERT_EQ(written.objects().size(), read.objects().size());
  for (std::size_t o = 0; o < written.objects().size(); ++o) {
    const SceneObject& a = written.objects()[o];
    const SceneObject& b = read.objects()[o];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.movable, b.movable);
    EXPECT_EQ(a.role, b.role);
    EXPECT_EQ(a.collisionEnabled, b.collisionEnabled);
    EXPECT_EQ(a.cavity.has_value(), b.cavity.has_value());
    if (a.cavity && b.cavity) {
      EXPECT_TRUE(a.cavity->min().isApprox(b.cavity->min(), 1e-12));
    }
    expectSamePose(a.pose, b.pose, "object " + a.name);
    expectSameShapes(a.collisions, b.collisions, "object " + a.name);
    EXPECT_TRUE(a.dimensions().isApprox(b.dimensions(), 1e-9)) << a.name;
  }
  ASSERT_EQ(written.attachments().size(), read.attachments().size());
  for (std::size_t i = 0; i < written.attachments().size(); ++i) {
    EXPECT_EQ(written.attachments()[i].object, read.attachments()[i].object);
    EXPECT_EQ(written.attachments()[i].link, read.attachments()[i].link);
    expectSamePose(written.attachments()[i].linkToObject, read.attachments()[i].linkToObject, "attachment");
  }
}

SceneObject object(const std::string& name, const Geometry& geometry, const Vector3& position) {
  SceneObject result;
  result.name = name;
  result.kind = name + "_kind";
  result.collisions.push_back(Shape{geometry, makePose(Vector3(0, 0, 0.01), quaternionFromRpy(0.1, 0.2, 0.3)),
                                    std::nullopt, "part"});
  result.visuals = result.collisions;
  result.visuals[0].material = Material{"blue", Vector4(0, 0, 1, 1), ""};
  result.pose = makePose(position, quaternionFromRpy(0.0, 0.0, 0.7));
  return result;
}

TEST(KauthamRoundTrip, SceneBuiltInCodeReadsBackTheSame) {
  const test::TempDirectory directory;
  test::writeText(directory.path() / "robot" / "arm.urdf", test::twoJointUrdf());
  Scene scene;
  scene.addRobot(SceneRobot{"arm", readUrdfFile(directory.path() / "robot" / "arm.urdf"),
                            makePose(Vector3(0.1, -0.2, 0.7), quaternionFromRpy(0, 0, 1.2)),
                            Eigen::Vector2d(0.4, -1.1), {}});
  SceneObject cup = object("cup", Cylinder{0.04, 0.1}, Vector3(0.5, 0.1, 0.75));
  cup.movable = true;
  cup.role = ObjectRole::kContainer;
  cup.cavity = AlignedBox3(Vector3(-0.03, -0.03, 0.005), Vector3(0.03, 0.03, 0.1));
  scene.addObject(cup);
  SceneObject table = object("table", Box{Vector3(1.2, 0.8, 0.03)}, Vector3(0.4, 0, 0.735));
  table.role = ObjectRole::kSupport;
  table.collisionEnabled = false;
  scene.addObject(table);
  scene.addObject(object("ball", Sphere{0.03}, Vector3(0.3, 0.3, 0.8)));
  const Pose X_WTip = scene.robot("arm").basePose *
                      scene.robot("arm").model->linkPoses(scene.robot("arm").configuration)[2];
  scene.attach(Attachment{"ball", "arm", "tip", X_WTip.inverse() * scene.object("ball").pose});

  const KauthamProblem problem = kauthamProblemFromScene(scene, "roundtrip");
  const std::filesystem::path file = writeKauthamProblem(problem, directory.path() / "out", "roundtrip");
  const KauthamProblem read = readKauthamProblem(file);
  EXPECT_EQ(read.name, "roundtrip");
  expectSameScene(scene, read.scene);
}

TEST(KauthamRoundTrip, BuiltInPaperSceneReadsBackTheSame) {
  const KauthamProblem original = readKauthamProblem(resolveProblem(defaultProblemName()));
  const test::TempDirectory directory;
  const std::filesystem::path file = writeKauthamProblem(original, directory.path(), "copy");
  const KauthamProblem read = readKauthamProblem(file);
  expectSameScene(original.scene, read.scene);
  EXPECT_EQ(read.planner.name, original.planner.name);
  EXPECT_EQ(read.planner.parameters, original.planner.parameters);
  ASSERT_EQ(read.queries.size(), original.queries.size());
  for (std::size_t i = 0; i < read.queries.size(); ++i) {
    const RobotStates a = robotStatesFromControls(original, original.queries[i].goal, "goal");
    const RobotStates b = robotStatesFromControls(read, read.queries[i].goal, "goal");
    EXPECT_TRUE(a.configurations[0].isApprox(b.configurations[0], 1e-9));
  }
}

TEST(KauthamRoundTrip, EveryBuiltInProblemReadsBackTheSame) {
  for (const BuiltinProblem& builtin : builtinProblems()) {
    SCOPED_TRACE(builtin.shortName);
    const KauthamProblem original = readKauthamProblem(builtin.file);
    const test::TempDirectory directory;
    expectSameScene(original.scene, readKauthamProblem(writeKauthamProblem(original, directory.path(), "p")).scene);
  }
}

TEST(KauthamRoundTrip, WritingIntoAnUnwritableDirectoryIsAnError) {
  Scene scene;
  const KauthamProblem problem = kauthamProblemFromScene(scene, "empty");
  EXPECT_THAT(test::errorMessage([&] { writeKauthamProblem(problem, "/proc/lang2manip/x", "p"); }),
              HasSubstr("/proc/lang2manip/x"));
}

}  // namespace
}  // namespace lang2manip
