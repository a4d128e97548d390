#include "lang2manip/core/json_limits.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

namespace lang2manip {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

std::string nested(std::size_t levels, char open = '[', char close = ']') {
  return std::string(levels, open) + std::string(levels, close);
}

std::string parseMessage(const std::string& text, const JsonLimits& limits = {}) {
  try {
    parseJsonWithinLimits(text, limits, "test document");
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(JsonLimitsTest, HundredThousandLevelsAreRefusedBeforeParsing) {
  // 200 kB of brackets: nlohmann alone would overflow the stack parsing or destroying it.
  for (const std::string& text : {nested(100000), std::string(100000, '[') + "{}"}) {
    const auto violation = findJsonLimitViolation(text, {});
    ASSERT_TRUE(violation.has_value());
    EXPECT_EQ(violation->kind, JsonLimitViolation::Kind::kTooDeep);
    EXPECT_EQ(violation->at, kDefaultJsonMaxDepth);
    EXPECT_THAT(parseMessage(text), HasSubstr("test document: nested deeper than 128 levels (at byte 128)"));
  }
  // Objects nest too: {"a":{"a":...}}.
  std::string objects;
  for (int i = 0; i < 50000; ++i) objects += "{\"a\":";
  EXPECT_THAT(parseMessage(objects + "1" + std::string(50000, '}')), HasSubstr("nested deeper than 128"));
}

TEST(JsonLimitsTest, DepthUpToTheLimitParses) {
  JsonLimits limits;
  limits.maxDepth = 10;
  EXPECT_FALSE(findJsonLimitViolation(nested(10), limits).has_value());
  EXPECT_EQ(parseJsonWithinLimits(nested(10), limits, "doc").dump(), nested(10));
  EXPECT_TRUE(findJsonLimitViolation(nested(11), limits).has_value());
  // Siblings do not add up: depth is nesting, not a count of brackets.
  std::string siblings = "[";
  for (int i = 0; i < 1000; ++i) siblings += nested(5) + ",";
  siblings += "1]";
  EXPECT_FALSE(findJsonLimitViolation(siblings, limits).has_value());
}

TEST(JsonLimitsTest, BracketsInsideStringsDoNotCount) {
  JsonLimits limits;
  limits.maxDepth = 3;
  const std::string text = R"({"text": "[[[[[[{{{{\"[[[[", "b": ["x\\", "[[[["]})";
  EXPECT_FALSE(findJsonLimitViolation(text, limits).has_value()) << text;
  EXPECT_EQ(parseJsonWithinLimits(text, limits, "doc")["b"][1], "[[[[");
  // An escaped quote does not end the string; an escaped backslash before a quote does.
  EXPECT_TRUE(findJsonLimitViolation(R"(["\\", [[[[]]]]])", limits).has_value());
}

TEST(JsonLimitsTest, SizeLimitNamesTheSizeAndTheLimit) {
  JsonLimits limits;
  limits.maxBytes = 100;
  const std::string text = "[\"" + std::string(200, 'x') + "\"]";
  const auto violation = findJsonLimitViolation(text, limits);
  ASSERT_TRUE(violation.has_value());
  EXPECT_EQ(violation->kind, JsonLimitViolation::Kind::kTooLarge);
  EXPECT_THAT(parseMessage(text, limits), HasSubstr("test document: 204 bytes, more than the limit of 100 bytes"));
}

TEST(JsonLimitsTest, EveryNlohmannFailureBecomesAnInputErrorNamingTheDocument) {
  // Syntax errors, numbers out of range (out_of_range, not parse_error), invalid UTF-8,
  // truncation, empty input.
  for (const std::string text : {"{\"a\": 1e400}", "[-1e400]", "[\"\xff\xfe\"]", "{\"a\": [1, 2",
                                  "", "nul", "{\"a\" 1}"}) {
    const std::string message = parseMessage(text);
    EXPECT_THAT(message, HasSubstr("test document: not valid JSON: ")) << text;
    EXPECT_THAT(message, ::testing::Not(HasSubstr("[json.exception"))) << text;
  }
  EXPECT_EQ(parseJsonWithinLimits("{\"n\": 18446744073709551615}", {}, "d")["n"].get<std::uint64_t>(),
            18446744073709551615ULL);
}

TEST(JsonLimitsTest, AKeyGivenTwiceInOneObjectIsRefusedAtAnyDepth) {
  const JsonLimits limits;
  EXPECT_THAT([&] { (void)parseJsonWithinLimits(R"({"actions": [], "actions": [1]})", limits, "plan file p.json"); },
              ::testing::ThrowsMessage<InputError>(::testing::HasSubstr("plan file p.json: not valid JSON here: the key \"actions\" appears twice")));
  EXPECT_THROW((void)parseJsonWithinLimits(R"({"a": [{"x": 1, "y": 2, "x": 3}]})", limits, "body"), InputError);
  // The same key in sibling or nested objects is not a duplicate.
  const nlohmann::json value = parseJsonWithinLimits(R"({"a": {"a": 1}, "b": [{"a": 2}, {"a": 3}]})", limits, "body");
  EXPECT_EQ(value["b"][1]["a"], 3);
}

TEST(JsonLimitsTest, BoundedDumpNeverSerialisesTheWholeValue) {
  json big = json::array();
  for (int i = 0; i < 100000; ++i) big.push_back(i);
  EXPECT_LE(boundedJsonDump(big).size(), 40U);
  EXPECT_EQ(boundedJsonDump(big).substr(0, 10), "[0,1,2,3,4");
  EXPECT_EQ(boundedJsonDump(big).substr(37), "...");

  json deep = 1;  // built in code, deeper than any parsed document may be
  for (int i = 0; i < 20000; ++i) deep = json::array({std::move(deep)});
  EXPECT_LE(boundedJsonDump(deep, 200).size(), 200U);
  EXPECT_THAT(boundedJsonDump(deep, 200), HasSubstr("[...]"));

  const json longString = std::string(1 << 20, 'a');
  EXPECT_LE(boundedJsonDump(longString).size(), 40U);
  EXPECT_EQ(boundedJsonDump(json::object()), "{}");
  EXPECT_EQ(boundedJsonDump(json{{"a", 1}, {"b", {true, nullptr}}}), R"({"a":1,"b":[true,null]})");
}

TEST(JsonLimitsTest, BoundedDumpKeepsUtf8ValidAndNeverThrows) {
  const json accents = std::string(50, 'x') + "\xc3\xa9\xc3\xa9";
  const std::string shown = boundedJsonDump(accents, 52);
  EXPECT_NO_THROW(json(shown).dump()) << "a cut inside a UTF-8 sequence makes the message invalid";
  const json invalid = std::string("abc\xff\xfe");
  EXPECT_NO_THROW(boundedJsonDump(invalid));
  EXPECT_EQ(utf8Prefix("\xc3\xa9\xc3\xa9", 3), "\xc3\xa9");
  EXPECT_EQ(utf8Prefix("abc", 10), "abc");
}

TEST(JsonLimitsTest, BoundedLinesAreReadWithoutBufferingLongOnes) {
  std::istringstream in("short\n" + std::string(1000, 'x') + "\nlast");
  std::string line;
  EXPECT_EQ(readBoundedLine(in, line, 10), LineReadStatus::kLine);
  EXPECT_EQ(line, "short");
  EXPECT_EQ(readBoundedLine(in, line, 10), LineReadStatus::kTooLong);
  EXPECT_EQ(line.size(), 10U);
  EXPECT_EQ(readBoundedLine(in, line, 10), LineReadStatus::kLine);
  EXPECT_EQ(line, "last");
  EXPECT_EQ(readBoundedLine(in, line, 10), LineReadStatus::kEnd);
  std::istringstream exact("0123456789\n");
  EXPECT_EQ(readBoundedLine(exact, line, 10), LineReadStatus::kLine);
}

}  // namespace
}  // namespace lang2manip
