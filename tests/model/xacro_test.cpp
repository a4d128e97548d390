// The xacro processor: each construct of the language on small files written here, each class of
// bad input refused with the file, line and macro, and the official robot descriptions of
// ../shared/data/robots expanded, loaded and checked against their published kinematics.

#include "lang2manip/model/xacro.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>

#include "lang2manip/core/error.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

class XacroTest : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& text) {
    const fs::path path = directory_.path() / name;
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
    return path;
  }

  /// The expansion of a robot whose body is `body`.
  std::string expand(const std::string& body, const std::map<std::string, std::string>& arguments = {}) {
    const fs::path file = write("robot.urdf.xacro", "<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\" name=\"r\">\n" +
                                                        body + "\n</robot>\n");
    return expandXacroFile(file, XacroOptions{arguments, {}});
  }

  std::string error(const std::string& body) {
    try {
      expand(body);
    } catch (const InputError& failure) {
      return failure.what();
    }
    ADD_FAILURE() << "no InputError for " << body;
    return {};
  }

  test::TempDirectory directory_;
};

TEST_F(XacroTest, PropertiesAndExpressions) {
  const std::string urdf = expand(R"XML(
    <xacro:property name="width" value="0.2"/>
    <xacro:property name="half" value="${width / 2}"/>
    <xacro:property name="words" value="a b c"/>
    <xacro:property name="width" default="9"/>
    <xacro:property name="table" value="${ {'leg': [1, 2, 3], 'name': 'desk'} }"/>
    <a v1="${half}" v2="${pi}" v3="${radians(180)}" v4="${2**10}" v5="${7 // 2} ${7 % 3} ${-7 // 2}"
       v6="${words.split()[1]}" v7="${'x' if width > 0.1 else 'y'}" v8="${'b' in words and not False}"
       v9="${table.leg[-1] + len(table['name'])}" v10="${1e-05} ${1.0} ${3} ${0.1 + 0.2}" v11="$${literal}"
       v12="${width * 2 == 0.4}" v13="${max(1, 5, 3)} ${abs(-2.5)} ${int('42') + 1} ${str(5) + 'x'}"
       v14="${words.upper().replace(' ', '-')}" v15="${cos(0)} ${sqrt(16)} ${atan2(0, -1)}"/>)XML");
  EXPECT_THAT(urdf, HasSubstr("v1=\"0.1\""));
  EXPECT_THAT(urdf, HasSubstr("v2=\"3.141592653589793\""));
  EXPECT_THAT(urdf, HasSubstr("v3=\"3.141592653589793\""));
  EXPECT_THAT(urdf, HasSubstr("v4=\"1024\""));
  EXPECT_THAT(urdf, HasSubstr("v5=\"3 1 -4\""));
  EXPECT_THAT(urdf, HasSubstr("v6=\"b\""));
  EXPECT_THAT(urdf, HasSubstr("v7=\"x\""));
  EXPECT_THAT(urdf, HasSubstr("v8=\"True\""));
  EXPECT_THAT(urdf, HasSubstr("v9=\"7\""));
  EXPECT_THAT(urdf, HasSubstr("v10=\"1e-05 1.0 3 0.30000000000000004\""));
  EXPECT_THAT(urdf, HasSubstr("v11=\"${literal}\""));
  EXPECT_THAT(urdf, HasSubstr("v12=\"True\""));
  EXPECT_THAT(urdf, HasSubstr("v13=\"5 2.5 43 5x\""));
  EXPECT_THAT(urdf, HasSubstr("v14=\"A-B-C\""));
  EXPECT_THAT(urdf, HasSubstr("v15=\"1.0 4.0 3.141592653589793\""));
  EXPECT_THAT(urdf, Not(HasSubstr("xacro")));
}

