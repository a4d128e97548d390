#include "lang2manip/model/joint_limits_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numbers>
#include <string>
#include <vector>

#include "lang2manip/core/log.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "model_test_support.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;
using test::errorMessage;
using test::twoJointUrdf;
using test::writeText;

constexpr double kDegree = std::numbers::pi / 180.0;

/// The two-joint arm of model_test_support.hpp with a prismatic slide and a continuous wrist.
std::string armUrdf() {
  return twoJointUrdf(R"(
  <link name="carriage"/>
  <link name="hand"/>
  <joint name="slide" type="prismatic"><parent link="tip"/><child link="carriage"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.2" velocity="0.5" effort="20"/></joint>
  <joint name="wrist" type="continuous"><parent link="carriage"/><child link="hand"/>
    <axis xyz="0 0 1"/><limit velocity="4" effort="5"/></joint>
  <link name="flange"/>
  <joint name="flange_joint" type="fixed"><parent link="hand"/><child link="flange"/></joint>)");
}

/// Collects the warnings logged while it lives.
class WarningLog {
 public:
  WarningLog() {
    setLogSink([this](LogLevel level, std::string_view message) {
      if (level == LogLevel::kWarn) warnings.emplace_back(message);
    });
  }
  ~WarningLog() { setLogSink({}); }
  WarningLog(const WarningLog&) = delete;
  WarningLog& operator=(const WarningLog&) = delete;
  std::vector<std::string> warnings;
};

/// Reads `yaml` written to a file named joint_limits.yaml in a fresh directory.
class JointLimitsFileTest : public testing::Test {
 protected:
  JointLimitsFile read(const std::string& yaml) const {
    writeText(file(), yaml);
    return readJointLimitsFile(file());
  }
  std::string failure(const std::string& yaml) const {
    writeText(file(), yaml);
    return errorMessage([&] { (void)readJointLimitsFile(file()); });
  }
  /// The arm with `yaml` applied.
  RobotModel applied(const std::string& yaml, double lengthScale = 1.0) const {
    RobotModel model = *readUrdfString(armUrdf(), "arm.urdf", ".");
    applyJointLimits(read(yaml), model, lengthScale);
    return model;
  }
  std::string applyFailure(const std::string& yaml) const {
    return errorMessage([&] { (void)applied(yaml); });
  }
  [[nodiscard]] std::filesystem::path file() const { return directory_.path() / "joint_limits.yaml"; }
  [[nodiscard]] std::string at(int line) const { return file().string() + ":" + std::to_string(line) + ": "; }

 private:
  test::TempDirectory directory_;
};

TEST_F(JointLimitsFileTest, ReadsEveryLimitKindWithDegreesAndScalingFactors) {
  const JointLimitsFile limits = read(R"(default_velocity_scaling_factor: 0.1
default_acceleration_scaling_factor: 1
joint_limits:
  shoulder:
    has_velocity_limits: true
    max_velocity: !degrees 90
    has_acceleration_limits: yes
    max_acceleration: 5
    has_jerk_limits: true
    max_jerk: !radians 100.5
    has_position_limits: true
    min_position: !degrees -45
    max_position: 0.5
    has_effort_limits: true
    max_effort: 12
    has_soft_limits: false
    k_velocity: 3
  elbow: {}
)");
  EXPECT_EQ(limits.source, file().string());
  EXPECT_EQ(limits.defaultVelocityScalingFactor, 0.1);
  EXPECT_EQ(limits.defaultAccelerationScalingFactor, 1.0);
  ASSERT_EQ(limits.joints.size(), 2U);
  const JointLimitsEntry& shoulder = limits.joints[0];
  EXPECT_EQ(shoulder.joint, "shoulder");
  EXPECT_EQ(shoulder.line, 4);
  EXPECT_NEAR(*shoulder.maxVelocity, 90 * kDegree, 1e-12);
  EXPECT_EQ(shoulder.maxAcceleration, 5.0);
  EXPECT_EQ(shoulder.maxJerk, 100.5);
  EXPECT_NEAR(*shoulder.minPosition, -45 * kDegree, 1e-12);
  EXPECT_EQ(shoulder.maxPosition, 0.5);
  EXPECT_EQ(shoulder.maxEffort, 12.0);
  EXPECT_EQ(shoulder.degreesLine, 6);
  EXPECT_EQ(limits.joints[1].joint, "elbow");
  EXPECT_FALSE(limits.joints[1].maxVelocity || limits.joints[1].maxAcceleration || limits.joints[1].minPosition);
}

