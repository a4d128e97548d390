#include "lang2manip/core/text_parsing.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace lang2manip {
namespace {

using ::testing::HasSubstr;

std::string messageOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

const SourceLocation kWhere{"file.xml", 12};

TEST(TextParsing, ParsesFiniteNumbersWithSurroundingSpaces) {
  EXPECT_DOUBLE_EQ(parseFiniteNumber("  1.5 ", "value", kWhere), 1.5);
  EXPECT_DOUBLE_EQ(parseFiniteNumber("+2e-3", "value", kWhere), 2e-3);
  EXPECT_DOUBLE_EQ(parseFiniteNumber("-7", "value", kWhere), -7.0);
}

TEST(TextParsing, RejectsNanInfinityAndGarbageNamingWhereAndWhat) {
  EXPECT_THAT(messageOf([] { parseFiniteNumber("nan", "joint limit", kWhere); }),
              HasSubstr("file.xml:12: joint limit must be a finite number"));
  EXPECT_THAT(messageOf([] { parseFiniteNumber("inf", "x", kWhere); }), HasSubstr("finite"));
  EXPECT_THAT(messageOf([] { parseFiniteNumber("1.0abc", "x", kWhere); }),
              HasSubstr("\"1.0abc\" is not a number"));
  EXPECT_THAT(messageOf([] { parseFiniteNumber("", "x", kWhere); }), HasSubstr("is not a number"));
}

TEST(TextParsing, ParsesListsAndVectors) {
  EXPECT_THAT(parseNumberList(" 1 2\n3\t4 ", "list", kWhere), ::testing::ElementsAre(1, 2, 3, 4));
  EXPECT_TRUE(parseNumberList("   ", "list", kWhere).empty());
  EXPECT_TRUE(parseVector3("0 0.5 1", "xyz", kWhere).isApprox(Vector3(0, 0.5, 1)));
  EXPECT_THAT(messageOf([] { parseVector3("1 2", "xyz", kWhere); }),
              HasSubstr("xyz: expected 3 numbers, got 2"));
  EXPECT_THAT(messageOf([] { parseNumberList("1 nan 3", "list", kWhere); }), HasSubstr("finite"));
}

TEST(TextParsing, ParsesFlags) {
  EXPECT_TRUE(parseFlag("TRUE", "flag", kWhere));
  EXPECT_FALSE(parseFlag(" 0 ", "flag", kWhere));
  EXPECT_THAT(messageOf([] { parseFlag("yes please", "enabled", kWhere); }),
              HasSubstr("enabled: expected true/false or 1/0"));
}

TEST(InputErrorTest, FormatsLocation) {
  EXPECT_STREQ(InputError(SourceLocation{"a.urdf", 3}, "bad").what(), "a.urdf:3: bad");
  EXPECT_STREQ(InputError(SourceLocation{"a.urdf", 0}, "bad").what(), "a.urdf: bad");
  EXPECT_STREQ(InputError("bad").what(), "bad");
}

}  // namespace
}  // namespace lang2manip
