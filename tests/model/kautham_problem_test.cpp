// Kautham problems written into a temporary directory: query forms and the control -> joint
// formula. Every expected joint value is computed by hand from kautham-format.md:
//   p_d = clamp(sum_j eigValue_j * k_dj * (c_j - 0.5) + offset_d, 0, 1)  (offset 0.5 by default)
//   q_d = lower + p_d * (upper - lower)  (continuous joints: lower = -2 pi, upper = 2 pi)
#include "lang2manip/model/kautham_problem.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numbers>

#include "kautham_test_support.hpp"
#include "lang2manip/model/kautham_dof_target.hpp"
#include "lang2manip/model/urdf_reader.hpp"

namespace lang2manip {
namespace {

using test::controlSet;
using test::oldQuery;
using test::plannerWithQueries;
using test::simpleControl;
using ::testing::ElementsAre;
using ::testing::ElementsAreArray;

constexpr double kProblemTolerance = 1e-9;

std::string robotXml(const std::string& inner = "", const std::string& reference = "robots/arm.urdf",
                     const std::string& scale = "1.0") {
  return "  <Robot robot=\"" + reference + "\" scale=\"" + scale + "\">\n" + inner + "  </Robot>\n";
}

/// Configuration of robot `robot` for control values `controls`.
VectorX configurationFor(const KauthamProblem& problem, const std::vector<double>& controls,
                         std::size_t robot = 0) {
  return robotStatesFromControls(problem, controls, "test values").configurations.at(robot);
}

/// Value of joint `joint` of robot `robot` in `q`.
double jointValue(const KauthamProblem& problem, const VectorX& q, const std::string& joint,
                  std::size_t robot = 0) {
  return q[problem.scene.robots().at(robot).model->variableIndex(joint)];
}

class KauthamProblemTest : public test::KauthamDirectoryTest {
 protected:
  void SetUp() override {
    writeModel("robots/arm.urdf", test::armUrdf());
    writeModel("robots/hand.urdf", test::mimicHandUrdf());
    writeModel("obstacles/crate.urdf", test::boxUrdf("crate_model", "0.1 0.1 0.1"));
  }
};

TEST(KauthamModelSearch, ModelsAreFoundInTheModelsDirectoryOfTheProblemsDirectoryOrAnyAboveIt) {
  // A user's project: problems/ beside models/ (one level up), and Kautham's own layout,
  // demos/<set>/<scene>/ under demos/models/ (two levels up); references stay "robots/...".
  for (const char* problemDirectory : {"project/problems", "demos/set/scene"}) {
    SCOPED_TRACE(problemDirectory);
    const test::TempDirectory directory;
    const std::filesystem::path problem = directory.path() / problemDirectory / "problem.xml";
    const std::filesystem::path models = std::string(problemDirectory).rfind("project", 0) == 0
                                             ? directory.path() / "project" / "models"
                                             : directory.path() / "demos" / "models";
    test::writeText(models / "robots" / "arm.urdf", test::armUrdf());
    test::writeText(models / "obstacles" / "crate.urdf", test::boxUrdf("crate_model", "0.1 0.1 0.1"));
    test::writeText(problem, test::problemXml(robotXml() + "  <Obstacle obstacle=\"obstacles/crate.urdf\"/>\n"));
    const KauthamProblem read = readKauthamProblem(problem, {});
    EXPECT_EQ(read.scene.robots().size(), 1u);
    EXPECT_EQ(read.scene.objects().size(), 1u);
  }
}

TEST_F(KauthamProblemTest, OldQueryFormKeepsSeveralInitGoalPairsAndQueriesInOrder) {
  writeControls("arm.cntr", controlSet(simpleControl("a", "arm/upper") + simpleControl("b", "arm/fore")));
  writeProblem(robotXml() + "  <Controls robot=\"controls/arm.cntr\"/>\n" +
               plannerWithQueries("      <Query><Init>0.1 0.2</Init><Goal>0.3 0.4</Goal>\n"
                                  "             <Init>0.5 0.6</Init><Goal>0.7 0.8</Goal></Query>\n" +
                                  oldQuery("1 0", "0 1")));
  const KauthamProblem problem = read();
  ASSERT_EQ(problem.queries.size(), 3U);
  EXPECT_THAT(problem.queries[0].init, ElementsAre(0.1, 0.2));
  EXPECT_THAT(problem.queries[0].goal, ElementsAre(0.3, 0.4));
  EXPECT_THAT(problem.queries[1].init, ElementsAre(0.5, 0.6));
  EXPECT_THAT(problem.queries[1].goal, ElementsAre(0.7, 0.8));
  EXPECT_THAT(problem.queries[2].init, ElementsAre(1.0, 0.0));
  EXPECT_TRUE(problem.queries[0].obstacles.empty());
  EXPECT_EQ(problem.name, "test");
  EXPECT_EQ(problem.file, problemFile());
}

TEST_F(KauthamProblemTest, NewQueryFormIsReorderedToTheControlFileOrder) {
  writeControls("arm.cntr",
                controlSet(simpleControl("first", "arm/upper") + simpleControl("second", "arm/fore") +
                           simpleControl("third", "arm/slider")));
  writeControls("crates.cntr",
                controlSet(simpleControl("crate/x", "crate/X") + simpleControl("crate/y", "crate/Y")));
  const std::string crate =
      "  <Obstacle obstacle=\"obstacles/crate.urdf\"><KauthamName name=\"crate\"/>\n"
      "    <Limits name=\"X\" min=\"0\" max=\"1\"/><Limits name=\"Y\" min=\"0\" max=\"1\"/>\n"
      "  </Obstacle>\n";
  writeProblem(robotXml() + crate +
               "  <Controls robot=\"controls/arm.cntr\" obstacle=\"controls/crates.cntr\"/>\n" +
               plannerWithQueries("      <Query>\n"
                                  "        <ObstacleControl name=\"crate/y\" default=\"0.9\"/>\n"
                                  "        <RobotControl name=\"third\" init=\"0.3\" goal=\"0.33\"/>\n"
                                  "        <RobotControl name=\"first\" init=\"0.1\" goal=\"0.11\"/>\n"
                                  "        <RobotControl name=\"second\" init=\"0.2\" goal=\"0.22\"/>\n"
                                  "      </Query>\n"));
  const KauthamProblem problem = read();
  ASSERT_EQ(problem.queries.size(), 1U);
  EXPECT_THAT(problem.queries[0].init, ElementsAre(0.1, 0.2, 0.3));
  EXPECT_THAT(problem.queries[0].goal, ElementsAre(0.11, 0.22, 0.33));
  // crate/x is not given: it defaults to 0.5.
  EXPECT_THAT(problem.queries[0].obstacles, ElementsAre(0.5, 0.9));
}

TEST_F(KauthamProblemTest, OldQueryFormReadsInitObsAndObstacleSamplesDefaultToHalf) {
  writeControls("arm.cntr", controlSet(simpleControl("a", "arm/upper")));
  writeControls("crates.cntr",
                controlSet(simpleControl("crate/x", "crate/X") + simpleControl("crate/y", "crate/Y")));
  const std::string crate =
      "  <Obstacle obstacle=\"obstacles/crate.urdf\"><KauthamName name=\"crate\"/>\n"
      "    <Limits name=\"X\" min=\"0\" max=\"1\"/><Limits name=\"Y\" min=\"0\" max=\"1\"/>\n"
      "  </Obstacle>\n";
  writeProblem(robotXml() + crate +
               "  <Controls robot=\"controls/arm.cntr\" obstacle=\"controls/crates.cntr\"/>\n" +
               plannerWithQueries(
                   "      <Query><InitObs>0.25 0.75</InitObs><Init>0.1</Init><Goal>0.2</Goal></Query>\n" +
                   oldQuery("0.3", "0.4")));
  const KauthamProblem problem = read();
  ASSERT_EQ(problem.queries.size(), 2U);
  EXPECT_THAT(problem.queries[0].obstacles, ElementsAre(0.25, 0.75));
  EXPECT_THAT(problem.queries[1].obstacles, ElementsAre(0.5, 0.5));
}

TEST_F(KauthamProblemTest, CoupledControlsWithOffsetsEigValuesAndNegativeCoefficientsAreClamped) {
  writeControls("arm.cntr", controlSet(R"(  <Offset>
    <DOF name="arm/upper" value="0.3"/>
    <DOF name="arm/fore" value="0.6"/>
  </Offset>
  <Control name="reach" eigValue="0.8">
    <DOF name="arm/upper" value="1.0"/>
    <DOF name="arm/fore" value="-0.5"/>
  </Control>
  <Control name="twist" eigValue="2">
    <DOF name="arm/fore" value="0.25"/>
    <DOF name="arm/slider" value="-1"/>
  </Control>
)"));
  writeProblem(robotXml() + "  <Controls robot=\"controls/arm.cntr\"/>\n" +
               plannerWithQueries(oldQuery("0.9 0.3", "0.1 1.0")));
  const KauthamProblem problem = read();
  const VectorX init = configurationFor(problem, problem.queries[0].init);
  // upper:  p = 0.3 + 0.8*1*(0.9-0.5) = 0.62                          q = -1 + 0.62*2 = 0.24
  EXPECT_NEAR(jointValue(problem, init, "shoulder"), 0.24, kProblemTolerance);
  // fore:   p = 0.6 + 0.8*(-0.5)*(0.9-0.5) + 2*0.25*(0.3-0.5) = 0.34  q = -2 + 0.34*5 = -0.3
  EXPECT_NEAR(jointValue(problem, init, "elbow"), -0.3, kProblemTolerance);
  // slider: p = 0.5 (no offset) + 2*(-1)*(0.3-0.5) = 0.9             q = 0 + 0.9*0.4 = 0.36
  EXPECT_NEAR(jointValue(problem, init, "slide"), 0.36, kProblemTolerance);
  // wheel: no DOF -> the middle of the continuous range, 0.
  EXPECT_NEAR(jointValue(problem, init, "spin"), 0.0, kProblemTolerance);

  const VectorX goal = configurationFor(problem, problem.queries[0].goal);
  // upper:  p = 0.3 + 0.8*(0.1-0.5) = -0.02 -> clamped to 0           q = -1
  EXPECT_NEAR(jointValue(problem, goal, "shoulder"), -1.0, kProblemTolerance);
  // fore:   p = 0.6 + 0.8*(-0.5)*(-0.4) + 2*0.25*0.5 = 1.01 -> 1      q = 3
  EXPECT_NEAR(jointValue(problem, goal, "elbow"), 3.0, kProblemTolerance);
  // slider: p = 0.5 + 2*(-1)*0.5 = -0.5 -> 0                          q = 0
  EXPECT_NEAR(jointValue(problem, goal, "slide"), 0.0, kProblemTolerance);
}

TEST_F(KauthamProblemTest, OffsetWithoutControlPlacesTheJoint) {
  writeControls("arm.cntr", controlSet("  <Offset><DOF name=\"arm/fore\" value=\"0.1\"/></Offset>\n" +
                                       simpleControl("a", "arm/upper")));
  writeProblem(robotXml() + "  <Controls robot=\"controls/arm.cntr\"/>\n" +
               plannerWithQueries(oldQuery("0.5", "0.5")));
  const KauthamProblem problem = read();
  // fore: p = 0.1 -> q = -2 + 0.1*5 = -1.5
  EXPECT_NEAR(jointValue(problem, configurationFor(problem, {0.5}), "elbow"), -1.5, kProblemTolerance);
}

TEST_F(KauthamProblemTest, ContinuousJointsMapOverPlusMinusTwoPi) {
  writeControls("arm.cntr", controlSet(simpleControl("spin", "arm/wheel")));
  writeProblem(robotXml() + "  <Controls robot=\"controls/arm.cntr\"/>\n" +
               plannerWithQueries(oldQuery("0.9", "0.1")));
  const KauthamProblem problem = read();
  // q = -2 pi + 0.9 * 4 pi = 1.6 pi (beyond the model's own +-pi range).
  EXPECT_NEAR(jointValue(problem, configurationFor(problem, {0.9}), "spin"), 1.6 * std::numbers::pi, kProblemTolerance);
  // q = -2 pi + 0.1 * 4 pi = -1.6 pi
  EXPECT_NEAR(jointValue(problem, configurationFor(problem, {0.1}), "spin"), -1.6 * std::numbers::pi, kProblemTolerance);
}

TEST(KauthamJointRange, LimitsOrPlusMinusTwoPiForContinuousJoints) {
  const RobotModelPtr arm = readUrdfString(test::armUrdf(), "arm.urdf", ".");
  const auto range = [&](const char* joint) { return kauthamJointRange(*arm, arm->variableIndex(joint)); };
  EXPECT_EQ(range("elbow"), std::make_pair(-2.0, 3.0));
  EXPECT_EQ(range("slide"), std::make_pair(0.0, 0.4));
  EXPECT_EQ(range("spin"), std::make_pair(-2.0 * std::numbers::pi, 2.0 * std::numbers::pi));
}

TEST_F(KauthamProblemTest, SafetyControllerSoftLimitsReplaceTheUrdfLimits) {
  // test::twoJointUrdf(): elbow (child "tip") has <limit> [-2, 2] and soft limits [-1.9, 1.8].
  writeModel("robots/soft.urdf", test::twoJointUrdf());
  writeControls("soft.cntr", controlSet(simpleControl("e", "arm/tip")));
  writeProblem(robotXml("", "robots/soft.urdf") + "  <Controls robot=\"controls/soft.cntr\"/>\n" +
               plannerWithQueries(oldQuery("0.25", "1")));
  const KauthamProblem problem = read();
  // q = -1.9 + 0.25 * (1.8 + 1.9) = -0.975; goal: 1.8.
  EXPECT_NEAR(jointValue(problem, configurationFor(problem, {0.25}), "elbow"), -0.975, kProblemTolerance);
  EXPECT_NEAR(jointValue(problem, configurationFor(problem, {1.0}), "elbow"), 1.8, kProblemTolerance);
}

TEST_F(KauthamProblemTest, ScaleMultipliesPrismaticLimitsButNotRevoluteOnes) {
  writeControls("arm.cntr", controlSet(simpleControl("s", "arm/slider") + simpleControl("u", "arm/upper")));
  writeProblem(robotXml("", "robots/arm.urdf", "2.0") + "  <Controls robot=\"controls/arm.cntr\"/>\n" +
               plannerWithQueries(oldQuery("1 1", "0 0")));
  const KauthamProblem problem = read();
  const VectorX q = configurationFor(problem, {1.0, 0.75});
  EXPECT_NEAR(jointValue(problem, q, "slide"), 0.8, kProblemTolerance);     // 0 + 1*(2*0.4)
  EXPECT_NEAR(jointValue(problem, q, "shoulder"), 0.5, kProblemTolerance);  // -1 + 0.75*2
  EXPECT_DOUBLE_EQ(problem.robots[0].scale, 2.0);
}

TEST_F(KauthamProblemTest, HomeIsATranslationAndAnAxisAngleRotation) {
  writeProblem(
      robotXml("    <Home X=\"1\" Y=\"2\" Z=\"3\" WX=\"0\" WY=\"0\" WZ=\"1\" "
               "TH=\"1.5707963267948966\"/>\n"));
  const KauthamProblem problem = read();
  const Pose& X_WB = problem.scene.robots()[0].basePose;
  EXPECT_TRUE(X_WB.translation().isApprox(Vector3(1, 2, 3), kProblemTolerance));
  // A quarter turn about z takes x to y.
  EXPECT_TRUE((X_WB.linear() * Vector3::UnitX()).isApprox(Vector3::UnitY(), kProblemTolerance));
  EXPECT_TRUE(problem.robots[0].home.isApprox(X_WB, kProblemTolerance));
}

TEST_F(KauthamProblemTest, AllZeroHomeAxisIsTheIdentityWhateverTheAngle) {
  writeProblem(
      robotXml("    <Home TH=\"1.0\" WZ=\"0.0\" WY=\"0.0\" WX=\"0.0\" Z=\"0.01\" Y=\"0.0\" X=\"0.0\"/>\n"));
  const Pose X_WB = read().scene.robots()[0].basePose;
  EXPECT_TRUE(X_WB.linear().isApprox(Matrix3::Identity(), kProblemTolerance));
  EXPECT_TRUE(X_WB.translation().isApprox(Vector3(0, 0, 0.01), kProblemTolerance));
}

TEST_F(KauthamProblemTest, HomeAxisIsNotNormalisedBeforeBuildingTheQuaternion) {
  // Kautham: q = (cos(TH/2), axis * sin(TH/2)), then normalised as a quaternion. Axis (0,0,2),
  // TH = pi/2: q ~ (1, 0, 0, 2) / sqrt(5): cos(angle) = w^2 - z^2 = -3/5, sin(angle) = 2wz = 4/5.
  writeProblem(robotXml("    <Home WX=\"0\" WY=\"0\" WZ=\"2\" TH=\"1.5707963267948966\"/>\n"));
  const Pose X_WB = read().scene.robots()[0].basePose;
  EXPECT_TRUE((X_WB.linear() * Vector3::UnitX()).isApprox(Vector3(-0.6, 0.8, 0), kProblemTolerance));
}

TEST_F(KauthamProblemTest, KauthamNameRenamesTheRobotAndItsDofs) {
  writeControls("arm.cntr", controlSet(simpleControl("a", "lefty/upper")));
  writeProblem(robotXml("    <KauthamName name=\"lefty\"/>\n") +
               "  <Controls robot=\"controls/arm.cntr\"/>\n" + plannerWithQueries(oldQuery("0.75", "0.25")));
  const KauthamProblem problem = read();
  EXPECT_EQ(problem.scene.robots()[0].name, "lefty");
  EXPECT_EQ(problem.robots[0].name, "lefty");
  EXPECT_EQ(problem.robots[0].reference, "robots/arm.urdf");
  EXPECT_EQ(problem.robots[0].resolvedPath, (root() / "models" / "robots" / "arm.urdf").lexically_normal());
  // -1 + 0.75*2 = 0.5
  EXPECT_NEAR(jointValue(problem, configurationFor(problem, {0.75}), "shoulder"), 0.5, kProblemTolerance);
}

TEST_F(KauthamProblemTest, BaseXYZControlsTranslateInTheHomeFrame) {
  writeControls("arm.cntr", controlSet("  <Offset><DOF name=\"arm/X1\" value=\"0\"/><DOF name=\"arm/X2\" value=\"0\"/>"
                                       "<DOF name=\"arm/X3\" value=\"0\"/></Offset>\n" +
                                       simpleControl("x", "arm/X") + simpleControl("y", "arm/Y")));
  writeProblem(robotXml("    <Limits name=\"X\" min=\"-1\" max=\"1\"/>\n"
                        "    <Limits name=\"Y\" min=\"0\" max=\"2\"/>\n"
                        "    <Limits name=\"Z\" min=\"0.5\" max=\"0.5\"/>\n"
                        "    <Home X=\"1\" Y=\"2\" Z=\"3\" WZ=\"1\" TH=\"1.5707963267948966\"/>\n") +
               "  <Controls robot=\"controls/arm.cntr\"/>\n" +
               plannerWithQueries(oldQuery("0.75 0.25", "0 1")));
  const KauthamProblem problem = read();
  // x = -1 + 0.75*2 = 0.5, y = 0 + 0.25*2 = 0.5, z = 0.5 (min = max).
  // X_WB = Home * T(x, y, z): (1,2,3) + Rz(pi/2) (0.5, 0.5, 0.5) = (1 - 0.5, 2 + 0.5, 3 + 0.5).
  const Pose& X_WB = problem.scene.robots()[0].basePose;
  EXPECT_TRUE(X_WB.translation().isApprox(Vector3(0.5, 2.5, 3.5), kProblemTolerance));
  EXPECT_TRUE((X_WB.linear() * Vector3::UnitX()).isApprox(Vector3::UnitY(), kProblemTolerance));
  // Goal: x = -1, y = 2 -> (1,2,3) + Rz(pi/2) (-1, 2, 0.5) = (1 - 2, 2 - 1, 3.5).
  const Pose goal = robotStatesFromControls(problem, {0.0, 1.0}, "goal").basePoses[0];
  EXPECT_TRUE(goal.translation().isApprox(Vector3(-1, 1, 3.5), kProblemTolerance));
  EXPECT_THAT(problem.robots[0].limits.x, ::testing::Optional(std::pair{-1.0, 1.0}));
}

TEST_F(KauthamProblemTest, UnnamedRotationDofsOfAMovingBaseTakeKauthamsDefaultOffset) {
  writeControls("arm.cntr", controlSet(simpleControl("x", "arm/X")));
  writeProblem(robotXml("    <Limits name=\"X\" min=\"0\" max=\"2\"/>\n") +
               "  <Controls robot=\"controls/arm.cntr\"/>\n" + plannerWithQueries(oldQuery("0.5", "0.5")));
  const Pose X_WB = read().scene.robots()[0].basePose;
  // X1 = X2 = X3 = 0.5: qx = sqrt(.5) sin(pi) = 0, qy = sqrt(.5) cos(pi) = -sqrt(.5),
  // qz = sqrt(.5) sin(pi/2) = sqrt(.5), qw = sqrt(.5) cos(pi/2) = 0: a half turn about (0,-1,1)/sqrt(2).
  const Quaternion expected(0.0, 0.0, -std::sqrt(0.5), std::sqrt(0.5));
  EXPECT_TRUE(X_WB.linear().isApprox(expected.toRotationMatrix(), kProblemTolerance));
  EXPECT_TRUE(X_WB.translation().isApprox(Vector3(1, 0, 0), kProblemTolerance));
}

TEST_F(KauthamProblemTest, X3IsAYawOfTwoPiX3AfterTheTranslation) {
  writeControls("arm.cntr", controlSet(R"(  <Offset>
    <DOF name="arm/X1" value="0"/><DOF name="arm/X2" value="0"/><DOF name="arm/X3" value="0.25"/>
  </Offset>
)" + simpleControl("x", "arm/X")));
  writeProblem(robotXml("    <Limits name=\"X\" min=\"0\" max=\"2\"/>\n"
                        "    <Home X=\"1\" WZ=\"1\" TH=\"1.5707963267948966\"/>\n") +
               "  <Controls robot=\"controls/arm.cntr\"/>\n" + plannerWithQueries(oldQuery("0.25", "0.25")));
  const Pose X_WB = read().scene.robots()[0].basePose;
  // x = 0 + 0.25*2 = 0.5: (1,0,0) + Rz(pi/2) (0.5, 0, 0) = (1, 0.5, 0); yaw pi/2 + 2 pi*0.25 = pi.
  EXPECT_TRUE(X_WB.translation().isApprox(Vector3(1, 0.5, 0), kProblemTolerance));
  EXPECT_TRUE((X_WB.linear() * Vector3::UnitX()).isApprox(-Vector3::UnitX(), kProblemTolerance));
  EXPECT_TRUE((X_WB.linear() * Vector3::UnitZ()).isApprox(Vector3::UnitZ(), kProblemTolerance));
}

TEST_F(KauthamProblemTest, X1X2X3UseTheUniformQuaternionMap) {
  // X1 = 1, X2 = 0.25: qx = sin(pi/2) = 1, qy = cos(pi/2) = 0, qz = qw = 0: a half turn about x.
  writeControls("arm.cntr",
                controlSet(R"(  <Offset><DOF name="arm/X1" value="1"/><DOF name="arm/X2" value="0.25"/>
    <DOF name="arm/X3" value="0"/></Offset>
)" + simpleControl("u", "arm/upper")));
  writeProblem(robotXml() + "  <Controls robot=\"controls/arm.cntr\"/>\n" +
               plannerWithQueries(oldQuery("0.5", "0.5")));
  const Pose X_WB = read().scene.robots()[0].basePose;
  EXPECT_TRUE((X_WB.linear() * Vector3::UnitX()).isApprox(Vector3::UnitX(), kProblemTolerance));
  EXPECT_TRUE((X_WB.linear() * Vector3::UnitY()).isApprox(-Vector3::UnitY(), kProblemTolerance));
  EXPECT_TRUE((X_WB.linear() * Vector3::UnitZ()).isApprox(-Vector3::UnitZ(), kProblemTolerance));
  EXPECT_TRUE(X_WB.translation().isZero(kProblemTolerance));
}

TEST_F(KauthamProblemTest, ControlledX3YawsFromItsOffset) {
  // X1 = X2 = 0, X3: p = 0.5 + (0.625 - 0.5) = 0.625 -> yaw 2 pi * 0.625 = 1.25 pi.
  writeControls("arm.cntr",
                controlSet(R"(  <Offset><DOF name="arm/X1" value="0"/><DOF name="arm/X2" value="0"/></Offset>
)" + simpleControl("yaw", "arm/X3")));
  writeProblem(robotXml() + "  <Controls robot=\"controls/arm.cntr\"/>\n" +
               plannerWithQueries(oldQuery("0.625", "0.5")));
  const Pose X_WB = read().scene.robots()[0].basePose;
  const double half = std::sqrt(0.5);
  EXPECT_TRUE((X_WB.linear() * Vector3::UnitX()).isApprox(Vector3(-half, -half, 0), kProblemTolerance));
}

TEST_F(KauthamProblemTest, RobotWhoseControlsMoveNoBaseDofStaysAtHomeDespiteLimits) {
  // Kautham moves a base only when the control file names one of its X..X3 DOFs.
  writeControls("arm.cntr", controlSet(simpleControl("u", "arm/upper")));
  writeProblem(robotXml("    <Limits name=\"X\" min=\"0\" max=\"2\"/>\n    <Home X=\"1\"/>\n") +
               "  <Controls robot=\"controls/arm.cntr\"/>\n" + plannerWithQueries(oldQuery("0.5", "0.5")));
  const Pose X_WB = read().scene.robots()[0].basePose;
  EXPECT_TRUE(X_WB.translation().isApprox(Vector3(1, 0, 0), kProblemTolerance));
}

TEST_F(KauthamProblemTest, EmptyRobotControlsGiveOneControlPerJointAndPerMovableBaseAxis) {
  writeProblem(robotXml("    <Limits name=\"X\" min=\"0\" max=\"2\"/>\n"
                        "    <Limits name=\"Z\" min=\"1\" max=\"1\"/>\n") +
               "  <Controls robot=\"\"/>\n" +
               plannerWithQueries(oldQuery("0.25 0.75 0.5 0.5 1", "0.5 0.5 0.5 0.5 0.5")));
  const KauthamProblem problem = read();
  // Z has min = max: no control for it.
  EXPECT_THAT(problem.robotControls.controlNames(),
              ElementsAre("arm/X", "arm/upper", "arm/fore", "arm/wheel", "arm/slider"));
  EXPECT_TRUE(problem.robotControls.source.empty());
  const RobotStates states = robotStatesFromControls(problem, problem.queries[0].init, "init");
  // x = 0 + 0.25*2 = 0.5, z = 1 (min = max), no Y limits -> 0.
  EXPECT_TRUE(states.basePoses[0].translation().isApprox(Vector3(0.5, 0, 1), kProblemTolerance));
  EXPECT_NEAR(jointValue(problem, states.configurations[0], "shoulder"), 0.5, kProblemTolerance);  // -1 + 0.75*2
  EXPECT_NEAR(jointValue(problem, states.configurations[0], "slide"), 0.4, kProblemTolerance);     // 0 + 1*0.4
}

TEST_F(KauthamProblemTest, MissingControlsAndQueriesPlaceTheRobotAtTheMiddleOfItsRanges) {
  writeProblem(robotXml());
  const KauthamProblem problem = read();
  EXPECT_EQ(problem.robotControls.controls.size(), 4U);
  EXPECT_TRUE(problem.queries.empty());
  const VectorX& q = problem.scene.robots()[0].configuration;
  EXPECT_NEAR(jointValue(problem, q, "shoulder"), 0.0, kProblemTolerance);  // (-1 + 1) / 2
  EXPECT_NEAR(jointValue(problem, q, "elbow"), 0.5, kProblemTolerance);     // (-2 + 3) / 2
  EXPECT_NEAR(jointValue(problem, q, "slide"), 0.2, kProblemTolerance);     // (0 + 0.4) / 2
}

TEST_F(KauthamProblemTest, SceneHoldsTheRobotsAtTheFirstQueryInit) {
  writeControls("arm.cntr", controlSet(simpleControl("a", "arm/upper") + simpleControl("b", "arm/fore")));
  writeProblem(robotXml() + "  <Controls robot=\"controls/arm.cntr\"/>\n" +
               plannerWithQueries(oldQuery("0.25 1", "0 0") + oldQuery("1 1", "0 0")));
  const KauthamProblem problem = read();
  const VectorX& q = problem.scene.robots()[0].configuration;
  EXPECT_NEAR(jointValue(problem, q, "shoulder"), -0.5, kProblemTolerance);  // -1 + 0.25*2
  EXPECT_NEAR(jointValue(problem, q, "elbow"), 3.0, kProblemTolerance);      // -2 + 1*5
}

TEST_F(KauthamProblemTest, MimicTagsAreIgnoredSoEachCoupledFingerFollowsTheFormula) {
  writeControls("hand.cntr", controlSet(R"(  <Control name="grip" eigValue="1.0">
    <DOF name="hand/left" value="1.0"/>
    <DOF name="hand/right" value="-1.0"/>
  </Control>
)"));
  writeProblem(robotXml("", "robots/hand.urdf") + "  <Controls robot=\"controls/hand.cntr\"/>\n" +
               plannerWithQueries(oldQuery("0.75", "0.25")));
  const KauthamProblem problem = read();
  EXPECT_EQ(problem.scene.robots()[0].model->variableCount(), 2);
  const VectorX q = configurationFor(problem, {0.75});
  // left:  p = 0.5 + 1*(0.75-0.5) = 0.75  -> -0.5 + 0.75*1 = 0.25
  EXPECT_NEAR(jointValue(problem, q, "left_joint"), 0.25, kProblemTolerance);
  // right: p = 0.5 - 1*(0.75-0.5) = 0.25  -> -0.4 + 0.25*1 = -0.15 (the mimic would give -0.25)
  EXPECT_NEAR(jointValue(problem, q, "right_joint"), -0.15, kProblemTolerance);
}

TEST_F(KauthamProblemTest, SeveralRobotsAreMappedIndependently) {
  writeControls("arms.cntr", controlSet(simpleControl("l", "left/upper") + simpleControl("r", "right/fore") +
                                        simpleControl("rx", "right/X")));
  writeProblem(robotXml("    <KauthamName name=\"left\"/>\n    <Home X=\"-1\"/>\n") +
               robotXml("    <KauthamName name=\"right\"/>\n    <Home X=\"1\"/>\n"
                        "    <Limits name=\"X\" min=\"0\" max=\"1\"/>\n") +
               "  <Controls robot=\"controls/arms.cntr\"/>\n" +
               plannerWithQueries(oldQuery("1 0 0.5", "0 1 1")));
  const KauthamProblem problem = read();
  ASSERT_EQ(problem.scene.robots().size(), 2U);
  EXPECT_EQ(problem.scene.robots()[1].name, "right");
  const RobotStates goal = robotStatesFromControls(problem, problem.queries[0].goal, "goal");
  EXPECT_NEAR(jointValue(problem, goal.configurations[0], "shoulder", 0), -1.0, kProblemTolerance);  // p = 0
  EXPECT_NEAR(jointValue(problem, goal.configurations[0], "elbow", 0), 0.5, kProblemTolerance);      // middle
  EXPECT_NEAR(jointValue(problem, goal.configurations[1], "shoulder", 1), 0.0, kProblemTolerance);   // middle
  EXPECT_NEAR(jointValue(problem, goal.configurations[1], "elbow", 1), 3.0, kProblemTolerance);      // p = 1
  EXPECT_TRUE(goal.basePoses[0].translation().isApprox(Vector3(-1, 0, 0), kProblemTolerance));
  EXPECT_TRUE(goal.basePoses[1].translation().isApprox(Vector3(2, 0, 0), kProblemTolerance));  // 1 + 1
}

TEST_F(KauthamProblemTest, ModelDirectoriesFromTheOptionsAreTriedLast) {
  test::writeText(root() / "elsewhere" / "robots" / "other.urdf", test::armUrdf("other"));
  writeProblem(robotXml("", "robots/other.urdf"));
  KauthamReadOptions options;
  options.modelDirectories = {root() / "elsewhere"};
  const KauthamProblem problem = read(options);
  EXPECT_EQ(problem.scene.robots()[0].name, "other");
  EXPECT_EQ(problem.robots[0].resolvedPath,
            (root() / "elsewhere" / "robots" / "other.urdf").lexically_normal());
}

TEST_F(KauthamProblemTest, PlannerBlockIsKeptVerbatimInFileOrder) {
  writeProblem(robotXml() + R"xml(  <Planner>
    <Parameters>
      <Name> omplRRTConnect </Name>
      <Parameter name="Range">0.1</Parameter>
      <Parameter name="Speed Factor">1</Parameter>
      <Parameter name="_Max Planning Time">10.0</Parameter>
      <Parameter name="Sampler 0(r) 1(h) 2(sdk) 3(g)">2</Parameter>
    </Parameters>
  </Planner>
)xml");
  const KauthamProblem problem = read();
  EXPECT_EQ(problem.planner.name, "omplRRTConnect");
  using Parameter = std::pair<std::string, std::string>;
  EXPECT_THAT(problem.planner.parameters,
              ElementsAreArray({Parameter{"Range", "0.1"}, Parameter{"Speed Factor", "1"},
                                Parameter{"_Max Planning Time", "10.0"},
                                Parameter{"Sampler 0(r) 1(h) 2(sdk) 3(g)", "2"}}));
}

}  // namespace
}  // namespace lang2manip
