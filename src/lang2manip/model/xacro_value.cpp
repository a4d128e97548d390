#include "lang2manip/model/xacro_value.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>
#include <utility>

namespace lang2manip::xacro {
namespace {

thread_local bool budgetActive = false;
thread_local std::uint64_t workSpent = 0;

[[noreturn]] void typeError(const Value& value, const char* wanted) {
  throw ExpressionError(std::string("expected ") + wanted + ", got " + typeName(value) + " " + toRepr(value));
}

/// Python's repr() of a float: the shortest text that reads back, fixed notation for exponents
/// from -4 to 15, else scientific with a two-digit exponent ("1e-05", "1.5e+16").
std::string floatText(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::scientific);
  const std::string scientific(buffer, result.ptr);
  const std::size_t e = scientific.find('e');
  const int exponent = std::atoi(scientific.c_str() + e + 1);
  const bool negative = scientific[0] == '-';
  std::string digits;
  for (std::size_t i = negative ? 1 : 0; i < e; ++i) {
    if (scientific[i] != '.') digits += scientific[i];
  }
  std::string text = negative ? "-" : "";
  if (exponent < -4 || exponent >= 16) {
    text += digits.substr(0, 1);
    if (digits.size() > 1) text += "." + digits.substr(1);
    char exponentText[16];
    std::snprintf(exponentText, sizeof exponentText, "e%c%02d", exponent < 0 ? '-' : '+', std::abs(exponent));
    return text + exponentText;
  }
  if (exponent < 0) return text + "0." + std::string(static_cast<std::size_t>(-exponent - 1), '0') + digits;
  const auto integerDigits = static_cast<std::size_t>(exponent + 1);
  if (digits.size() <= integerDigits) return text + digits + std::string(integerDigits - digits.size(), '0') + ".0";
  return text + digits.substr(0, integerDigits) + "." + digits.substr(integerDigits);
}

std::string quoted(const std::string& text) {
  const char quote = text.find('\'') != std::string::npos && text.find('"') == std::string::npos ? '"' : '\'';
  std::string result(1, quote);
  for (const char c : text) {
    if (c == quote || c == '\\') result += '\\';
    result += c;
  }
  return result + quote;
}

/// `text` without surrounding spaces and a leading '+', as Python's int() and float() read it.
std::string_view numberText(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  return text;
}

/// Python's int() of text (decimal digits).
bool parseInteger(std::string_view text, long long& value) {
  text = numberText(text);
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return !text.empty() && error == std::errc() && end == text.data() + text.size();
}

/// Python's float() of text (inf and nan included).
bool parseFloat(std::string_view text, double& value) {
  text = numberText(text);
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return !text.empty() && error == std::errc() && end == text.data() + text.size();
}

}  // namespace

double Value::number() const {
  if (const auto* b = std::get_if<bool>(&data)) return *b ? 1.0 : 0.0;
  if (const auto* i = std::get_if<long long>(&data)) return static_cast<double>(*i);
  if (const auto* d = std::get_if<double>(&data)) return *d;
  typeError(*this, "a number");
}

long long Value::integer() const {
  if (const auto* b = std::get_if<bool>(&data)) return *b ? 1 : 0;
  if (const auto* i = std::get_if<long long>(&data)) return *i;
  typeError(*this, "an integer");
}

const std::string& Value::string() const {
  if (const auto* s = std::get_if<std::string>(&data)) return *s;
  typeError(*this, "a string");
}

const ValueList& Value::list() const {
  if (const auto* l = std::get_if<std::shared_ptr<const ValueList>>(&data)) return **l;
  typeError(*this, "a list");
}

const ValueDict& Value::dict() const {
  if (const auto* d = std::get_if<std::shared_ptr<const ValueDict>>(&data)) return **d;
  typeError(*this, "a dict");
}

const Function& Value::function() const {
  if (const auto* f = std::get_if<Function>(&data)) return *f;
  typeError(*this, "a function");
}