TEST_F(XacroTest, MacrosWithDefaultsInheritanceBlocksAndDynamicScope) {
  const std::string urdf = expand(R"XML(
    <xacro:property name="prefix" value="arm_"/>
    <xacro:property name="shared" value="outer"/>
    <xacro:macro name="part" params="name size:=1 offset:='0 0 0' tag:=^ colour:=^|red *shape **extra">
      <link name="${prefix}${name}" size="${size * 2}" offset="${offset}" tag="${tag}" colour="${colour}" seen="${shared}">
        <xacro:insert_block name="shape"/>
        <xacro:insert_block name="extra"/>
      </link>
    </xacro:macro>
    <xacro:property name="tag" value="T"/>
    <xacro:macro name="pair" params="shared">
      <xacro:part name="left"><box/><extra><e1/><e2/></extra></xacro:part>
    </xacro:macro>
    <xacro:pair shared="inner"/>
    <xacro:call macro="part" name="right" size="3"><sphere/><x><y/></x></xacro:call>)XML");
  EXPECT_THAT(urdf, HasSubstr("<link name=\"arm_left\" size=\"2\" offset=\"0 0 0\" tag=\"T\" colour=\"red\" seen=\"inner\">"));
  EXPECT_THAT(urdf, HasSubstr("<box />"));
  EXPECT_THAT(urdf, HasSubstr("<e1 />"));
  EXPECT_THAT(urdf, Not(HasSubstr("<extra>")));
  EXPECT_THAT(urdf, HasSubstr("<link name=\"arm_right\" size=\"6\" offset=\"0 0 0\" tag=\"T\" colour=\"red\" seen=\"outer\">"));
  EXPECT_THAT(urdf, HasSubstr("<y />"));
}

TEST_F(XacroTest, ABlockPassedOnUnderItsOwnNameIsTheCallersBlock) {
  // Kinova's description passes its *origin on to a macro whose block parameter is also named
  // origin: the call's blocks are expanded in the caller's scope, as ROS's xacro does.
  const std::string urdf = expand(R"XML(
    <xacro:macro name="inner" params="*origin prefix">
      <joint name="${prefix}j" type="fixed"><xacro:insert_block name="origin"/></joint>
    </xacro:macro>
    <xacro:macro name="outer" params="*origin prefix">
      <xacro:inner prefix="${prefix}arm_"><xacro:insert_block name="origin"/></xacro:inner>
    </xacro:macro>
    <xacro:outer prefix="left_"><origin xyz="1 2 3" rpy="0 0 0"/></xacro:outer>)XML");
  EXPECT_THAT(urdf, HasSubstr("<joint name=\"left_arm_j\" type=\"fixed\">"));
  EXPECT_THAT(urdf, HasSubstr("<origin xyz=\"1 2 3\" rpy=\"0 0 0\" />"));
}

TEST_F(XacroTest, ConditionalsArgumentsElementsAndPropertyBlocks) {
  const std::string urdf = expand(R"XML(
    <xacro:arg name="hand" default="false"/>
    <xacro:arg name="name" default="robot"/>
    <xacro:property name="geometry"><cylinder radius="1"/></xacro:property>
    <xacro:if value="$(arg hand)"><hand/></xacro:if>
    <xacro:unless value="$(arg hand)"><flange/></xacro:unless>
    <xacro:if value="${1 + 1 == 2}"><two/></xacro:if>
    <xacro:if value="0"><zero/></xacro:if>
    <xacro:element xacro:name="${'gen' + 'erated'}" a="$(arg name)"><xacro:attribute name="b" value="${3 * 3}"/></xacro:element>
    <shape><xacro:insert_block name="geometry"/></shape>)XML",
                                  {{"name", "given"}});
  EXPECT_THAT(urdf, Not(HasSubstr("<hand")));
  EXPECT_THAT(urdf, HasSubstr("<flange />"));
  EXPECT_THAT(urdf, HasSubstr("<two />"));
  EXPECT_THAT(urdf, Not(HasSubstr("<zero")));
  EXPECT_THAT(urdf, HasSubstr("<generated a=\"given\" b=\"9\" />"));
  EXPECT_THAT(urdf, HasSubstr("<shape>\n    <cylinder radius=\"1\" />"));
  EXPECT_THAT(expand("<xacro:arg name=\"hand\" default=\"false\"/><xacro:if value=\"$(arg hand)\"><hand/></xacro:if>",
                     {{"hand", "true"}}),
              HasSubstr("<hand />"));
}

