// Bad Kautham problems: each message must name the file, the line where there is one, and what
// is wrong.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "kautham_test_support.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/model/kautham_problem.hpp"

namespace lang2manip {
namespace {

using test::controlSet;
using test::fileLine;
using test::lineOf;
using test::plannerWithQueries;
using ::testing::AllOf;
using ::testing::HasSubstr;

const char* const kArmRobotElement = "  <Robot robot=\"robots/arm.urdf\"/>\n";
const char* const kArmControls = "  <Controls robot=\"controls/arm.cntr\"/>\n";

std::string twoArmControls() {
  return controlSet(
      "  <Control name=\"a\"><DOF name=\"arm/upper\" value=\"1\"/></Control>\n"
      "  <Control name=\"b\"><DOF name=\"arm/fore\" value=\"1\"/></Control>\n");
}

class KauthamBadInputTest : public test::KauthamDirectoryTest {
 protected:
  void SetUp() override {
    writeModel("robots/arm.urdf", test::armUrdf());
    writeModel("obstacles/crate.urdf", test::boxUrdf("crate_model", "0.1 0.1 0.1"));
    writeControls("arm.cntr", twoArmControls());
  }

  /// Writes a problem with the arm, its two controls and `queries`; returns the problem text.
  std::string writeQueries(const std::string& queries) const {
    return writeProblem(std::string(kArmRobotElement) + kArmControls + plannerWithQueries(queries));
  }
  /// Writes `cntr` as controls/arm.cntr under a problem using it.
  void writeArmControls(const std::string& cntr, const std::string& robotInner = "") const {
    writeControls("arm.cntr", cntr);
    writeProblem("  <Robot robot=\"robots/arm.urdf\">\n" + robotInner + "  </Robot>\n" + kArmControls);
  }
};

TEST_F(KauthamBadInputTest, MissingProblemFile) {
  EXPECT_THAT(readError(), AllOf(HasSubstr(problemFile().string()), HasSubstr("does not exist")));
}

TEST_F(KauthamBadInputTest, MalformedXmlNamesTheLine) {
  const std::string text =
      test::problemXml(std::string(kArmRobotElement) + "  <Obstacle obstacle=\"x\">\n  <Oops>\n");
  test::writeText(problemFile(), text);
  // pugixml notices the unclosed <Oops> at </Problem>.
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "</Problem>"))),
                                 HasSubstr("malformed XML"), HasSubstr("mismatch")));
}

TEST_F(KauthamBadInputTest, RootThatIsNotProblem) {
  test::writeText(problemFile(), "<?xml version=\"1.0\"?>\n<ControlSet/>\n");
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(problemFile(), 2)), HasSubstr("not <Problem>")));
}

TEST_F(KauthamBadInputTest, ProblemWithoutRobot) {
  writeProblem("  <Obstacle obstacle=\"obstacles/crate.urdf\"/>\n");
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(problemFile(), 2)), HasSubstr("no <Robot>")));
}

TEST_F(KauthamBadInputTest, ModelReferenceThatResolvesNowhereListsThePathsTried) {
  const std::string text = writeProblem("  <Robot robot=\"robots/none.urdf\"/>\n");
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "none.urdf"))),
                                 HasSubstr("\"robots/none.urdf\" resolves to no readable file"),
                                 HasSubstr((sceneDirectory() / "robots" / "none.urdf").string()),
                                 HasSubstr((root() / "models" / "robots" / "none.urdf").string())));
}

TEST_F(KauthamBadInputTest, SrdfThatResolvesNowhere) {
  const std::string text = writeProblem("  <Robot robot=\"robots/arm.urdf\">\n    <Srdf file=\"robots/missing.srdf\"/>\n  </Robot>\n");
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "missing.srdf"))),
                                 HasSubstr("SRDF file \"robots/missing.srdf\" resolves to no readable file")));
}

TEST_F(KauthamBadInputTest, ControlFileThatIsNotCntr) {
  writeControls("arm.xml", twoArmControls());
  writeProblem(std::string(kArmRobotElement) + "  <Controls robot=\"controls/arm.xml\"/>\n");
  EXPECT_THAT(readError(), AllOf(HasSubstr(controlFile("arm.xml").string()), HasSubstr(".cntr")));
}

TEST_F(KauthamBadInputTest, MissingControlFile) {
  const std::string text =
      writeProblem(std::string(kArmRobotElement) + "  <Controls robot=\"controls/none.cntr\"/>\n");
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "<Controls"))),
                                 HasSubstr("\"controls/none.cntr\" resolves to no readable file")));
}

