#include "lang2manip/llm/gemini_schema.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "lang2manip/core/error.hpp"

namespace lang2manip {

namespace {

using nlohmann::json;

constexpr int kMaxRefDepth = 32;
constexpr std::array kCopiedKeywords = {"description", "format", "minItems", "maxItems",
                                        "minimum",     "maximum", "title"};

class GeminiSchemaConverter {
 public:
  explicit GeminiSchemaConverter(const json& root) : root_(root) {}

  json convert(const json& node, const std::string& path, int refDepth) const {
    if (!node.is_object()) throw InputError("schema " + path + ": expected an object");
    if (node.contains("$ref")) return convert(resolve(node, path, refDepth), path, refDepth + 1);
    json out = json::object();
    for (const char* keyword : kCopiedKeywords) {
      if (node.contains(keyword)) out[keyword] = node[keyword];
    }
    convertType(node, path, out);
    if (node.contains("enum")) copyStringEnum(node["enum"], out);
    if (node.contains("const") && node["const"].is_string()) out["enum"] = json::array({node["const"]});
    if (node.contains("properties")) {
      json properties = json::object();
      for (const auto& [name, property] : node["properties"].items()) {
        properties[name] = convert(property, path + ".properties." + name, refDepth);
      }
      out["properties"] = properties;
      if (node.contains("required")) out["required"] = node["required"];
    }
    if (node.contains("items")) out["items"] = convert(node["items"], path + ".items", refDepth);
    for (const char* unionKey : {"anyOf", "oneOf"}) {
      if (node.contains(unionKey)) mergeUnion(node[unionKey], path + "." + unionKey, refDepth, out);
    }
    if (node.contains("nullable") && node["nullable"] == true) out["nullable"] = true;
    return out;
  }

 private:
  const json& resolve(const json& node, const std::string& path, int refDepth) const {
    const json& reference = node["$ref"];
    if (!reference.is_string()) throw InputError("schema " + path + ".$ref: expected a string");
    const std::string target = reference.get<std::string>();
    if (refDepth >= kMaxRefDepth) {
      throw InputError("schema " + path + ": $ref \"" + target +
                       "\" is recursive; Gemini's responseSchema cannot express recursion");
    }
    for (const char* prefix : {"#/$defs/", "#/definitions/"}) {
      const std::string start(prefix);
      if (target.rfind(start, 0) != 0) continue;
      const std::string section = start.substr(2, start.size() - 3);
      const std::string name = target.substr(start.size());
      if (root_.contains(section) && root_[section].contains(name)) return root_[section][name];
    }
    throw InputError("schema " + path + ": cannot resolve $ref \"" + target +
                     "\" (only #/$defs/NAME and #/definitions/NAME are supported)");
  }

  static std::string geminiType(const json& type, const std::string& path) {
    static const std::array kTypes = {"string", "number", "integer", "boolean", "array", "object"};
    const std::string name = type.is_string() ? type.get<std::string>() : "";
    if (std::find(kTypes.begin(), kTypes.end(), name) == kTypes.end()) {
      throw InputError("schema " + path + ".type: \"" + type.dump() + "\" is not a JSON Schema type");
    }
    std::string upper = name;
    std::transform(upper.begin(), upper.end(), upper.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    return upper;
  }

  static void convertType(const json& node, const std::string& path, json& out) {
    if (!node.contains("type")) return;
    const json& type = node["type"];
    if (!type.is_array()) {
      if (type == "null") {
        out["nullable"] = true;
        return;
      }
      out["type"] = geminiType(type, path);
      return;
    }
    std::vector<std::string> types;
    for (const json& member : type) {
      if (member == "null") {
        out["nullable"] = true;
      } else {
        types.push_back(geminiType(member, path));
      }
    }
    if (types.size() == 1) {
      out["type"] = types.front();
    } else if (types.size() > 1) {
      json options = json::array();
      for (const std::string& each : types) options.push_back({{"type", each}});
      out["anyOf"] = options;
    }
  }

  static void copyStringEnum(const json& values, json& out) {
    if (!values.is_array()) return;
    json strings = json::array();
    for (const json& value : values) {
      if (value.is_null()) out["nullable"] = true;
      if (value.is_string()) strings.push_back(value);
    }
    if (!strings.empty()) out["enum"] = strings;
  }

  void mergeUnion(const json& options, const std::string& path, int refDepth, json& out) const {
    if (!options.is_array()) throw InputError("schema " + path + ": expected an array");
    json kept = json::array();
    for (std::size_t i = 0; i < options.size(); ++i) {
      if (options[i].is_object() && options[i].value("type", json()) == "null") {
        out["nullable"] = true;
      } else {
        kept.push_back(convert(options[i], path + "[" + std::to_string(i) + "]", refDepth));
      }
    }
    if (kept.size() == 1) {
      for (const auto& [key, value] : kept[0].items()) out[key] = value;
    } else if (!kept.empty()) {
      out["anyOf"] = kept;
    }
  }

  const json& root_;
};

}  // namespace

nlohmann::json toGeminiSchema(const nlohmann::json& schema) {
  return GeminiSchemaConverter(schema).convert(schema, "$", 0);
}

}  // namespace lang2manip
