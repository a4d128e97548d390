#include "lang2manip/model/urdf_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>

#include "lang2manip/model/urdf_structure_check.hpp"
#include "model_test_support.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;
using test::errorMessage;
using test::twoJointUrdf;
using test::writeText;

TEST(UrdfReader, ReadsLinksInAnyOrderWithLimitsGeometryAndMaterials) {
  const RobotModelPtr model = readUrdfString(twoJointUrdf(), "arm.urdf", ".");
  EXPECT_EQ(model->name(), "arm");
  EXPECT_EQ(model->links()[static_cast<std::size_t>(model->rootLink())].name, "base");
  EXPECT_EQ(model->variableNames(), (std::vector<std::string>{"shoulder", "elbow"}));
  // Soft limits from the safety controller replace <limit>.
  EXPECT_DOUBLE_EQ(model->lowerLimits()[1], -1.9);
  EXPECT_DOUBLE_EQ(model->upperLimits()[1], 1.8);
  EXPECT_TRUE(model->joints()[1].limits.soft);
  EXPECT_DOUBLE_EQ(model->velocityLimits()[0], 2.0);
  const Link& tip = model->links()[static_cast<std::size_t>(model->linkIndex("tip"))];
  ASSERT_EQ(tip.collisions.size(), 1U);
  EXPECT_TRUE(std::get<Box>(tip.collisions[0].geometry).size.isApprox(Vector3(0.1, 0.2, 0.3)));
  EXPECT_TRUE(tip.collisions[0].origin.translation().isApprox(Vector3(0, 0, 0.1)));
  ASSERT_TRUE(tip.visuals[0].material.has_value());
  EXPECT_EQ(tip.visuals[0].material->name, "red");
  EXPECT_TRUE(tip.visuals[0].material->rgba.isApprox(Vector4(1, 0, 0, 1)));
}

TEST(UrdfReader, ScaleMultipliesGeometryOriginsAndPrismaticLimitsOnly) {
  const std::string slider = R"(
  <link name="carriage"/>
  <joint name="slide" type="prismatic"><parent link="tip"/><child link="carriage"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.2" velocity="1" effort="1"/></joint>)";
  UrdfReadOptions options;
  options.scale = 0.5;
  const RobotModelPtr model = readUrdfString(twoJointUrdf(slider), "arm.urdf", ".", options);
  EXPECT_TRUE(model->joints()[0].origin.translation().isApprox(Vector3(0, 0, 0.15)));
  EXPECT_DOUBLE_EQ(model->upperLimits()[0], 1.5);  // revolute: not scaled
  EXPECT_DOUBLE_EQ(model->upperLimits()[model->variableIndex("slide")], 0.1);
  const Link& tip = model->links()[static_cast<std::size_t>(model->linkIndex("tip"))];
  EXPECT_TRUE(std::get<Box>(tip.collisions[0].geometry).size.isApprox(Vector3(0.05, 0.1, 0.15)));
}

TEST(UrdfReader, MimicJointsAreVariablesOnlyWhenIgnored) {
  const std::string mimic = R"(
  <link name="finger"/>
  <joint name="finger_joint" type="revolute"><parent link="tip"/><child link="finger"/>
    <limit lower="-1" upper="1" velocity="1" effort="1"/><mimic joint="elbow" multiplier="2"/></joint>)";
  EXPECT_EQ(readUrdfString(twoJointUrdf(mimic), "a.urdf", ".")->variableCount(), 2);
  UrdfReadOptions kautham;
  kautham.ignoreMimic = true;
  EXPECT_EQ(readUrdfString(twoJointUrdf(mimic), "a.urdf", ".", kautham)->variableCount(), 3);
}

TEST(UrdfReader, AcceptsMaterialsWithoutNameAsKauthamDoes) {
  const std::string urdf = R"(<robot name="box"><link name="base"><visual><geometry><box size="1 1 1"/></geometry>
    <material><color rgba="0 1 0 1"/></material></visual>
    <collision><geometry><box size="1 1 1"/></geometry></collision></link></robot>)";
  const RobotModelPtr model = readUrdfString(urdf, "box.urdf", ".");
  EXPECT_EQ(model->links()[0].visuals.size(), 1U);
  EXPECT_EQ(model->links()[0].collisions.size(), 1U);
}

