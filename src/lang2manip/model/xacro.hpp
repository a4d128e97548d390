#pragma once
/// @file xacro without ROS: expands a .xacro robot description into URDF text, as ROS's `xacro`
/// tool does (properties and property blocks, macros with default, inherited (^), block (*) and
/// content (**) parameters, includes with namespaces, if/unless, args, element/attribute,
/// insert_block, $(arg/find/env/optenv/dirname/eval) and ${} Python expressions with math,
/// xacro.load_yaml (!degrees and !radians tags) and dict/list indexing).

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace lang2manip {

/// How to expand a xacro file.
struct XacroOptions {
  /// Values of the file's <xacro:arg>s by name (a command line's name:=value).
  std::map<std::string, std::string> arguments;
  /// Directories searched first for $(find PKG): each may be the package (its package.xml names
  /// it, or its folder does) or hold it up to two levels down. Then LANG2MANIP_PACKAGE_PATH and
  /// ROS_PACKAGE_PATH (colon-separated), then the directories above the file.
  std::vector<std::filesystem::path> packagePaths;
};

/// Most nested includes and macro calls (a file that includes itself, a macro that calls itself).
inline constexpr int kMaxXacroNesting = 100;
/// Deepest element nesting while expanding (includes and macro bodies nest their elements).
inline constexpr int kMaxXacroDepth = 500;
/// Most elements an expansion may produce (a two-arm robot with every option expands to a few
/// thousand).
inline constexpr int kMaxXacroElements = 100000;

/// True for a file whose name ends in ".xacro" (such as "panda.urdf.xacro").
bool isXacroFile(const std::filesystem::path& path);

/// The URDF text of the xacro file at `path`.
/// @throws InputError "file:line: what" naming the xacro file and line of the element at fault
/// and, inside a macro, the macro and where it was called: malformed XML, an undefined property,
/// argument, macro or package, a missing include or YAML file, a YAML file that does not parse,
/// an expression that does not evaluate, a macro parameter that is unknown or missing, a
/// conditional that is not a boolean, includes or macro calls nested more than kMaxXacroNesting
/// deep, elements nested more than kMaxXacroDepth deep, a property defined in terms of itself,
/// more than kMaxXacroElements elements.
std::string expandXacroFile(const std::filesystem::path& path, const XacroOptions& options = {});

/// "name:=value" as a pair. @throws InputError for text without ":=" or with an empty name.
std::pair<std::string, std::string> parseXacroArgument(const std::string& text);

}  // namespace lang2manip