TEST_F(KauthamBadInputTest, MalformedControlFileNamesItsLine) {
  writeArmControls("<?xml version=\"1.0\"?>\n<ControlSet>\n  <Control name=\"a\">\n</ControlSet>\n");
  EXPECT_THAT(readError(),
              AllOf(HasSubstr(fileLine(controlFile("arm.cntr"), 4)), HasSubstr("malformed XML")));
}

TEST_F(KauthamBadInputTest, DofNameWithoutSlash) {
  const std::string cntr =
      controlSet("  <Control name=\"a\">\n    <DOF name=\"upper\" value=\"1\"/>\n  </Control>\n");
  writeArmControls(cntr);
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(controlFile("arm.cntr"), lineOf(cntr, "\"upper\""))),
                                 HasSubstr("\"upper\" is not of the form")));
}

TEST_F(KauthamBadInputTest, UnknownDofNameListsTheValidDofs) {
  const std::string cntr =
      controlSet("  <Control name=\"a\">\n    <DOF name=\"arm/shoulder\" value=\"1\"/>\n  </Control>\n");
  writeArmControls(cntr);
  EXPECT_THAT(readError(),
              AllOf(HasSubstr(fileLine(controlFile("arm.cntr"), lineOf(cntr, "arm/shoulder"))),
                    HasSubstr("unknown DOF \"arm/shoulder\""),
                    HasSubstr("X, Y, Z, X1, X2, X3, upper, fore, wheel, slider"), HasSubstr("child link")));
}

TEST_F(KauthamBadInputTest, UnknownRobotInADofName) {
  const std::string cntr =
      controlSet("  <Control name=\"a\">\n    <DOF name=\"bot/upper\" value=\"1\"/>\n  </Control>\n");
  writeArmControls(cntr);
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(controlFile("arm.cntr"), lineOf(cntr, "bot/upper"))),
                                 HasSubstr("no robot named \"bot\""), HasSubstr("robots: arm")));
}

TEST_F(KauthamBadInputTest, BaseDofWithoutLimits) {
  const std::string cntr =
      controlSet("  <Control name=\"x\">\n    <DOF name=\"arm/Y\" value=\"1\"/>\n  </Control>\n");
  writeArmControls(cntr, "    <Limits name=\"X\" min=\"0\" max=\"1\"/>\n");
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(controlFile("arm.cntr"), lineOf(cntr, "arm/Y"))),
                                 HasSubstr("no <Limits name=\"Y\">")));
}

TEST_F(KauthamBadInputTest, WrongNumberOfInitValues) {
  const std::string text = writeQueries(
      "      <Query>\n        <Init>0.1 0.2 0.3</Init>\n"
      "        <Goal>0.1 0.2</Goal>\n      </Query>\n");
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "<Init>"))),
                                 HasSubstr("<Init> has 3 values; the control set has 2 controls")));
}

TEST_F(KauthamBadInputTest, ControlValueOutsideTheUnitInterval) {
  const std::string text = writeQueries(
      "      <Query>\n        <Init>0.1 0.2</Init>\n"
      "        <Goal>0.1 1.5</Goal>\n      </Query>\n");
  EXPECT_THAT(readError(),
              AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "<Goal>"))), HasSubstr("outside [0, 1]")));
}

TEST_F(KauthamBadInputTest, NonFiniteNumberInInit) {
  const std::string text = writeQueries(
      "      <Query>\n        <Init>0.1 nan</Init>\n"
      "        <Goal>0.1 0.2</Goal>\n      </Query>\n");
  EXPECT_THAT(readError(),
              AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "<Init>"))), HasSubstr("nan")));
}

TEST_F(KauthamBadInputTest, NonFiniteNumberInHome) {
  const std::string text =
      writeProblem("  <Robot robot=\"robots/arm.urdf\">\n    <Home X=\"0\" TH=\"inf\"/>\n  </Robot>\n");
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "<Home"))), HasSubstr("TH"),
                                 HasSubstr("inf")));
}

TEST_F(KauthamBadInputTest, UnknownRobotControlNameListsTheControls) {
  const std::string text = writeQueries(
      "      <Query>\n        <RobotControl name=\"a\" init=\"0.1\" goal=\"0.2\"/>\n"
      "        <RobotControl name=\"c\" init=\"0.1\" goal=\"0.2\"/>\n      </Query>\n");
  EXPECT_THAT(readError(),
              AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "name=\"c\""))),
                    HasSubstr("unknown robot control \"c\""), HasSubstr("the controls are: a, b")));
}