TEST_F(JointLimitsFileTest, MoveIt2sWrapperIsReadAndTheScalingDefaultsGoOnTheModel) {
  const RobotModel model = applied(R"(robot_description_planning:
  default_velocity_scaling_factor: 0.1
  default_acceleration_scaling_factor: 0.2
  joint_limits:
    shoulder:
      has_acceleration_limits: true
      max_acceleration: 3
)");
  EXPECT_EQ(model.scalingDefaults().velocity, 0.1);
  EXPECT_EQ(model.scalingDefaults().acceleration, 0.2);
  EXPECT_EQ(model.accelerationLimit(model.variableIndex("shoulder")), 3.0);
  const RobotModel plain = applied("joint_limits: {}\n");
  EXPECT_FALSE(plain.scalingDefaults().velocity || plain.scalingDefaults().acceleration);
  EXPECT_THAT(failure("robot_description_planning:\n  joint_limits: {}\nextra: 1\n"), HasSubstr("unknown key 'robot_description_planning'"));
  EXPECT_THAT(failure("robot_description_planning:\n  default_velocity_scaling_factor: 2\n  joint_limits: {}\n"),
              HasSubstr("must be in (0, 1], got 2"));
}

TEST_F(JointLimitsFileTest, AValueWithoutItsFlagIsIgnoredWithAWarning) {
  const WarningLog log;
  const JointLimitsFile limits = read(R"(joint_limits:
  shoulder:
    has_acceleration_limits: false
    max_acceleration: 5
    max_velocity: 3
)");
  ASSERT_EQ(limits.joints.size(), 1U);
  EXPECT_FALSE(limits.joints[0].maxAcceleration);
  EXPECT_FALSE(limits.joints[0].maxVelocity);
  EXPECT_THAT(log.warnings,
              ElementsAre(at(5) + "joint_limits.shoulder.max_velocity is ignored: has_velocity_limits is absent "
                                  "(set it to true to use the limit)",
                          at(4) + "joint_limits.shoulder.max_acceleration is ignored: has_acceleration_limits is false "
                                  "(set it to true to use the limit)"));
}