std::string meshUrdf(const std::string& reference) {
  return R"(<robot name="m"><link name="base"><collision><geometry><mesh filename=")" + reference +
         R"(" scale="2 2 2"/></geometry></collision></link></robot>)";
}

const char* kTetrahedronStl = R"(solid t
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 0 1 0
 endloop
endfacet
facet normal 0 -1 0
 outer loop
  vertex 0 0 0
  vertex 0 0 1
  vertex 1 0 0
 endloop
endfacet
endsolid t
)";

TEST(UrdfReader, ResolvesRelativeAndPackageMeshes) {
  const test::TempDirectory directory;
  writeText(directory.path() / "pkgs" / "mypkg" / "meshes" / "t.stl", kTetrahedronStl);
  writeText(directory.path() / "robot" / "meshes" / "t.stl", kTetrahedronStl);
  writeText(directory.path() / "robot" / "rel.urdf", meshUrdf("meshes/t.stl"));
  const RobotModelPtr relative = readUrdfFile(directory.path() / "robot" / "rel.urdf");
  const auto& mesh = std::get<MeshGeometry>(relative->links()[0].collisions[0].geometry);
  ASSERT_TRUE(mesh.mesh);
  EXPECT_EQ(mesh.mesh->triangles.size(), 2U);
  EXPECT_TRUE(mesh.scale.isApprox(Vector3(2, 2, 2)));

  writeText(directory.path() / "robot" / "pkg.urdf", meshUrdf("package://mypkg/meshes/t.stl"));
  UrdfReadOptions options;
  options.packagePaths = {directory.path() / "pkgs"};
  EXPECT_NO_THROW(readUrdfFile(directory.path() / "robot" / "pkg.urdf", options));
  EXPECT_THAT(errorMessage([&] { readUrdfFile(directory.path() / "robot" / "pkg.urdf"); }),
              HasSubstr("mesh \"package://mypkg/meshes/t.stl\" resolves to no readable file (no package search path given)"));
  // A package found as an ancestor directory of the URDF.
  writeText(directory.path() / "pkgs" / "mypkg" / "urdf" / "r.urdf", meshUrdf("package://mypkg/meshes/t.stl"));
  EXPECT_NO_THROW(readUrdfFile(directory.path() / "pkgs" / "mypkg" / "urdf" / "r.urdf"));
}

TEST(UrdfReader, ReportsMissingMeshAndMeshWithoutTriangles) {
  const test::TempDirectory directory;
  writeText(directory.path() / "missing.urdf", meshUrdf("meshes/none.stl"));
  EXPECT_THAT(errorMessage([&] { readUrdfFile(directory.path() / "missing.urdf"); }),
              HasSubstr("(link \"base\"): mesh \"meshes/none.stl\" resolves to no readable file (tried: "));
  // A reference to something that is not a regular file says what it is.
  writeText(directory.path() / "device.urdf", meshUrdf("/dev/zero"));
  EXPECT_THAT(errorMessage([&] { readUrdfFile(directory.path() / "device.urdf"); }),
              HasSubstr("tried: /dev/zero (is a character device, not a regular file)"));
  std::filesystem::create_directory(directory.path() / "folder.stl");
  writeText(directory.path() / "folder.urdf", meshUrdf("folder.stl"));
  EXPECT_THAT(errorMessage([&] { readUrdfFile(directory.path() / "folder.urdf"); }),
              HasSubstr("folder.stl (is a directory, not a file)"));
  writeText(directory.path() / "empty.obj", "v 0 0 0\nv 1 0 0\n");
  writeText(directory.path() / "empty.urdf", meshUrdf("empty.obj"));
  EXPECT_THAT(errorMessage([&] { readUrdfFile(directory.path() / "empty.urdf"); }),
              HasSubstr("empty.obj"));
}

struct BadUrdf {
  const char* name;
  std::string xml;
  const char* expected;
};

class UrdfReaderBadInput : public ::testing::TestWithParam<BadUrdf> {};