TEST_F(KauthamBadInputTest, MissingRobotControl) {
  const std::string text = writeQueries(
      "      <Query>\n        <RobotControl name=\"b\" init=\"0.1\" goal=\"0.2\"/>\n"
      "      </Query>\n");
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "<Query>"))),
                                 HasSubstr("no <RobotControl> for control \"a\"")));
}

/// Warnings logged while `action` runs.
template <typename Action>
std::vector<std::string> warningsOf(Action action) {
  std::vector<std::string> warnings;
  setLogSink([&](LogLevel level, std::string_view message) {
    if (level == LogLevel::kWarn) warnings.emplace_back(message);
  });
  action();
  setLogSink({});
  return warnings;
}

TEST_F(KauthamBadInputTest, TwoObstaclesWithTheSameNameAreBothKeptWithAWarning) {
  const std::string text =
      writeProblem(std::string(kArmRobotElement) + "  <Obstacle obstacle=\"obstacles/crate.urdf\"/>\n" +
                   "  <Obstacle obstacle=\"obstacles/crate.urdf\" scale=\"2\"/>\n" + kArmControls);
  KauthamProblem problem;
  const std::vector<std::string> warnings = warningsOf([&] { problem = read(); });
  ASSERT_EQ(problem.scene.objects().size(), 2U);
  EXPECT_EQ(problem.scene.objects()[0].name, "crate_model");
  EXPECT_EQ(problem.scene.objects()[1].name, "crate_model_2");
  ASSERT_EQ(warnings.size(), 1U);
  EXPECT_THAT(warnings[0], AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "scale=\"2\""))), HasSubstr("\"crate_model_2\""),
                                 HasSubstr("<KauthamName>")));
}

TEST_F(KauthamBadInputTest, ANumberWithASpaceInsideIsReadAsKauthamReadsIt) {
  const std::string text = writeProblem("  <Robot robot=\"robots/arm.urdf\">\n    <Home X=\"0.5 0.3\" Y=\" 0.25 \"/>\n  </Robot>\n" +
                                        std::string(kArmControls));
  KauthamProblem problem;
  const std::vector<std::string> warnings = warningsOf([&] { problem = read(); });
  EXPECT_DOUBLE_EQ(problem.scene.robots()[0].basePose.translation().x(), 0.5);
  EXPECT_DOUBLE_EQ(problem.scene.robots()[0].basePose.translation().y(), 0.25);
  ASSERT_EQ(warnings.size(), 1U);
  EXPECT_THAT(warnings[0], AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "<Home"))), HasSubstr("\"0.5 0.3\" has a space inside"),
                                 HasSubstr("as Kautham does")));
  writeProblem("  <Robot robot=\"robots/arm.urdf\">\n    <Home X=\"half 0.3\"/>\n  </Robot>\n" + std::string(kArmControls));
  EXPECT_THAT(readError(), HasSubstr("\"half\" is not a number"));
}

TEST_F(KauthamBadInputTest, AMeshPathWithALeadingSlashIsFoundBesideTheUrdf) {
  writeModel("obstacles/meshes/crate.stl", "solid crate\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0.1 0 0\nvertex 0 0.1 0\n"
                                            "endloop\nendfacet\nendsolid crate\n");
  writeModel("obstacles/meshed.urdf", R"(<robot name="meshed"><link name="body"><collision><geometry>
    <mesh filename="/meshes/crate.stl"/></geometry></collision></link></robot>)");
  writeProblem(std::string(kArmRobotElement) + "  <Obstacle obstacle=\"obstacles/meshed.urdf\"/>\n" + kArmControls);
  KauthamProblem problem;
  const std::vector<std::string> warnings = warningsOf([&] { problem = read(); });
  EXPECT_EQ(problem.scene.object("meshed").collisions.size(), 1U);
  ASSERT_EQ(warnings.size(), 1U);
  EXPECT_THAT(warnings[0], AllOf(HasSubstr("\"/meshes/crate.stl\" is absolute but does not exist"), HasSubstr("as Kautham does")));
}

TEST_F(KauthamBadInputTest, InitialAttachedObstacleNamingAnUnknownLink) {
  const std::string text =
      writeProblem(std::string(kArmRobotElement) + "  <Obstacle obstacle=\"obstacles/crate.urdf\"/>\n" +
                   "  <InitialAttachedObstacle robot=\"arm\" link=\"hand\" obstacle=\"crate_model\"/>\n");
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "<InitialAttachedObstacle"))),
                                 HasSubstr("<InitialAttachedObstacle>"), HasSubstr("\"hand\"")));
}

