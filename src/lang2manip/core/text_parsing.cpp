#include "lang2manip/core/text_parsing.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <cmath>

namespace lang2manip {

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::string metresText(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f m", value);
  return text;
}

std::string numberText(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string_view trimmed(std::string_view text) {
  const auto isSpace = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
  while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
  return text;
}

void requireFinite(double value, std::string_view what, const SourceLocation& where) {
  if (!std::isfinite(value)) {
    throw InputError(where, std::string(what) + " must be a finite number, got " +
                                std::to_string(value));
  }
}

double parseFiniteNumber(std::string_view text, std::string_view what,
                         const SourceLocation& where) {
  const std::string_view number = trimmed(text);
  double value = 0.0;
  const char* first = number.data();
  const char* last = number.data() + number.size();
  if (!number.empty() && *first == '+') ++first;
  const auto [end, error] = std::from_chars(first, last, value);
  if (number.empty() || error != std::errc() || end != last) {
    throw InputError(where, std::string(what) + ": \"" + std::string(number) +
                                "\" is not a number");
  }
  if (!std::isfinite(value)) {
    throw InputError(where, std::string(what) + " must be a finite number, got \"" +
                                std::string(number) + "\"");
  }
  return value;
}

std::vector<double> parseNumberList(std::string_view text, std::string_view what,
                                    const SourceLocation& where) {
  std::vector<double> values;
  std::size_t position = 0;
  while (position < text.size()) {
    while (position < text.size() && std::isspace(static_cast<unsigned char>(text[position]))) {
      ++position;
    }
    std::size_t end = position;
    while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end]))) ++end;
    if (end > position) {
      values.push_back(parseFiniteNumber(text.substr(position, end - position), what, where));
    }
    position = end;
  }
  return values;
}

Vector3 parseVector3(std::string_view text, std::string_view what, const SourceLocation& where) {
  const std::vector<double> values = parseNumberList(text, what, where);
  if (values.size() != 3) {
    throw InputError(where, std::string(what) + ": expected 3 numbers, got " +
                                std::to_string(values.size()) + " in \"" +
                                std::string(trimmed(text)) + "\"");
  }
  return {values[0], values[1], values[2]};
}

bool parseFlag(std::string_view text, std::string_view what, const SourceLocation& where) {
  std::string lower(trimmed(text));
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower == "true" || lower == "1") return true;
  if (lower == "false" || lower == "0") return false;
  throw InputError(where, std::string(what) + ": expected true/false or 1/0, got \"" +
                              std::string(trimmed(text)) + "\"");
}

std::string joinedNames(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

}  // namespace lang2manip
