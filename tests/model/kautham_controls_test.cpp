// Kautham control sets (.cntr): reading, the normalized DOF values p_d, writing and errors.
// p_d = clamp(sum_j eigValue_j * k_dj * (c_j - 0.5) + offset_d, 0, 1), offset 0.5 by default.
#include "lang2manip/model/kautham_controls.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "model_test_support.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

using test::errorMessage;
using ::testing::AllOf;
using ::testing::DoubleNear;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr double kControlsTolerance = 1e-12;

// Line 4: the first Offset DOF; line 9: control "grip".
const char* const kGripper = R"(<?xml version="1.0"?>
<ControlSet>
  <Offset>
    <DOF name="hand/left" value="0.2"/>
    <DOF name="hand/right" value="0.7"/>
    <DOF name="hand/X3" value="0.5"/>
  </Offset>
  <Control name="wrist" eigValue="1.0"><DOF name="hand/wrist" value="1.0"/></Control>
  <Control name="grip" eigValue="0.5">
    <DOF name="hand/left" value="1.0"/>
    <DOF name="hand/right" value="-2.0"/>
  </Control>
  <Control name="both"><DOF name="hand/wrist" value="0.5"/><DOF name="hand/left" value="0.5"/></Control>
</ControlSet>
)";

std::vector<std::string> dofNames(const ControlSet& set) {
  std::vector<std::string> names;
  for (const ControlledDof& dof : set.dofs) names.push_back(dof.fullName());
  return names;
}

std::string controlError(const std::string& xml) {
  return errorMessage([&] { (void)readControlString(xml, "bad.cntr"); });
}

TEST(KauthamControls, ReadsOffsetsControlsAndCouplingsInFileOrder) {
  const ControlSet set = readControlString(kGripper, "gripper.cntr");
  EXPECT_EQ(set.source, "gripper.cntr");
  // Offset DOFs first, then DOFs first named in a control.
  EXPECT_THAT(dofNames(set), ElementsAre("hand/left", "hand/right", "hand/X3", "hand/wrist"));
  EXPECT_DOUBLE_EQ(set.dofs[0].offset, 0.2);
  EXPECT_DOUBLE_EQ(set.dofs[1].offset, 0.7);
  EXPECT_DOUBLE_EQ(set.dofs[3].offset, 0.5);  // no Offset entry
  EXPECT_EQ(set.dofs[0].line, 4);
  EXPECT_THAT(set.controlNames(), ElementsAre("wrist", "grip", "both"));
  EXPECT_DOUBLE_EQ(set.controls[1].eigValue, 0.5);
  EXPECT_DOUBLE_EQ(set.controls[2].eigValue, 1.0);  // eigValue absent
  EXPECT_EQ(set.controls[1].line, 9);
  using Coefficient = std::pair<int, double>;
  EXPECT_THAT(set.controls[1].coefficients, ElementsAre(Coefficient{0, 1.0}, Coefficient{1, -2.0}));
  EXPECT_THAT(set.controls[2].coefficients, ElementsAre(Coefficient{3, 0.5}, Coefficient{0, 0.5}));
  EXPECT_EQ(set.findDof("hand", "right"), 1);
  EXPECT_EQ(set.findDof("hand", "thumb"), -1);
  EXPECT_EQ(set.findDof("arm", "right"), -1);
}

TEST(KauthamControls, DofNamesAreSplitAtTheLastSlash) {
  const ControlSet set = readControlString(
      "<ControlSet><Control name=\"c\"><DOF name=\"ns/robot/link_1\" value=\"1\"/></Control></ControlSet>",
      "x.cntr");
  EXPECT_EQ(set.dofs[0].entity, "ns/robot");
  EXPECT_EQ(set.dofs[0].dof, "link_1");
}

TEST(KauthamControls, DofValuesFollowTheFormula) {
  const ControlSet set = readControlString(kGripper, "gripper.cntr");
  // c = (wrist 0.9, grip 0.7, both 0.1)
  //   left:  0.2 + 0.5*1*(0.7-0.5) + 1*0.5*(0.1-0.5) = 0.2 + 0.1 - 0.2 = 0.1
  //   right: 0.7 + 0.5*(-2)*(0.7-0.5)              = 0.7 - 0.2       = 0.5
  //   X3:    0.5 (offset only)
  //   wrist: 0.5 + 1*(0.9-0.5) + 0.5*(0.1-0.5)     = 0.5 + 0.4 - 0.2 = 0.7
  EXPECT_THAT(set.dofValues({0.9, 0.7, 0.1}, "c"),
              ElementsAre(DoubleNear(0.1, kControlsTolerance), DoubleNear(0.5, kControlsTolerance),
                          DoubleNear(0.5, kControlsTolerance), DoubleNear(0.7, kControlsTolerance)));
  // All controls at 0.5: the offsets.
  EXPECT_THAT(set.dofValues({0.5, 0.5, 0.5}, "c"), ElementsAre(0.2, 0.7, 0.5, 0.5));
}