TEST_F(XacroTest, IncludesPackagesYamlAndSubstitutions) {
  write("pkg/package.xml", "<package><name>my_robot</name></package>");
  write("pkg/urdf/parts.xacro", R"XML(<robot xmlns:xacro="x">
    <xacro:property name="length" value="0.5"/>
    <xacro:macro name="arm" params="n"><link name="arm${n}" dir="$(dirname)"/></xacro:macro></robot>)XML");
  write("pkg/config/limits.yaml", "joint:\n  upper: !degrees 90\n  lower: !radians -1.5\n  flags: [true, null, 3]\n");
  write("pkg/urdf/robot.xacro", R"XML(<robot xmlns:xacro="x" name="r">
    <xacro:include filename="$(find my_robot)/urdf/parts.xacro"/>
    <xacro:include filename="parts.xacro" ns="other"/>
    <xacro:property name="limits" value="${xacro.load_yaml('../config/limits.yaml')}"/>
    <xacro:arm n="1"/>
    <xacro:other.arm n="2"/>
    <v a="${length} ${other.length}" b="${limits.joint.upper}" c="${limits['joint']['lower']}"
       d="${limits.joint.flags}" e="$(env LANG2MANIP_XACRO_TEST)" f="$(optenv LANG2MANIP_UNSET_VARIABLE fallback)"
       g="$(eval 6 * 7)"/></robot>)XML");
  ::setenv("LANG2MANIP_XACRO_TEST", "from-env", 1);
  const std::string urdf = expandXacroFile(directory_.path() / "pkg/urdf/robot.xacro");
  EXPECT_THAT(urdf, HasSubstr("<link name=\"arm1\" dir=\"" + (directory_.path() / "pkg/urdf").string() + "\""));
  EXPECT_THAT(urdf, HasSubstr("<link name=\"arm2\""));
  EXPECT_THAT(urdf, HasSubstr("a=\"0.5 0.5\" b=\"1.5707963267948966\" c=\"-1.5\" d=\"[True, None, 3]\""));
  EXPECT_THAT(urdf, HasSubstr("e=\"from-env\" f=\"fallback\" g=\"42\""));
  // The package found through LANG2MANIP_PACKAGE_PATH from anywhere.
  const fs::path elsewhere = write("elsewhere/robot.xacro", R"XML(<robot xmlns:xacro="x"><v p="$(find my_robot)"/></robot>)XML");
  ::setenv("LANG2MANIP_PACKAGE_PATH", directory_.path().string().c_str(), 1);
  EXPECT_THAT(expandXacroFile(elsewhere), HasSubstr("p=\"" + (directory_.path() / "pkg").string() + "\""));
  ::unsetenv("LANG2MANIP_PACKAGE_PATH");
}

TEST_F(XacroTest, EveryClassOfBadInputNamesFileLineAndMacro) {
  write("bad.yaml", "a: [1, 2\n");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"<a v=\"${undefined_name}\"/>", "robot.urdf.xacro:2: \"${undefined_name}\": name 'undefined_name' is not defined"},
      {"<xacro:nothing/>", "robot.urdf.xacro:2: unknown macro or xacro element \"xacro:nothing\""},
      {"<xacro:macro name=\"m\" params=\"\"><xacro:m/></xacro:macro><xacro:m/>", "nest more than 100 levels"},
      {"<xacro:include filename=\"robot.urdf.xacro\"/>", "nest more than 100 levels"},
      {"<xacro:include filename=\"missing.xacro\"/>", "missing.xacro: xacro file does not exist"},
      {"<xacro:include filename=\"$(find no_such_package)/x.xacro\"/>", "package 'no_such_package' not found"},
      {"<a v=\"${xacro.load_yaml('bad.yaml')}\"/>", "bad.yaml:2: malformed YAML"},
      {"<a v=\"${xacro.load_yaml('none.yaml')}\"/>", "none.yaml: YAML file does not exist"},
      {"<xacro:macro name=\"m\" params=\"a\"/><xacro:m b=\"1\"/>", "macro 'm' has no parameter 'b'"},
      {"<xacro:macro name=\"m\" params=\"a\"/><xacro:m/>", "macro 'm' needs parameter 'a'"},
      {"<xacro:macro name=\"m\" params=\"*b\"/><xacro:m/>", "macro 'm' needs a block for its parameter 'b'"},
      {"<xacro:if value=\"maybe\"><a/></xacro:if>", "<xacro:if> value \"maybe\" is 'maybe', not a boolean"},
      {"<xacro:property name=\"p\" value=\"${p + 1}\"/><a v=\"${p}\"/>", "property 'p' is defined in terms of itself"},
      {"<a v=\"$(arg nothing)\"/>", "undefined argument 'nothing'"},
      {"<a v=\"${1 / 0}\"/>", "division by zero"},
      {"<a v=\"${(1 + }\"/>", "robot.urdf.xacro:2"},
      {"<a v=\"${'abc' * 100000000}\"/>", "repetition of more than"},
      {"<xacro:macro name=\"m\" params=\"x\"><a v=\"${x.nothing}\"/></xacro:macro>\n<xacro:m x=\"1\"/>",
       "robot.urdf.xacro:2: \"${x.nothing}\": 'int' object has no attribute 'nothing' (in macro 'm' called at "},
      {"<xacro:insert_block name=\"nothing\"/>", "no block named \"nothing\""},
      {"<a v=\"$(anon x)\"/>", "$(anon ...) is not supported"},
  };
  for (const auto& [body, expected] : cases) {
    SCOPED_TRACE(body);
    EXPECT_THAT(error(body), HasSubstr(expected));
  }
}

