#pragma once
/// @file JSON Schema -> Gemini responseSchema (an OpenAPI 3.0 subset).

#include <nlohmann/json.hpp>

namespace lang2manip {

/// Converts a JSON Schema to the subset Gemini's responseSchema accepts: type names in capitals;
/// ["T","null"] type unions and anyOf/oneOf with {"type":"null"} become "nullable": true; other
/// unions become anyOf; local $ref (#/$defs/NAME, #/definitions/NAME) are inlined; const becomes
/// a one-value enum. Kept: description, format, enum (of strings), properties, required, items,
/// minItems, maxItems, minimum, maximum, title. Dropped, because Gemini rejects them:
/// additionalProperties, $schema, $defs, default, pattern, string lengths, examples (the answer
/// is validated against the full schema afterwards anyway). Throws InputError naming the JSON
/// path for a schema that cannot be converted (a recursive or unresolved $ref, a type that is
/// not a JSON Schema type).
nlohmann::json toGeminiSchema(const nlohmann::json& schema);

}  // namespace lang2manip