TEST(KauthamControls, DofValuesAreClampedToTheUnitInterval) {
  const ControlSet set = readControlString(kGripper, "gripper.cntr");
  // c = (1, 0, 1)
  //   left:  0.2 + 0.5*(-0.5) + 0.5*0.5 = 0.2       right: 0.7 + 0.5*(-2)*(-0.5) = 1.2 -> 1
  //   wrist: 0.5 + 0.5 + 0.5*0.5 = 1.25 -> 1
  EXPECT_THAT(set.dofValues({1.0, 0.0, 1.0}, "c"), ElementsAre(DoubleNear(0.2, kControlsTolerance), 1.0, 0.5, 1.0));
  // c = (0, 1, 0)
  //   left:  0.2 + 0.25 - 0.25 = 0.2                right: 0.7 - 0.5 = 0.2
  //   wrist: 0.5 - 0.5 - 0.25 = -0.25 -> 0
  EXPECT_THAT(set.dofValues({0.0, 1.0, 0.0}, "c"),
              ElementsAre(DoubleNear(0.2, kControlsTolerance), DoubleNear(0.2, kControlsTolerance), 0.5, 0.0));
}

TEST(KauthamControls, DofValuesRejectWrongSizeAndValuesOutsideTheUnitInterval) {
  const ControlSet set = readControlString(kGripper, "gripper.cntr");
  EXPECT_THAT(errorMessage([&] {
                (void)set.dofValues({0.5, 0.5}, "the goal");
              }),
              AllOf(HasSubstr("the goal has 2 control values"), HasSubstr("gripper.cntr has 3")));
  EXPECT_THAT(
      errorMessage([&] {
        (void)set.dofValues({0.5, 1.5, 0.5}, "the goal");
      }),
      AllOf(HasSubstr("the goal"), HasSubstr("1.5"), HasSubstr("\"grip\""), HasSubstr("outside [0, 1]")));
  EXPECT_THAT(errorMessage([&] {
                (void)set.dofValues({-0.25, 0.5, 0.5}, "init");
              }),
              HasSubstr("control \"wrist\" is outside [0, 1]"));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(errorMessage([&] { (void)set.dofValues({0.5, 0.5, nan}, "init"); }), HasSubstr("\"both\""));
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THAT(errorMessage([&] { (void)set.dofValues({inf, 0.5, 0.5}, "init"); }), HasSubstr("\"wrist\""));
}

TEST(KauthamControls, WriteThenReadGivesTheSameControlSet) {
  const ControlSet original = readControlString(kGripper, "gripper.cntr");
  const ControlSet copy = readControlString(writeControlString(original), "copy.cntr");
  ASSERT_EQ(copy.dofs.size(), original.dofs.size());
  for (std::size_t d = 0; d < original.dofs.size(); ++d) {
    EXPECT_EQ(copy.dofs[d].fullName(), original.dofs[d].fullName());
    EXPECT_EQ(copy.dofs[d].offset, original.dofs[d].offset);
  }
  ASSERT_EQ(copy.controls.size(), original.controls.size());
  for (std::size_t j = 0; j < original.controls.size(); ++j) {
    EXPECT_EQ(copy.controls[j].name, original.controls[j].name);
    EXPECT_EQ(copy.controls[j].eigValue, original.controls[j].eigValue);
    EXPECT_EQ(copy.controls[j].coefficients, original.controls[j].coefficients);
  }
  for (const std::vector<double>& c :
       {std::vector<double>{0.9, 0.7, 0.1}, std::vector<double>{0.0, 1.0, 0.3}}) {
    EXPECT_EQ(copy.dofValues(c, "c"), original.dofValues(c, "c"));
  }
}

TEST(KauthamControls, WritingKeepsExactNumbersAndEscapesNames) {
  ControlSet set;
  set.dofs.push_back(ControlledDof{"R&D <arm>", "link \"1\"", 0.1 + 0.2, 0});
  set.controls.push_back(Control{"a&b", 1.0 / 3.0, {{0, -0.7}}, 0});
  const ControlSet copy = readControlString(writeControlString(set), "copy.cntr");
  ASSERT_EQ(copy.dofs.size(), 1U);
  EXPECT_EQ(copy.dofs[0].entity, "R&D <arm>");
  EXPECT_EQ(copy.dofs[0].dof, "link \"1\"");
  EXPECT_EQ(copy.dofs[0].offset, 0.1 + 0.2);
  EXPECT_EQ(copy.controls[0].name, "a&b");
  EXPECT_EQ(copy.controls[0].eigValue, 1.0 / 3.0);
  EXPECT_EQ(copy.controls[0].coefficients[0].second, -0.7);
}

