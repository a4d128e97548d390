#pragma once
/// @file Internal to the xacro processor: the Python expressions of ${...} as xacro evaluates
/// them: literals, names, attribute access and indexing, calls, arithmetic, comparisons, `in`,
/// `and`/`or`/`not`, `x if c else y`, lists and dicts, with math's functions and constants and
/// the methods of str, list and dict that robot descriptions use.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "lang2manip/model/xacro_value.hpp"

namespace lang2manip::xacro {

/// What an expression can see besides the built-ins.
struct ExpressionScope {
  /// The value of a property or macro parameter, or nullopt when `name` is not defined.
  std::function<std::optional<Value>(const std::string& name)> lookup;
  /// Calls a function of the xacro namespace ("xacro.load_yaml", "xacro.warning", ...; also
  /// the bare "load_yaml"). Throws ExpressionError for names it does not know.
  std::function<Value(const std::string& name, const ValueList& arguments)> call;
};

/// Most levels of nested parentheses, brackets and operators in one expression.
inline constexpr int kMaxExpressionDepth = 100;

/// Longest expression text accepted (robot descriptions write a few dozen characters).
inline constexpr std::size_t kMaxExpressionLength = 65536;

/// Evaluates one expression (the text between "${" and "}").
/// @throws ExpressionError naming what is wrong: a syntax error, an undefined name, an
/// operation on the wrong types, a division by zero, nesting deeper than kMaxExpressionDepth,
/// text longer than kMaxExpressionLength.
Value evaluateExpression(std::string_view text, const ExpressionScope& scope);

}  // namespace lang2manip::xacro