TEST_F(JointLimitsFileTest, RejectsBadFilesNamingFileLineAndKey) {
  EXPECT_EQ(failure("- shoulder\n- elbow\n"), at(1) + "expected a map at the top level");
  EXPECT_EQ(failure("default_velocity_scaling_factor: 0.5\n"), at(1) + "missing required key 'joint_limits'");
  EXPECT_EQ(failure("joint_limits:\n  - shoulder\n"), at(2) + "joint_limits: expected a map from joint names to their limits");
  EXPECT_EQ(failure("joint_limits:\n"), at(1) + "missing required key 'joint_limits'");
  EXPECT_EQ(failure("joint_limits: {}\ncartesian_limits: {}\n"),
            at(2) + "cartesian_limits: unknown key 'cartesian_limits'; a joint limits file has joint_limits, "
                    "default_velocity_scaling_factor and default_acceleration_scaling_factor");
  EXPECT_EQ(failure("default_velocity_scaling_factor: 1.5\njoint_limits: {}\n"),
            at(1) + "default_velocity_scaling_factor: must be in (0, 1], got 1.5");
  EXPECT_EQ(failure("default_acceleration_scaling_factor: !degrees 0.5\njoint_limits: {}\n"),
            at(1) + "default_acceleration_scaling_factor: !degrees applies to angles, not to this value");
  EXPECT_EQ(failure("joint_limits:\n  shoulder: 3\n"),
            at(2) + "joint_limits.shoulder: expected a map of limits (has_velocity_limits, max_velocity, ...)");
  EXPECT_THAT(failure("joint_limits:\n  shoulder:\n    max_velocty: 3\n"),
              HasSubstr(at(3) + "joint_limits.shoulder.max_velocty: unknown key 'max_velocty'; a joint's keys are "
                                "has_velocity_limits, max_velocity, has_acceleration_limits"));
  EXPECT_EQ(failure("joint_limits:\n  shoulder: {}\n  elbow: {}\n  shoulder: {}\n"),
            at(4) + "joint_limits.shoulder: the joint is given twice (first on line 2)");
  EXPECT_EQ(failure("joint_limits:\n  shoulder:\n    has_jerk_limits: true\n    has_jerk_limits: false\n"),
            at(4) + "joint_limits.shoulder.has_jerk_limits: 'has_jerk_limits' is given twice (first on line 3)");
  EXPECT_EQ(failure("joint_limits: {shoulder: {[a]: 1}}\n"),
            at(1) + "joint_limits.shoulder: expected a name as a key, got a list");
}

TEST_F(JointLimitsFileTest, RejectsBadFlagsAndValues) {
  const auto limit = [&](const std::string& lines) { return failure("joint_limits:\n  shoulder:\n" + lines); };
  EXPECT_EQ(limit("    has_acceleration_limits: true\n"),
            at(3) + "joint_limits.shoulder.has_acceleration_limits: is true but max_acceleration is not given");
  EXPECT_EQ(limit("    has_position_limits: true\n    min_position: 0\n"),
            at(3) + "joint_limits.shoulder.has_position_limits: is true but max_position is not given");
  EXPECT_EQ(limit("    has_velocity_limits: maybe\n    max_velocity: 1\n"),
            at(3) + "joint_limits.shoulder.has_velocity_limits: expected true or false, got \"maybe\"");
  EXPECT_EQ(limit("    has_velocity_limits:\n    max_velocity: 1\n"),
            at(3) + "joint_limits.shoulder.has_velocity_limits: expected true or false, got nothing");
  EXPECT_EQ(limit("    has_velocity_limits: true\n    max_velocity: -1\n"),
            at(4) + "joint_limits.shoulder.max_velocity: must be positive, got -1");
  EXPECT_EQ(limit("    has_acceleration_limits: true\n    max_acceleration: 0\n"),
            at(4) + "joint_limits.shoulder.max_acceleration: must be positive, got 0");
  EXPECT_EQ(limit("    has_jerk_limits: true\n    max_jerk: !degrees -0.0\n"),
            at(4) + "joint_limits.shoulder.max_jerk: must be positive, got -0.0");
  EXPECT_EQ(limit("    has_effort_limits: true\n    max_effort: .inf\n"),
            at(4) + "joint_limits.shoulder.max_effort: must be a finite number, got .inf");
  EXPECT_EQ(limit("    has_velocity_limits: true\n    max_velocity: -.NaN\n"),
            at(4) + "joint_limits.shoulder.max_velocity: must be a finite number, got -.NaN");
  EXPECT_THAT(limit("    has_velocity_limits: true\n    max_velocity: fast\n"),
              HasSubstr(at(4) + "joint_limits.shoulder.max_velocity"));
  EXPECT_THAT(limit("    has_velocity_limits: true\n    max_velocity: fast\n"), HasSubstr("fast"));
  EXPECT_EQ(limit("    has_velocity_limits: true\n    max_velocity: [1, 2]\n"),
            at(4) + "joint_limits.shoulder.max_velocity: expected a number, got a list");
  EXPECT_EQ(limit("    has_effort_limits: true\n    max_effort: !degrees 10\n"),
            at(4) + "joint_limits.shoulder.max_effort: !degrees applies to angles, not to this value");
  EXPECT_EQ(limit("    has_velocity_limits: true\n    max_velocity: !rpm 10\n"),
            at(4) + "joint_limits.shoulder.max_velocity: unknown tag !rpm (only !degrees and !radians are understood)");
  EXPECT_EQ(limit("    has_position_limits: true\n    min_position: 1\n    max_position: !degrees 45\n"),
            at(4) + "joint_limits.shoulder.min_position: min_position 1 is above max_position 0.785398");
}

