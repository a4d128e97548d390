#include "lang2manip/llm/gemini_schema.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "lang2manip/core/error.hpp"
#include "llm_test_support.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

TEST(GeminiSchema, ConvertsTypesUnionsAndDropsUnsupportedKeywords) {
  const json converted = toGeminiSchema(test::smallPlanSchema());
  EXPECT_EQ(converted["type"], "OBJECT");
  EXPECT_FALSE(converted.contains("additionalProperties"));
  EXPECT_EQ(converted["required"], json::array({"actions"}));
  const json& item = converted["properties"]["actions"]["items"];
  EXPECT_EQ(converted["properties"]["actions"]["type"], "ARRAY");
  EXPECT_EQ(item["properties"]["action"], json({{"type", "STRING"}, {"enum", {"pick", "place"}}}));
  EXPECT_EQ(item["properties"]["object"], json({{"type", "STRING"}, {"nullable", true}}));
}

TEST(GeminiSchema, InlinesLocalReferencesAndMergesNullableAnyOf) {
  const json schema = json::parse(R"({
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "$defs": {"pose": {"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3}},
    "type": "object",
    "properties": {
      "pose": {"anyOf": [{"$ref": "#/$defs/pose"}, {"type": "null"}]},
      "kind": {"const": "box", "description": "what it is"},
      "size": {"type": ["integer", "string"]}
    }
  })");
  const json converted = toGeminiSchema(schema);
  EXPECT_FALSE(converted.contains("$schema"));
  EXPECT_FALSE(converted.contains("$defs"));
  EXPECT_EQ(converted["properties"]["pose"],
            json({{"type", "ARRAY"}, {"items", {{"type", "NUMBER"}}}, {"minItems", 3},
                  {"maxItems", 3}, {"nullable", true}}));
  EXPECT_EQ(converted["properties"]["kind"],
            json({{"enum", {"box"}}, {"description", "what it is"}}));
  EXPECT_EQ(converted["properties"]["size"]["anyOf"],
            json::parse(R"([{"type":"INTEGER"},{"type":"STRING"}])"));
}

TEST(GeminiSchema, RejectsWhatItCannotExpressNamingThePath) {
  const json recursive = json::parse(R"({
    "$defs": {"node": {"type": "object", "properties": {"child": {"$ref": "#/$defs/node"}}}},
    "$ref": "#/$defs/node"})");
  try {
    toGeminiSchema(recursive);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("recursive"));
    EXPECT_THAT(error.what(), HasSubstr("properties.child"));
  }
  EXPECT_THROW(toGeminiSchema(json::parse(R"({"$ref": "http://x/schema.json"})")), InputError);
  try {
    toGeminiSchema(json::parse(R"({"type":"object","properties":{"a":{"type":"float"}}})"));
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("$.properties.a.type"));
  }
}

}  // namespace
}  // namespace lang2manip
