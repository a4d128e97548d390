#pragma once
/// @file Internal to the xacro processor: Python's operators, attribute access, indexing and
/// built-in functions on xacro values (used by xacro_expression.cpp).

#include <optional>
#include <string>
#include <string_view>

#include "lang2manip/model/xacro_expression.hpp"
#include "lang2manip/model/xacro_value.hpp"

namespace lang2manip::xacro {

/// a OP b for OP in + - * / // % ** == != < > <= >= in "not in". Throws ExpressionError.
Value binaryOperation(std::string_view op, const Value& a, const Value& b);

/// -a, +a, not a.
Value unaryOperation(std::string_view op, const Value& a);

/// value.name: a dict's key, a method of a str, list or dict, or a member of the math and xacro
/// namespaces.
Value attribute(const Value& value, const std::string& name);

/// value[key] for lists and strings (negative indices from the end) and dicts.
Value subscript(const Value& value, const Value& key);

/// A built-in constant or function ("pi", "radians", "math", "xacro", ...), or nullopt.
std::optional<Value> builtinName(const std::string& name);

/// Calls `function` (a built-in, a method, or a name of the xacro namespace through `scope`).
Value callFunction(const Function& function, const ValueList& arguments, const ExpressionScope& scope);

}  // namespace lang2manip::xacro