TEST_F(XacroTest, ExponentialExpansionStopsAtTheElementBudget) {
  std::string body = "<xacro:macro name=\"m0\" params=\"\"><a/></xacro:macro>";
  for (int level = 1; level <= 30; ++level) {
    const std::string below = "<xacro:m" + std::to_string(level - 1) + "/>";
    body += "<xacro:macro name=\"m" + std::to_string(level) + "\" params=\"\">" + below + below + "</xacro:macro>";
  }
  EXPECT_THAT(error(body + "<xacro:m30/>"), HasSubstr("exceeds 100000 elements"));
}

/// Properties p1..pN, each made from the one before by `step` (with {} for the previous name).
std::string propertyChain(const std::string& first, const std::string& step, int count) {
  std::string body = "<xacro:property name=\"p0\" value=\"" + first + "\"/>";
  for (int i = 1; i <= count; ++i) {
    std::string value = step;
    for (std::size_t at = value.find("{}"); at != std::string::npos; at = value.find("{}")) {
      value.replace(at, 2, "p" + std::to_string(i - 1));
    }
    body += "<xacro:property name=\"p" + std::to_string(i) + "\" value=\"" + value + "\"/>";
  }
  return body;
}

TEST_F(XacroTest, MemoryAndTimeBombsStopWithAnErrorInBoundedWork) {
  std::string yaml = "a0: &a0 [lol, lol, lol, lol, lol, lol, lol, lol, lol]\n";
  for (int i = 1; i <= 12; ++i) {
    yaml += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [";
    for (int k = 0; k < 9; ++k) yaml += (k > 0 ? ", *a" : "*a") + std::to_string(i - 1);
    yaml += "]\n";
  }
  write("bomb.yaml", yaml);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {propertyChain("xxxxxxxxxxxxxxxx", "${{}}${{}}", 40) + "<a v=\"${p40}\"/>", "text longer than 16 MiB"},
      {propertyChain("${[0, 1, 2, 3, 4, 5, 6, 7, 8, 9]}", "${{} * 10}", 11) + "<a v=\"${len(p11)}\"/>",
       "list longer than 1000000 items"},
      {propertyChain("${[0] * 1000}", "${[{}] * 1000}", 7) + "<a v=\"${p7 == p7}\"/>", "million steps of work"},
      {propertyChain("${[0] * 1000}", "${[{}] * 1000}", 7) + "<a v=\"${len(str(p7))}\"/>", "text longer than 16 MiB"},
      {propertyChain("${[0] * 1000}", "${[{}] * 1000}", 7) + "<a v=\"${p6 in p7}\"/>", "million steps of work"},
      {"<a v=\"${len(str(xacro.load_yaml('bomb.yaml')))}\"/>", "bomb.yaml:1: YAML expands to more than 1000000 values"},
  };
  for (const auto& [body, expected] : cases) {
    SCOPED_TRACE(body.substr(0, 200));
    EXPECT_THAT(error(body), HasSubstr(expected));
  }
  // A shared list is repeated without copying its items: real descriptions' idioms stay cheap.
  EXPECT_THAT(expand(propertyChain("${[0] * 1000}", "${[{}] * 1000}", 7) + "<a v=\"${len(p7)}\"/>"), HasSubstr("v=\"1000\""));
}

TEST(XacroArguments, NameColonEqualsValue) {
  EXPECT_EQ(parseXacroArgument("hand:=true"), (std::pair<std::string, std::string>{"hand", "true"}));
  EXPECT_EQ(parseXacroArgument("xyz:=0 0 1"), (std::pair<std::string, std::string>{"xyz", "0 0 1"}));
  EXPECT_THROW(parseXacroArgument("hand=true"), InputError);
  EXPECT_THROW(parseXacroArgument(":=true"), InputError);
  EXPECT_TRUE(isXacroFile("panda.urdf.xacro"));
  EXPECT_FALSE(isXacroFile("panda.urdf"));
}

// ------------------------------------------------------------------ official descriptions

/// The pose of `link` at configuration zero (every variable 0) of `model`.
Pose zeroPose(const RobotModel& model, const std::string& link) {
  return model.linkPoses(VectorX::Zero(model.variableCount()))[static_cast<std::size_t>(model.linkIndex(link))];
}