TEST(KauthamControls, ReadControlFileChecksTheExtensionAndTheFile) {
  const test::TempDirectory directory;
  const std::filesystem::path good = directory.path() / "g.cntr";
  test::writeText(good, kGripper);
  const ControlSet set = readControlFile(good);
  EXPECT_EQ(set.source, good.string());
  EXPECT_EQ(set.controls.size(), 3U);

  const std::filesystem::path xml = directory.path() / "g.xml";
  test::writeText(xml, kGripper);
  EXPECT_THAT(errorMessage([&] { (void)readControlFile(xml); }),
              AllOf(HasSubstr(xml.string()), HasSubstr(".cntr"), HasSubstr("\".xml\"")));
  const std::filesystem::path missing = directory.path() / "none.cntr";
  EXPECT_THAT(errorMessage([&] { (void)readControlFile(missing); }),
              AllOf(HasSubstr(missing.string()), HasSubstr("does not exist")));
}

TEST(KauthamControls, MalformedTextNamesTheFileAndLine) {
  EXPECT_THAT(controlError("<ControlSet>\n  <Control name=\"a\">\n</ControlSet>\n"),
              AllOf(HasSubstr("bad.cntr:3"), HasSubstr("malformed XML")));
  EXPECT_THAT(controlError("<?xml version=\"1.0\"?>\n<Problem/>\n"),
              AllOf(HasSubstr("bad.cntr:2"), HasSubstr("not <ControlSet>")));
}

TEST(KauthamControls, BadDofsAndControlsNameTheLine) {
  EXPECT_THAT(
      controlError(
          "<ControlSet>\n<Control name=\"a\">\n<DOF name=\"link\" value=\"1\"/></Control></ControlSet>"),
      AllOf(HasSubstr("bad.cntr:3"), HasSubstr("\"link\" is not of the form")));
  EXPECT_THAT(controlError("<ControlSet>\n<Offset><DOF name=\"arm/\" value=\"1\"/></Offset></ControlSet>"),
              AllOf(HasSubstr("bad.cntr:2"), HasSubstr("\"arm/\"")));
  EXPECT_THAT(controlError("<ControlSet>\n<Offset><DOF name=\"/link\" value=\"1\"/></Offset></ControlSet>"),
              AllOf(HasSubstr("bad.cntr:2"), HasSubstr("\"/link\"")));
  EXPECT_THAT(
      controlError(
          "<ControlSet>\n\n<Control name=\"a\"><DOF name=\"a/b\" value=\"inf\"/></Control></ControlSet>"),
      AllOf(HasSubstr("bad.cntr:3"), HasSubstr("inf")));
  EXPECT_THAT(
      controlError(
          "<ControlSet>\n<Control name=\"a\" eigValue=\"nan\"><DOF name=\"a/b\" value=\"1\"/></Control>"
          "</ControlSet>"),
      AllOf(HasSubstr("bad.cntr:2"), HasSubstr("eigValue")));
  EXPECT_THAT(controlError("<ControlSet>\n<Offset><DOF name=\"a/b\" value=\"x\"/></Offset></ControlSet>"),
              AllOf(HasSubstr("bad.cntr:2"), HasSubstr("value")));
  EXPECT_THAT(controlError("<ControlSet>\n<Control name=\"empty\"/></ControlSet>"),
              AllOf(HasSubstr("bad.cntr:2"), HasSubstr("\"empty\" moves no <DOF>")));
  EXPECT_THAT(controlError("<ControlSet><Control name=\"a\"><DOF name=\"a/b\" value=\"1\"/></Control>\n"
                           "<Control name=\"a\"><DOF name=\"a/c\" value=\"1\"/></Control></ControlSet>"),
              AllOf(HasSubstr("bad.cntr:2"), HasSubstr("\"a\" is defined twice")));
  EXPECT_THAT(controlError("<ControlSet>\n<Control><DOF name=\"a/b\" value=\"1\"/></Control></ControlSet>"),
              AllOf(HasSubstr("bad.cntr:2"), HasSubstr("needs attribute \"name\"")));
}

}  // namespace
}  // namespace lang2manip