TEST_F(JointLimitsFileTest, RejectsMissingAndMalformedFiles) {
  EXPECT_THAT(errorMessage([&] { (void)readJointLimitsFile(file().parent_path() / "absent.yaml"); }),
              HasSubstr("absent.yaml"));
  EXPECT_THAT(failure("joint_limits:\n  shoulder: [1\n"), HasSubstr(file().string() + ":"));
  EXPECT_THAT(failure("joint_limits:\n  shoulder: [1\n"), HasSubstr("malformed YAML"));
}

TEST_F(JointLimitsFileTest, AppliesVelocityAccelerationJerkEffortAndNarrowsPositions) {
  const RobotModel model = applied(R"(joint_limits:
  shoulder:
    has_velocity_limits: true
    max_velocity: 1.25
    has_acceleration_limits: true
    max_acceleration: 6
    has_jerk_limits: true
    max_jerk: 300
    has_effort_limits: true
    max_effort: 7
    has_position_limits: true
    min_position: -1
    max_position: !degrees 45
  slide:
    has_acceleration_limits: true
    max_acceleration: 2
    has_position_limits: true
    min_position: 0.05
    max_position: 0.1
)",
                                   2.0);
  const int shoulder = model.variableIndex("shoulder");
  EXPECT_EQ(model.velocityLimits()[shoulder], 1.25);
  EXPECT_EQ(model.accelerationLimit(shoulder), 6.0);
  EXPECT_EQ(model.jerkLimit(shoulder), 300.0);
  EXPECT_EQ(model.joints()[static_cast<std::size_t>(model.jointIndex("shoulder"))].limits.effort, 7.0);
  EXPECT_EQ(model.lowerLimits()[shoulder], -1.0);
  EXPECT_NEAR(model.upperLimits()[shoulder], 45 * kDegree, 1e-12);
  // The elbow is not in the file: the URDF's limits, no acceleration or jerk.
  const int elbow = model.variableIndex("elbow");
  EXPECT_EQ(model.velocityLimits()[elbow], 3.0);
  EXPECT_FALSE(model.accelerationLimit(elbow));
  EXPECT_FALSE(model.jerkLimit(elbow));
  // Prismatic positions are scaled as the URDF's are (the URDF was read at scale 1 here: 0..0.2).
  const int slide = model.variableIndex("slide");
  EXPECT_EQ(model.accelerationLimit(slide), 2.0);
  EXPECT_DOUBLE_EQ(model.lowerLimits()[slide], 0.1);
  EXPECT_DOUBLE_EQ(model.upperLimits()[slide], 0.2);
}

TEST_F(JointLimitsFileTest, NeverWidensTheUrdfRangeAndIgnoresPositionsOfContinuousJoints) {
  const WarningLog log;
  const RobotModel model = applied(R"(joint_limits:
  shoulder:
    has_position_limits: true
    min_position: -3
    max_position: !degrees 85.9436692696
  wrist:
    has_position_limits: true
    min_position: -1
    max_position: 1
)");
  const int shoulder = model.variableIndex("shoulder");
  EXPECT_EQ(model.lowerLimits()[shoulder], -1.5);
  EXPECT_NEAR(model.upperLimits()[shoulder], 1.5, 1e-9);  // 85.94... degrees is the URDF's 1.5 rad
  EXPECT_NEAR(model.lowerLimits()[model.variableIndex("wrist")], -std::numbers::pi, 1e-12);
  EXPECT_THAT(log.warnings,
              ElementsAre(at(2) + "joint_limits.shoulder.min_position -3 lies outside the URDF's range: the URDF's -1.5 "
                                  "is kept (a joint limits file narrows a joint's range, never widens it)",
                          at(6) + "joint_limits.wrist.has_position_limits: ignored: joint \"wrist\" is continuous "
                                  "(it turns without limit)"));
}