TEST_F(KauthamBadInputTest, BadRoleInLang2ManipObject) {
  const std::string urdf = test::boxUrdf("holder", "0.1 0.1 0.1", "  <lang2manip_object role=\"bucket\"/>\n");
  writeModel("obstacles/holder.urdf", urdf);
  writeProblem(std::string(kArmRobotElement) + "  <Obstacle obstacle=\"obstacles/holder.urdf\"/>\n");
  const std::filesystem::path model = (root() / "models" / "obstacles" / "holder.urdf").lexically_normal();
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(model, lineOf(urdf, "<lang2manip_object"))),
                                 HasSubstr("\"bucket\""), HasSubstr("none, support, container")));
}

TEST_F(KauthamBadInputTest, LimitsWithMinGreaterThanMax) {
  const std::string text = writeProblem(
      "  <Robot robot=\"robots/arm.urdf\">\n    <Limits name=\"X\" min=\"2\" max=\"1\"/>\n  </Robot>\n");
  EXPECT_THAT(readError(),
              AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "<Limits"))), HasSubstr("min > max")));
}

TEST_F(KauthamBadInputTest, RobotControlsOutOfRangeAtMappingTime) {
  writeQueries("");
  const KauthamProblem problem = read();
  EXPECT_THAT(
      test::errorMessage([&] { (void)robotStatesFromControls(problem, {0.5}, "my values"); }),
      AllOf(HasSubstr("my values has 1 control values"), HasSubstr(controlFile("arm.cntr").string())));
  EXPECT_THAT(test::errorMessage([&] {
                (void)robotStatesFromControls(problem, {0.5, -0.1}, "my values");
              }),
              AllOf(HasSubstr("my values"), HasSubstr("control \"b\""), HasSubstr("outside [0, 1]")));
}

TEST_F(KauthamBadInputTest, ModelReferenceToADirectorySaysSo) {
  writeProblem("  <Robot robot=\"robots\"/>\n");
  EXPECT_THAT(readError(), AllOf(HasSubstr("\"robots\" resolves to no readable file"),
                                 HasSubstr("robots (is a directory, not a file)")));
}

TEST_F(KauthamBadInputTest, HomeFarOutsideTheModelRange) {
  const std::string text = writeProblem(
      "  <Robot robot=\"robots/arm.urdf\">\n    <Home X=\"1e300\" Y=\"0\" Z=\"0\"/>\n  </Robot>\n");
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "<Home"))),
                                 HasSubstr("<Home> X Y Z"), HasSubstr("more than 10000 m from the origin")));
}

TEST_F(KauthamBadInputTest, ObstacleWithAHugeBoxNamesItsFileAndLink) {
  const std::string urdf = test::boxUrdf("slab", "1e300 1 1");
  writeModel("obstacles/slab.urdf", urdf);
  writeProblem(std::string(kArmRobotElement) + "  <Obstacle obstacle=\"obstacles/slab.urdf\"/>\n");
  const std::filesystem::path model = (root() / "models" / "obstacles" / "slab.urdf").lexically_normal();
  EXPECT_THAT(readError(), AllOf(HasSubstr(fileLine(model, lineOf(urdf, "<link"))),
                                 HasSubstr("link \"body\" collision 1 box size 1e+300 m is outside [1e-06, 10000] m")));
}

TEST_F(KauthamBadInputTest, ZeroRotationAxisInHomeIsNoRotationWithAWarning) {
  std::vector<std::string> warnings;
  setLogSink([&](LogLevel, std::string_view message) {
    if (message.find("rotation axis") != std::string_view::npos) warnings.emplace_back(message);
  });
  const std::string text = writeProblem(
      "  <Robot robot=\"robots/arm.urdf\">\n    <Home X=\"1\" WX=\"0\" WY=\"0\" WZ=\"0\" TH=\"1.5\"/>\n"
      "  </Robot>\n  <Obstacle obstacle=\"obstacles/crate.urdf\">\n"
      "    <Home WX=\"0\" WY=\"0\" WZ=\"0\" TH=\"0\"/>\n  </Obstacle>\n" + std::string(kArmControls));
  const KauthamProblem problem = read();
  setLogSink({});
  EXPECT_TRUE(problem.scene.robots()[0].basePose.linear().isIdentity(0.0));
  ASSERT_EQ(warnings.size(), 1U);
  EXPECT_THAT(warnings[0], AllOf(HasSubstr(fileLine(problemFile(), lineOf(text, "<Home"))),
                                 HasSubstr("zero rotation axis"), HasSubstr("TH=1.5"),
                                 HasSubstr("no rotation, as Kautham does")));
}

}  // namespace
}  // namespace lang2manip
