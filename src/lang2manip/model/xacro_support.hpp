#pragma once
/// @file Internal to the xacro processor: finding ROS packages, loading YAML as xacro values,
/// reading macro parameter lists, and splitting text into literals, ${} and $() parts.

#include <filesystem>
#include <functional>
#include <map>
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

/// What a $(...) substitution can see.
struct SubstitutionContext {
  const std::map<std::string, std::string>& arguments;
  std::filesystem::path currentFile;
  const std::vector<std::filesystem::path>& packagePaths;
  /// Evaluates the Python code of $(eval ...) to text.
  std::function<std::string(const std::string&)> evaluate;
};

/// The text of "$(COMMAND)": arg NAME, find PKG, env VAR, optenv VAR [DEFAULT], dirname, eval CODE.
/// @throws ExpressionError for an undefined argument, package or variable, or another command.
std::string substitutionArgument(const std::string& command, const SubstitutionContext& context);

/// Calls xacro.NAME (load_yaml relative to `currentFile`; warning, message, print_location; error,
/// fatal). `location` prefixes a warning. @throws ExpressionError for xacro.error and unknown names.
Value callXacroFunction(const std::string& name, const ValueList& arguments,
                        const std::filesystem::path& currentFile, const std::string& location);

}  // namespace lang2manip::xacro