TEST_F(JointLimitsFileTest, RejectsJointsTheModelHasNotAndDegreesOnPrismaticJoints) {
  const std::string movable = "its movable joints are: shoulder, elbow, slide, wrist";
  EXPECT_EQ(applyFailure("joint_limits:\n  shoulder: {}\n  knee:\n    has_velocity_limits: false\n"),
            at(3) + "joint_limits.knee: robot \"arm\" has no joint \"knee\"; " + movable);
  EXPECT_EQ(applyFailure("joint_limits:\n  flange_joint: {}\n"),
            at(2) + "joint_limits.flange_joint: robot \"arm\" has no movable joint \"flange_joint\"; " + movable);
  EXPECT_EQ(applyFailure("joint_limits:\n  slide:\n    has_velocity_limits: true\n    max_velocity: !degrees 10\n"),
            at(4) + "joint_limits.slide: joint \"slide\" is prismatic: its limits are in metres, not !degrees");
  // Nothing is applied when one entry is bad.
  RobotModel model = *readUrdfString(armUrdf(), "arm.urdf", ".");
  const JointLimitsFile limits =
      read("joint_limits:\n  shoulder:\n    has_acceleration_limits: true\n    max_acceleration: 1\n  knee: {}\n");
  EXPECT_THAT(errorMessage([&] { applyJointLimits(limits, model); }), HasSubstr("has no joint \"knee\""));
  EXPECT_FALSE(model.accelerationLimit(model.variableIndex("shoulder")));
}

TEST(JointLimitsDiscovery, ReadsTheUrdfsSiblingFileOrTheOptionsFile) {
  const test::TempDirectory directory;
  const std::filesystem::path urdf = directory.path() / "arm.urdf";
  writeText(urdf, twoJointUrdf());
  // A plain joint_limits.yaml is not ours: vendors put files of other formats under that name.
  writeText(directory.path() / "joint_limits.yaml", "shoulder:\n  limit: {velocity: 1}\n");
  EXPECT_FALSE(readUrdfFile(urdf)->accelerationLimit(0));
  writeText(directory.path() / "arm.joint_limits.yaml",
            "joint_limits:\n  elbow:\n    has_acceleration_limits: true\n    max_acceleration: 4.5\n");
  const RobotModelPtr sibling = readUrdfFile(urdf);
  EXPECT_EQ(sibling->accelerationLimit(sibling->variableIndex("elbow")), 4.5);
  EXPECT_FALSE(sibling->accelerationLimit(sibling->variableIndex("shoulder")));
  // An explicit file replaces the sibling; URDF text reads one only when told.
  UrdfReadOptions options;
  options.jointLimits = directory.path() / "other.yaml";
  writeText(options.jointLimits, "joint_limits:\n  shoulder:\n    has_acceleration_limits: true\n    max_acceleration: 9\n");
  const RobotModelPtr chosen = readUrdfFile(urdf, options);
  EXPECT_EQ(chosen->accelerationLimit(chosen->variableIndex("shoulder")), 9.0);
  EXPECT_FALSE(chosen->accelerationLimit(chosen->variableIndex("elbow")));
  EXPECT_FALSE(readUrdfString(twoJointUrdf(), "arm.urdf", directory.path())->accelerationLimit(0));
  EXPECT_EQ(readUrdfString(twoJointUrdf(), "arm.urdf", directory.path(), options)->accelerationLimit(0), 9.0);
  options.jointLimits = directory.path() / "missing.yaml";
  EXPECT_THAT(errorMessage([&] { (void)readUrdfFile(urdf, options); }), HasSubstr("missing.yaml"));
}

