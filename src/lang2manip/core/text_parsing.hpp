#pragma once
/// @file Strict parsing of numbers and flags from text in input files.
/// Every function throws InputError naming `what` and `where` on anything but a finite number.

#include <string>
#include <string_view>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/types.hpp"

namespace lang2manip {

/// Parses one finite number; the whole text (apart from surrounding spaces) must be the number.
double parseFiniteNumber(std::string_view text, std::string_view what, const SourceLocation& where);

/// Parses a whitespace-separated list of finite numbers.
std::vector<double> parseNumberList(std::string_view text, std::string_view what,
                                    const SourceLocation& where);

/// Parses exactly three numbers, e.g. "0 0.1 0.2".
Vector3 parseVector3(std::string_view text, std::string_view what, const SourceLocation& where);

/// Parses true/false/1/0 (case-insensitive).
bool parseFlag(std::string_view text, std::string_view what, const SourceLocation& where);

/// Throws InputError unless `value` is finite.
void requireFinite(double value, std::string_view what, const SourceLocation& where);

/// Text with leading and trailing whitespace removed.
std::string_view trimmed(std::string_view text);

/// `text` with ASCII letters lower-cased.
std::string lowercase(std::string text);

/// The names separated by ", " (for messages listing valid names).
std::string joinedNames(const std::vector<std::string>& names);

/// A length for messages: "0.123 m" (three decimals).
std::string metresText(double value);

/// A number for messages, at most six significant digits ("0.01", "1e-09", "nan").
std::string numberText(double value);

}  // namespace lang2manip
