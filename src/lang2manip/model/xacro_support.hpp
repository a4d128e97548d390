#pragma once
/// @file Internal to the xacro processor: finding ROS packages, loading YAML as xacro values,
/// reading macro parameter lists, and splitting text into literals, ${} and $() parts.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "lang2manip/model/xacro_value.hpp"

namespace lang2manip::xacro {

/// The directory of package `name` (see XacroOptions::packagePaths for the search), or nullopt.
std::optional<std::filesystem::path> findPackage(const std::string& name, const std::filesystem::path& nearFile,
                                                 const std::vector<std::filesystem::path>& extraPaths);

/// The YAML file as a value: maps become dicts, sequences lists, plain scalars numbers, bools,
/// None or strings; "!degrees x" and "!radians x" are numbers in radians.
/// @throws InputError "file:line: ..." when the file cannot be read or does not parse.
Value loadYamlValue(const std::filesystem::path& file);

/// One parameter of a macro: `name`, `name:=default` (or `=`), `name:=^` / `name:=^|default`
/// (inherited from the caller's scope), `*name` (a block) or `**name` (a block's content).
struct MacroParameter {
  enum class Kind { kValue, kBlock, kContent };
  std::string name;
  Kind kind = Kind::kValue;
  std::optional<std::string> defaultText;
  bool inherit = false;
};

/// The parameters of a params="..." attribute (quoted defaults may hold spaces).
/// @throws ExpressionError for an unclosed quote or an empty name.
std::vector<MacroParameter> parseMacroParameters(const std::string& params);

/// One part of an attribute or text: literal text, an ${expression} or a $(substitution).
struct TextPart {
  enum class Kind { kLiteral, kExpression, kSubstitution };
  Kind kind;
  std::string text;
};

/// The parts of `text` ("$${" and "$$(" are literal "${" and "$(").
/// @throws ExpressionError for an unclosed ${ or $(.
std::vector<TextPart> splitText(const std::string& text);

}  // namespace lang2manip::xacro