TEST(JointLimitsDiscovery, ABadSiblingFileFailsTheRobotAndXacroRobotsReadTheirsToo) {
  const test::TempDirectory directory;
  writeText(directory.path() / "arm.urdf", twoJointUrdf());
  writeText(directory.path() / "arm.joint_limits.yaml", "joint_limits:\n  wrist: {}\n");
  EXPECT_EQ(errorMessage([&] { (void)readUrdfFile(directory.path() / "arm.urdf"); }),
            (directory.path() / "arm.joint_limits.yaml").string() +
                ":2: joint_limits.wrist: robot \"arm\" has no joint \"wrist\"; its movable joints are: shoulder, elbow");
  for (const char* xacro : {"bot.urdf.xacro", "bot.xacro"}) {
    SCOPED_TRACE(xacro);
    const test::TempDirectory xacroDirectory;
    writeText(xacroDirectory.path() / xacro, twoJointUrdf());
    writeText(xacroDirectory.path() / "bot.joint_limits.yaml",
              "joint_limits:\n  elbow:\n    has_acceleration_limits: true\n    max_acceleration: 3\n");
    const RobotModelPtr model = readUrdfFile(xacroDirectory.path() / xacro);
    EXPECT_EQ(model->accelerationLimit(model->variableIndex("elbow")), 3.0);
  }
}