TEST_P(UrdfReaderBadInput, ReportsFileLineAndProblem) {
  EXPECT_THAT(errorMessage([] { readUrdfString(GetParam().xml, "bad.urdf", "."); }),
              HasSubstr(GetParam().expected));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, UrdfReaderBadInput,
    ::testing::Values(
        BadUrdf{"Malformed", "<robot name=\"r\">\n<link name=\"a\">\n</robot>", "bad.urdf:3: malformed XML"},
        BadUrdf{"NotUrdf", "<Problem/>", "not a URDF"},
        BadUrdf{"NoLinks", "<robot name=\"r\"/>", "defines no <link>"},
        BadUrdf{"TwoRoots", "<robot name=\"r\">\n<link name=\"a\"/>\n<link name=\"b\"/>\n</robot>",
                "bad.urdf:3: the URDF has 2 root links (a, b)"},
        BadUrdf{"Cycle",
                "<robot name=\"r\"><link name=\"root\"/><link name=\"a\"/><link name=\"b\"/>\n"
                "<joint name=\"ra\" type=\"fixed\"><parent link=\"root\"/><child link=\"a\"/></joint>\n"
                "<joint name=\"ab\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"
                "<joint name=\"ba\" type=\"fixed\"><parent link=\"b\"/><child link=\"a\"/></joint></robot>",
                "has two parent joints"},
        BadUrdf{"PureCycle",
                "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/>\n"
                "<joint name=\"ab\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"
                "<joint name=\"ba\" type=\"fixed\"><parent link=\"b\"/><child link=\"a\"/></joint></robot>",
                "cycle"},
        BadUrdf{"UnknownLink",
                "<robot name=\"r\"><link name=\"a\"/>\n<joint name=\"j\" type=\"fixed\"><parent link=\"a\"/>"
                "<child link=\"ghost\"/></joint></robot>",
                "bad.urdf:2: joint \"j\" refers to link \"ghost\", which is not defined"},
        BadUrdf{"NanOrigin",
                "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/>\n<joint name=\"j\" type=\"fixed\">"
                "<origin xyz=\"0 nan 0\"/><parent link=\"a\"/><child link=\"b\"/></joint></robot>",
                "bad.urdf:2: <origin> attribute xyz must be a finite number"},
        BadUrdf{"InfiniteLimit",
                "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" type=\"revolute\">"
                "<parent link=\"a\"/><child link=\"b\"/>\n<limit lower=\"-inf\" upper=\"1\" velocity=\"1\" "
                "effort=\"1\"/></joint></robot>",
                "bad.urdf:2: <limit> attribute lower must be a finite number"},
        BadUrdf{"UnknownGeometry",
                "<robot name=\"r\"><link name=\"a\"><collision><geometry>\n<capsule radius=\"1\" length=\"1\"/>"
                "</geometry></collision></link></robot>",
                "bad.urdf:2: unknown geometry <capsule>"},
        BadUrdf{"GeometryMissing", "<robot name=\"r\"><link name=\"a\">\n<visual/></link></robot>",
                "bad.urdf:2: <visual> has no <geometry>"},
        BadUrdf{"DuplicateLink", "<robot name=\"r\"><link name=\"a\"/>\n<link name=\"a\"/></robot>",
                "bad.urdf:2: link \"a\" is defined twice"},
        BadUrdf{"TabInLinkName", "<robot name=\"r\">\n<link name=\"a\tb\"/></robot>",
                "bad.urdf:2: link name \"a b\" contains whitespace or a control character"},
        BadUrdf{"CarriageReturnInLinkName", "<robot name=\"r\">\n<link name=\"a\rb\"/></robot>",
                "bad.urdf:2: link name"},
        BadUrdf{"EscapedTabInLinkName", "<robot name=\"r\">\n<link name=\"a&#9;b\"/></robot>",
                "bad.urdf:2: link name \"a\\tb\" contains whitespace"},
        BadUrdf{"EscapedCarriageReturnInLinkName", "<robot name=\"r\">\n<link name=\"a&#13;\"/></robot>",
                "bad.urdf:2: link name \"a\\r\" contains whitespace"},
        BadUrdf{"TrailingSpaceInLinkName", "<robot name=\"r\">\n<link name=\"a \"/></robot>",
                "bad.urdf:2: link name \"a \" contains whitespace"},
        BadUrdf{"ControlCharacterInLinkName", "<robot name=\"r\">\n<link name=\"a&#1;\"/></robot>",
                "bad.urdf:2: link name \"a\\x01\" contains whitespace or a control character"},
        BadUrdf{"EmptyLinkName", "<robot name=\"r\">\n<link name=\"\"/></robot>",
                "bad.urdf:2: link name is empty"},
        BadUrdf{"TabInJointName",
                "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/>\n<joint name=\"j\t1\" type=\"fixed\">"
                "<parent link=\"a\"/><child link=\"b\"/></joint></robot>",
                "bad.urdf:2: joint name \"j 1\" contains whitespace"},
        BadUrdf{"TabInParentLink",
                "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" type=\"fixed\">\n"
                "<parent link=\"a&#9;\"/><child link=\"b\"/></joint></robot>",
                "bad.urdf:2: joint \"j\" parent link \"a\\t\" contains whitespace"},
        BadUrdf{"TabInMimicJoint",
                "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>"
                "<joint name=\"j\" type=\"prismatic\"><parent link=\"a\"/><child link=\"b\"/>"
                "<limit lower=\"0\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>"
                "<joint name=\"k\" type=\"prismatic\"><parent link=\"a\"/><child link=\"c\"/>"
                "<limit lower=\"0\" upper=\"1\" effort=\"1\" velocity=\"1\"/>\n<mimic joint=\"j&#9;\"/>"
                "</joint></robot>",
                "bad.urdf:2: joint \"k\" mimic joint \"j\\t\" contains whitespace"},
        BadUrdf{"MimicOfUnknownJoint",
                "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/>"
                "<joint name=\"k\" type=\"prismatic\"><parent link=\"a\"/><child link=\"b\"/>"
                "<limit lower=\"0\" upper=\"1\" effort=\"1\" velocity=\"1\"/>\n<mimic joint=\"ghost\"/>"
                "</joint></robot>",
                "bad.urdf:2: joint \"k\" mimics joint \"ghost\", which is not defined"},
        BadUrdf{"HugeBox",
                "<robot name=\"r\">\n<link name=\"a\"><collision><geometry><box size=\"1e300 1 1\"/>"
                "</geometry></collision></link></robot>",
                "bad.urdf:2: link \"a\" collision 1 box size 1e+300 m is outside [1e-06, 10000] m"},
        BadUrdf{"HugeCylinder",
                "<robot name=\"r\">\n<link name=\"a\"><visual><geometry><cylinder radius=\"0.1\" "
                "length=\"1e308\"/></geometry></visual></link></robot>",
                "bad.urdf:2: link \"a\" visual 1 cylinder length 1e+308 m is outside"},
        BadUrdf{"TinySphere",
                "<robot name=\"r\">\n<link name=\"a\"><collision><geometry><sphere radius=\"1e-9\"/>"
                "</geometry></collision></link></robot>",
                "bad.urdf:2: link \"a\" collision 1 sphere radius 1e-09 m is outside"},
        BadUrdf{"FarShapeOrigin",
                "<robot name=\"r\">\n<link name=\"a\"><collision><origin xyz=\"0 0 2e4\"/><geometry>"
                "<sphere radius=\"1\"/></geometry></collision></link></robot>",
                "bad.urdf:2: link \"a\" collision 1 origin (0, 0, 20000) m is more than 10000 m from the origin"},
        BadUrdf{"FarJointOrigin",
                "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/>\n<joint name=\"j\" type=\"fixed\">"
                "<origin xyz=\"1e300 0 0\"/><parent link=\"a\"/><child link=\"b\"/></joint></robot>",
                "bad.urdf:2: joint \"j\" origin (1e+300, 0, 0) m is more than 10000 m"},
        BadUrdf{"HugePrismaticLimit",
                "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" type=\"prismatic\">"
                "<parent link=\"a\"/><child link=\"b\"/><limit lower=\"0\" upper=\"1e300\" velocity=\"1\" "
                "effort=\"1\"/></joint></robot>",
                "joint \"j\" limits (lower, upper, 0) (0, 1e+300, 0) m is more than 10000 m"},
        BadUrdf{"BadJointType",
                "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" type=\"wobbly\">"
                "<parent link=\"a\"/><child link=\"b\"/></joint></robot>",
                "urdfdom rejected the URDF"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(UrdfReader, RefusesDeeplyNestedXmlBeforeAnyRecursiveReader) {
  std::string nested;
  for (int i = 0; i < 100000; ++i) nested += "<a>";
  for (int i = 0; i < 100000; ++i) nested += "</a>";
  const std::string xml = "<robot name=\"r\">\n<link name=\"l\">" + nested + "</link></robot>";
  EXPECT_THAT(errorMessage([&] { readUrdfString(xml, "deep.urdf", "."); }),
              HasSubstr("deep.urdf:2: URDF nests elements more than 100 levels deep"));
}

/// A URDF of `links` links: each hangs from the one before (a chain) or all from the first (a star).
std::string generatedTree(int links, bool star) {
  std::string urdf = "<robot name=\"big\"><link name=\"l0\"/>";
  for (int i = 1; i < links; ++i) {
    const std::string name = "l" + std::to_string(i);
    const std::string parent = star ? "l0" : "l" + std::to_string(i - 1);
    urdf += "<link name=\"" + name + "\"><collision><geometry><box size=\"0.01 0.01 0.01\"/></geometry></collision></link>"
            "<joint name=\"j" + std::to_string(i) + "\" type=\"revolute\"><parent link=\"" + parent + "\"/><child link=\"" + name +
            "\"/><origin xyz=\"0 0 0.1\"/><axis xyz=\"0 1 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>";
  }
  return urdf + "</robot>";
}

TEST(UrdfReader, LargeTreesAreReadAndUnderstoodInWorkLinearInTheirSize) {
  // A 2000-link chain: one arm of 1999 joints (reading and inference were cubic in the size).
  const RobotModelPtr chain = readUrdfString(generatedTree(2000, false), "chain.urdf", ".");
  ASSERT_EQ(chain->semantics().manipulators.size(), 1U);
  EXPECT_EQ(chain->semantics().manipulators[0].armJoints.size(), 1999U);
  // Beyond the bounds: a clear error, not minutes of work.
  EXPECT_THAT(errorMessage([] { (void)readUrdfString(generatedTree(kMaxRobotLinks + 1, false), "huge.urdf", "."); }),
              HasSubstr("the URDF has more than 4096 links"));
  EXPECT_THAT(errorMessage([] { (void)readUrdfString(generatedTree(200, true), "star.urdf", "."); }),
              HasSubstr("its tree ends in 199 chains of movable joints (more than 64 arms): name its arms in an SRDF"));
}

TEST(UrdfReader, ReportsMissingFile) {
  EXPECT_THAT(errorMessage([] { readUrdfFile("/nonexistent/robot.urdf"); }),
              HasSubstr("/nonexistent/robot.urdf: URDF file does not exist"));
  EXPECT_THAT(errorMessage([] { readUrdfFile("/tmp"); }), HasSubstr("/tmp: URDF file is a directory, not a file"));
  // Read whole, a device would never end: refused before reading.
  EXPECT_THAT(errorMessage([] { readUrdfFile("/dev/zero"); }),
              HasSubstr("/dev/zero: URDF file is a character device, not a regular file"));
}

TEST(UrdfReader, ReadsSiblingSrdfOrInfersSemantics) {
  const test::TempDirectory directory;
  writeText(directory.path() / "arm.urdf", test::twoJointUrdf());
  const RobotModelPtr inferred = readUrdfFile(directory.path() / "arm.urdf");
  EXPECT_TRUE(inferred->semantics().inferred);
  ASSERT_EQ(inferred->semantics().manipulators.size(), 1U);
  EXPECT_EQ(inferred->semantics().manipulators[0].armJoints,
            (std::vector<std::string>{"shoulder", "elbow"}));
  writeText(directory.path() / "arm.srdf", R"(<robot name="arm">
    <group name="arm"><chain base_link="base" tip_link="tip"/></group>
    <group_state name="home" group="arm"><joint name="elbow" value="0.7"/></group_state></robot>)");
  const RobotModelPtr described = readUrdfFile(directory.path() / "arm.urdf");
  EXPECT_FALSE(described->semantics().inferred);
  EXPECT_NEAR(described->namedConfiguration("home")[described->variableIndex("elbow")], 0.7, 1e-12);
}

}  // namespace
}  // namespace lang2manip