std::string typeName(const Value& value) {
  static const char* const kNames[] = {"NoneType", "bool", "int", "float", "str", "list", "dict", "function"};
  return kNames[value.data.index()];
}

void spendWork(std::uint64_t units) {
  if (!budgetActive) return;
  workSpent += units;
  if (workSpent > kMaxXacroWork) {
    throw ExpressionError("expansion needs more than " + std::to_string(kMaxXacroWork / 1000000) +
                          " million steps of work (values repeated, printed or compared without end?)");
  }
}

WorkBudget::WorkBudget() : outermost_(!budgetActive) {
  if (outermost_) {
    budgetActive = true;
    workSpent = 0;
  }
}

WorkBudget::~WorkBudget() {
  if (outermost_) budgetActive = false;
}

namespace {

void appendRepr(std::string& text, const Value& value) {
  spendWork(1);
  switch (value.data.index()) {
    case 0: text += "None"; break;
    case 1: text += std::get<bool>(value.data) ? "True" : "False"; break;
    case 2: text += std::to_string(std::get<long long>(value.data)); break;
    case 3: text += floatText(std::get<double>(value.data)); break;
    case 4: text += quoted(value.string()); break;
    case 5: {
      text += '[';
      bool first = true;
      for (const Value& item : value.list()) {
        if (!std::exchange(first, false)) text += ", ";
        appendRepr(text, item);
      }
      text += ']';
      break;
    }
    case 6: {
      text += '{';
      bool first = true;
      for (const auto& [key, item] : value.dict()) {
        if (!std::exchange(first, false)) text += ", ";
        text += quoted(key) + ": ";
        appendRepr(text, item);
      }
      text += '}';
      break;
    }
    default: text += "<function " + value.function().name + ">";
  }
  if (text.size() > kMaxStringLength) throw ExpressionError("text longer than 16 MiB");
}

}  // namespace

std::string toText(const Value& value) {
  if (value.isString()) return value.string();
  return toRepr(value);
}

std::string toRepr(const Value& value) {
  std::string text;
  appendRepr(text, value);
  return text;
}

bool isTrue(const Value& value) {
  switch (value.data.index()) {
    case 0: return false;
    case 1: return std::get<bool>(value.data);
    case 2: return std::get<long long>(value.data) != 0;
    case 3: return std::get<double>(value.data) != 0.0;
    case 4: return !value.string().empty();
    case 5: return !value.list().empty();
    case 6: return !value.dict().empty();
    default: return true;
  }
}

bool equal(const Value& a, const Value& b) {
  spendWork(1);
  if (a.isNumber() && b.isNumber()) return a.number() == b.number();
  if (a.data.index() != b.data.index()) return false;
  if (a.isNone()) return true;
  if (a.isString()) return a.string() == b.string();
  if (a.isList()) {
    const ValueList& x = a.list();
    const ValueList& y = b.list();
    if (x.size() != y.size()) return false;
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (!equal(x[i], y[i])) return false;
    }
    return true;
  }
  if (a.isDict()) {
    if (a.dict().size() != b.dict().size()) return false;
    for (const auto& [key, item] : a.dict()) {
      const Value* other = findKey(b.dict(), key);
      if (other == nullptr || !equal(item, *other)) return false;
    }
    return true;
  }
  return false;
}

const Value* findKey(const ValueDict& dict, std::string_view key) {
  for (const auto& [name, item] : dict) {
    if (name == key) return &item;
  }
  return nullptr;
}

Value literalValue(const std::string& text) {
  if (text.size() >= 2 && text.front() == '\'' && text.back() == '\'') return text.substr(1, text.size() - 2);
  if (text.find('_') != std::string::npos) return text;
  long long integer = 0;
  if (parseInteger(text, integer)) return integer;
  double number = 0.0;
  if (parseFloat(text, number)) return number;
  if (text == "true" || text == "True") return true;
  if (text == "false" || text == "False") return false;
  return text;
}

}  // namespace lang2manip::xacro