TEST(JointLimitsDiscovery, AJointWithoutVelocityLimitIsWarnedOnceWhenTheModelIsRead) {
  const test::TempDirectory directory;
  const std::filesystem::path urdf = directory.path() / "arm.urdf";
  writeText(urdf, twoJointUrdf(R"(<link name="hand"/><joint name="wrist" type="continuous">
    <parent link="tip"/><child link="hand"/><axis xyz="0 0 1"/></joint>)"));
  {
    const WarningLog log;
    const RobotModelPtr model = readUrdfFile(urdf);
    EXPECT_THAT(log.warnings, ElementsAre(urdf.string() + ": robot \"arm\", joint \"wrist\": velocity limit 0 (zero or "
                                                          "absent in the URDF) is no limit; trajectories move it at most "
                                                          "at 1 rad/s"));
  }
  writeText(directory.path() / "arm.joint_limits.yaml",
            "joint_limits:\n  wrist:\n    has_velocity_limits: true\n    max_velocity: 2\n");
  const WarningLog log;
  EXPECT_EQ(readUrdfFile(urdf)->velocityLimits()[2], 2.0);
  EXPECT_TRUE(log.warnings.empty());
}

TEST(JointLimitsDiscovery, AZeroVelocityLimitIsWarnedAndANegativeOrTinyOneRefused) {
  const test::TempDirectory directory;
  const std::filesystem::path urdf = directory.path() / "arm.urdf";
  const auto wristWithVelocity = [](const std::string& velocity) {
    return twoJointUrdf(R"(<link name="hand"/><joint name="wrist" type="revolute"><parent link="tip"/><child link="hand"/>
      <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="5" velocity=")" + velocity + R"("/></joint>)");
  };
  writeText(urdf, wristWithVelocity("0"));
  {
    const WarningLog log;
    EXPECT_EQ(readUrdfFile(urdf)->velocityLimits()[2], 0.0);
    EXPECT_THAT(log.warnings, ElementsAre(HasSubstr("joint \"wrist\": velocity limit 0 (zero or absent in the URDF)")));
  }
  writeText(urdf, wristWithVelocity("-1"));
  EXPECT_THAT([&] { (void)readUrdfFile(urdf); },
              ThrowsMessage<InputError>(HasSubstr("joint \"wrist\" velocity limit must not be negative, got -1")));
  writeText(urdf, wristWithVelocity("1e-9"));
  EXPECT_THAT([&] { (void)readUrdfFile(urdf); },
              ThrowsMessage<InputError>(HasSubstr("joint \"wrist\" velocity limit 1e-09 is below 0.0001")));
}

/// The acceleration limits of `joints` of `model` (-1 for unknown).
std::vector<double> accelerations(const RobotModel& model, const std::vector<std::string>& joints) {
  std::vector<double> result;
  for (const std::string& joint : joints) result.push_back(model.accelerationLimit(model.variableIndex(joint)).value_or(-1.0));
  return result;
}

TEST(JointLimitsBuiltinRobots, PandaAndIiwaHaveTheirPublishedAccelerationsAndTheOthersNone) {
  const RobotModelPtr panda = readUrdfFile(builtinRobotUrdf("panda"));
  EXPECT_THAT(accelerations(*panda, {"panda_joint1", "panda_joint2", "panda_joint3", "panda_joint4", "panda_joint5",
                                     "panda_joint6", "panda_joint7", "panda_finger_joint1"}),
              ElementsAre(15, 7.5, 10, 12.5, 15, 20, 20, -1));
  EXPECT_EQ(panda->velocityLimits()[panda->variableIndex("panda_finger_joint1")], 0.2);
  const RobotModelPtr iiwa = readUrdfFile(builtinRobotUrdf("iiwa14"));
  EXPECT_THAT(accelerations(*iiwa, {"iiwa_joint_1", "iiwa_joint_2", "iiwa_joint_3", "iiwa_joint_4", "iiwa_joint_5",
                                    "iiwa_joint_6", "iiwa_joint_7", "gripper_finger_joint"}),
              ElementsAre(8.57, 8.57, 8.74, 11.36, 12.23, 15.72, 15.72, -1));
  for (const char* robot : {"ur5", "tx90", "yumi"}) {
    const RobotModelPtr model = readUrdfFile(builtinRobotUrdf(robot));
    for (int v = 0; v < model->variableCount(); ++v) EXPECT_FALSE(model->accelerationLimit(v)) << robot << " " << v;
  }
}

TEST(JointLimitsBuiltinRobots, BuiltinProblemsReadTheirRobotsLimits) {
  const KauthamProblem problem = readKauthamProblem(resolveProblem("panda_desk"));
  const RobotModel& panda = *problem.scene.robots().front().model;
  EXPECT_EQ(panda.accelerationLimit(panda.variableIndex("panda_joint2")), 7.5);
}

// ur_description's joint_limits.yaml files are keyed by its xacro's short names: read as a
// MoveIt file they parse (with !degrees), and applying one names the joints the robot has.
TEST(JointLimitsSharedData, UrDescriptionsVendorFileIsNotAMoveItFileForItsRobot) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const std::filesystem::path vendor = shared / "robots/ur_description/config/ur5e/joint_limits.yaml";
  const WarningLog log;
  const JointLimitsFile limits = readJointLimitsFile(vendor);
  ASSERT_EQ(limits.joints.size(), 6U);
  EXPECT_EQ(limits.joints[0].joint, "shoulder_pan");
  EXPECT_NEAR(*limits.joints[0].maxVelocity, std::numbers::pi, 1e-12);
  EXPECT_NEAR(*limits.joints[0].minPosition, -2 * std::numbers::pi, 1e-12);
  EXPECT_FALSE(limits.joints[0].maxAcceleration);
  EXPECT_TRUE(log.warnings.empty());
  RobotModel ur5e = *readUrdfFile(shared / "robots/ur_description/urdf/ur5e.xacro");
  EXPECT_THAT(errorMessage([&] { applyJointLimits(limits, ur5e); }),
              HasSubstr(vendor.string() + ":11: joint_limits.shoulder_pan: robot \"ur5e_robot\" has no joint \"shoulder_pan\"; "
                                          "its movable joints are: shoulder_pan_joint, shoulder_lift_joint, elbow_joint, wrist_1_joint, "
                                          "wrist_2_joint, wrist_3_joint"));
}

}  // namespace
}  // namespace lang2manip