TEST(XacroOfficialDescriptions, PandaAndFr3WithHandExpandLoadAndMatchTheirKinematics) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  for (const char* robot : {"panda/panda.urdf.xacro", "fr3/fr3.urdf.xacro"}) {
    SCOPED_TRACE(robot);
    UrdfReadOptions options;
    options.xacroArguments = {{"hand", "true"}};
    const RobotModelPtr model = readUrdfFile(shared / "robots/franka_description/robots" / robot, options);
    EXPECT_EQ(model->links().size(), 22u);  // link0..8, their _sc links, hand, hand_sc, hand_tcp, 2 fingers
    EXPECT_EQ(model->joints().size(), 21u);
    EXPECT_EQ(model->variableCount(), 8);  // 7 arm joints and one finger (the other mimics it)
    const std::string arm = std::string(robot).substr(0, std::string(robot).find('/'));
    // Franka's published kinematics: the flange 0.088 m forward and 0.926 m up at q = 0, the
    // hand's TCP 0.1034 m below it.
    const Pose flange = zeroPose(*model, arm + "_link8");
    EXPECT_NEAR((flange.translation() - Vector3(0.088, 0.0, 0.926)).norm(), 0.0, 1e-9);
    const Pose tcp = zeroPose(*model, arm + "_hand_tcp");
    EXPECT_NEAR((tcp.translation() - Vector3(0.088, 0.0, 0.926 - 0.1034)).norm(), 0.0, 1e-9);
    EXPECT_GT(model->links()[static_cast<std::size_t>(model->linkIndex(arm + "_link1"))].collisions.size(), 0u);
  }
  UrdfReadOptions withoutHand;
  const RobotModelPtr bare = readUrdfFile(shared / "robots/franka_description/robots/panda/panda.urdf.xacro", withoutHand);
  EXPECT_EQ(bare->variableCount(), 7);
}

TEST(XacroOfficialDescriptions, Ur5eAndUr10eExpandLoadAndMatchTheirDhParameters) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  // Published DH parameters (d1, a2, a3, d4, d5, d6): at q = 0 the tool flange is at
  // (a2 + a3, -(d4 + d6), d1 - d5) in the DH base frame, and base_link is that frame turned half
  // a turn about z.
  const std::map<std::string, std::array<double, 6>> dh = {
      {"ur5e", {0.1625, -0.425, -0.3922, 0.1333, 0.0997, 0.0996}},
      {"ur10e", {0.1807, -0.6127, -0.57155, 0.17415, 0.11985, 0.11655}}};
  for (const auto& [name, p] : dh) {
    SCOPED_TRACE(name);
    const RobotModelPtr model = readUrdfFile(shared / "robots/ur_description/urdf" / (name + ".xacro"));
    EXPECT_EQ(model->links().size(), 11u);
    EXPECT_EQ(model->joints().size(), 10u);
    EXPECT_EQ(model->variableCount(), 6);
    const Vector3 expected(-(p[1] + p[2]), p[3] + p[5], p[0] - p[4]);
    EXPECT_NEAR((zeroPose(*model, "tool0").translation() - expected).norm(), 0.0, 1e-9)
        << zeroPose(*model, "tool0").translation().transpose();
  }
}

TEST(XacroOfficialDescriptions, KauthamProblemRobotWithXacroArgsReadsAndWritesBack) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const test::TempDirectory directory;
  const fs::path panda = shared / "robots/franka_description/robots/panda/panda.urdf.xacro";
  const fs::path file = directory.path() / "problem.xml";
  std::ofstream(file) << "<Problem name=\"xacro\">\n  <Robot robot=\"" << panda.string() << "\" scale=\"1\">\n"
                      << "    <Home TH=\"0\" WX=\"0\" WY=\"0\" WZ=\"1\" X=\"0\" Y=\"0\" Z=\"0\"/>\n"
                      << "    <XacroArg name=\"hand\" value=\"true\"/>\n  </Robot>\n</Problem>\n";
  const KauthamProblem problem = readKauthamProblem(file);
  EXPECT_EQ(problem.scene.robots().front().model->variableCount(), 8);
  EXPECT_EQ(problem.robots.front().xacroArguments.at("hand"), "true");
  KauthamReadOptions without;
  without.xacroArguments = {{"hand", "false"}};  // the command line's --xacro-arg wins
  EXPECT_EQ(readKauthamProblem(file, without).scene.robots().front().model->variableCount(), 7);
  const fs::path written = writeKauthamProblem(problem, directory.path() / "out", "problem");
  EXPECT_THAT(test::readFileText(written), HasSubstr("<XacroArg name=\"hand\" value=\"true\"/>"));
  EXPECT_EQ(readKauthamProblem(written).scene.robots().front().model->variableCount(), 8);
}

}  // namespace
}  // namespace lang2manip
