#include "lang2manip/model/xacro_operations.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <functional>
#include <map>

namespace lang2manip::xacro {
namespace {

[[noreturn]] void fail(const std::string& message) { throw ExpressionError(message); }

[[noreturn]] void unsupported(std::string_view op, const Value& a, const Value& b) {
  fail("unsupported operand types for " + std::string(op) + ": '" + typeName(a) + "' and '" + typeName(b) + "'");
}

bool integral(const Value& v) { return v.isInt() || v.isBool(); }

/// x OP y for + - *, failing on overflow.
long long exactly(char op, long long x, long long y) {
  long long result = 0;
  const bool overflow = op == '+'   ? __builtin_add_overflow(x, y, &result)
                        : op == '-' ? __builtin_sub_overflow(x, y, &result)
                                    : __builtin_mul_overflow(x, y, &result);
  if (overflow) fail("integer overflow");
  return result;
}

Value arithmetic(std::string_view op, const Value& a, const Value& b) {
  if (integral(a) && integral(b)) {
    const long long x = a.integer();
    const long long y = b.integer();
    if (op == "+" || op == "-" || op == "*") return exactly(op[0], x, y);
    if (y == 0 && (op == "//" || op == "%")) fail("integer division or modulo by zero");
    if (op == "//") return x / y - ((x % y != 0 && ((x < 0) != (y < 0))) ? 1 : 0);
    if (op == "%") return ((x % y) + y) % y;
  }
  const double x = a.number();
  const double y = b.number();
  if (op == "+") return x + y;
  if (op == "-") return x - y;
  if (op == "*") return x * y;
  if (y == 0.0) fail("float division by zero");
  if (op == "/") return x / y;
  if (op == "//") return std::floor(x / y);
  return x - y * std::floor(x / y);  // %
}

Value power(const Value& a, const Value& b) {
  if (integral(a) && integral(b) && b.integer() >= 0) {
    long long result = 1;
    for (long long i = 0; i < b.integer(); ++i) {
      if (__builtin_mul_overflow(result, a.integer(), &result)) fail("integer overflow");
      if (result == 0 || result == 1) break;
    }
    return result;
  }
  if (a.number() == 0.0 && b.number() < 0.0) fail("0.0 cannot be raised to a negative power");
  const double result = std::pow(a.number(), b.number());
  if (std::isnan(result) && !std::isnan(a.number())) fail("math domain error in **");
  return result;
}

Value repeated(const Value& sequence, const Value& count) {
  const long long times = std::max(0LL, count.integer());
  if (times > 1000000) fail("repetition of more than 1000000 copies");
  if (sequence.isString()) {
    if (sequence.string().size() * static_cast<std::size_t>(times) > kMaxStringLength) fail("string longer than 16 MiB");
    spendWork(sequence.string().size() * static_cast<std::size_t>(times) / 64 + 1);
    std::string text;
    for (long long i = 0; i < times; ++i) text += sequence.string();
    return text;
  }
  if (sequence.list().size() * static_cast<std::size_t>(times) > kMaxListLength) fail("list longer than 1000000 items");
  spendWork(sequence.list().size() * static_cast<std::size_t>(times) + 1);
  ValueList items;
  for (long long i = 0; i < times; ++i) items.insert(items.end(), sequence.list().begin(), sequence.list().end());
  return items;
}

int compare(std::string_view op, const Value& a, const Value& b) {
  if (a.isNumber() && b.isNumber()) return a.number() < b.number() ? -1 : (a.number() > b.number() ? 1 : 0);
  if (a.isString() && b.isString()) return a.string().compare(b.string());
  unsupported(op, a, b);
}

bool contains(const Value& container, const Value& item) {
  if (container.isString()) return container.string().find(item.string()) != std::string::npos;
  if (container.isList()) {
    const ValueList& list = container.list();
    return std::any_of(list.begin(), list.end(), [&](const Value& element) { return equal(element, item); });
  }
  if (container.isDict()) return item.isString() && findKey(container.dict(), item.string()) != nullptr;
  fail("argument of type '" + typeName(container) + "' is not iterable");
}

std::size_t position(long long index, std::size_t size) {
  const long long resolved = index < 0 ? index + static_cast<long long>(size) : index;
  if (resolved < 0 || resolved >= static_cast<long long>(size)) fail("index " + std::to_string(index) + " out of range");
  return static_cast<std::size_t>(resolved);
}

// ----------------------------------------------------------------------------------- built-ins

using Builtin = std::function<Value(const ValueList&)>;

void requireCount(const std::string& name, const ValueList& arguments, std::size_t low, std::size_t high) {
  if (arguments.size() < low || arguments.size() > high) {
    fail(name + "() takes " + (low == high ? std::to_string(low) : std::to_string(low) + " to " + std::to_string(high)) +
         " arguments, " + std::to_string(arguments.size()) + " given");
  }
}

Builtin unaryMath(const std::string& name, double (*f)(double)) {
  return [name, f](const ValueList& arguments) -> Value {
    requireCount(name, arguments, 1, 1);
    const double result = f(arguments[0].number());
    if (std::isnan(result) && !std::isnan(arguments[0].number())) fail("math domain error in " + name + "()");
    return result;
  };
}

Value toInteger(const ValueList& arguments) {
  requireCount("int", arguments, 1, 1);
  const Value& value = arguments[0];
  if (value.isString()) {
    const Value parsed = literalValue(value.string());
    if (!parsed.isInt()) fail("invalid literal for int(): '" + value.string() + "'");
    return parsed;
  }
  const double number = std::trunc(value.number());
  if (!std::isfinite(number) || std::fabs(number) > 9.2e18) fail("cannot convert " + toRepr(value) + " to int");
  return static_cast<long long>(number);
}

Value toFloat(const ValueList& arguments) {
  requireCount("float", arguments, 1, 1);
  if (arguments[0].isString()) {
    const Value parsed = literalValue(arguments[0].string());
    if (!parsed.isInt() && !parsed.isFloat()) fail("could not convert string to float: '" + arguments[0].string() + "'");
    return parsed.number();
  }
  return arguments[0].number();
}

Value extreme(const std::string& name, const ValueList& arguments, bool smallest) {
  const ValueList& items = arguments.size() == 1 && arguments[0].isList() ? arguments[0].list() : arguments;
  if (items.empty()) fail(name + "() of an empty sequence");
  Value best = items[0];
  for (const Value& item : items) {
    const int order = compare(name, item, best);
    if (smallest ? order < 0 : order > 0) best = item;
  }
  return best;
}

Value length(const ValueList& arguments) {
  requireCount("len", arguments, 1, 1);
  const Value& value = arguments[0];
  if (value.isString()) return static_cast<long long>(value.string().size());
  if (value.isList()) return static_cast<long long>(value.list().size());
  if (value.isDict()) return static_cast<long long>(value.dict().size());
  fail("object of type '" + typeName(value) + "' has no len()");
}

Value rounded(const ValueList& arguments) {
  requireCount("round", arguments, 1, 2);
  if (arguments.size() == 1) return static_cast<long long>(std::nearbyint(arguments[0].number()));
  const double scale = std::pow(10.0, static_cast<double>(arguments[1].integer()));
  return std::nearbyint(arguments[0].number() * scale) / scale;
}

const std::map<std::string, Builtin>& builtins() {
  static const std::map<std::string, Builtin> functions = [] {
    std::map<std::string, Builtin> f;
    for (const auto& [name, function] : std::vector<std::pair<std::string, double (*)(double)>>{
             {"sqrt", std::sqrt}, {"sin", std::sin}, {"cos", std::cos}, {"tan", std::tan}, {"asin", std::asin},
             {"acos", std::acos}, {"atan", std::atan}, {"sinh", std::sinh}, {"cosh", std::cosh}, {"tanh", std::tanh},
             {"exp", std::exp}, {"log10", std::log10}, {"fabs", std::fabs}}) {
      f[name] = unaryMath(name, function);
    }
    f["log"] = [](const ValueList& a) -> Value {
      requireCount("log", a, 1, 2);
      if (a[0].number() <= 0.0) fail("math domain error in log()");
      return a.size() == 1 ? std::log(a[0].number()) : std::log(a[0].number()) / std::log(a[1].number());
    };
    f["floor"] = [](const ValueList& a) -> Value { return toInteger({Value(std::floor(a.empty() ? 0.0 : a[0].number()))}); };
    f["ceil"] = [](const ValueList& a) -> Value { return toInteger({Value(std::ceil(a.empty() ? 0.0 : a[0].number()))}); };
    f["radians"] = [](const ValueList& a) -> Value { requireCount("radians", a, 1, 1); return a[0].number() * M_PI / 180.0; };
    f["degrees"] = [](const ValueList& a) -> Value { requireCount("degrees", a, 1, 1); return a[0].number() * 180.0 / M_PI; };
    f["atan2"] = [](const ValueList& a) -> Value { requireCount("atan2", a, 2, 2); return std::atan2(a[0].number(), a[1].number()); };
    f["hypot"] = [](const ValueList& a) -> Value { requireCount("hypot", a, 2, 2); return std::hypot(a[0].number(), a[1].number()); };
    f["pow"] = [](const ValueList& a) -> Value { requireCount("pow", a, 2, 2); return power(a[0], a[1]); };
    f["fmod"] = [](const ValueList& a) -> Value {
      requireCount("fmod", a, 2, 2);
      if (a[1].number() == 0.0) fail("math domain error in fmod()");
      return std::fmod(a[0].number(), a[1].number());
    };
    f["abs"] = [](const ValueList& a) -> Value {
      requireCount("abs", a, 1, 1);
      if (integral(a[0])) return a[0].integer() == LLONG_MIN ? Value(9.223372036854775808e18) : Value(std::llabs(a[0].integer()));
      return std::fabs(a[0].number());
    };
    f["int"] = toInteger;
    f["float"] = toFloat;
    f["str"] = [](const ValueList& a) -> Value { requireCount("str", a, 1, 1); return toText(a[0]); };
    f["bool"] = [](const ValueList& a) -> Value { requireCount("bool", a, 1, 1); return isTrue(a[0]); };
    f["len"] = length;
    f["round"] = rounded;
    f["min"] = [](const ValueList& a) { return extreme("min", a, true); };
    f["max"] = [](const ValueList& a) { return extreme("max", a, false); };
    f["list"] = [](const ValueList& a) -> Value {
      requireCount("list", a, 1, 1);
      if (a[0].isList()) return a[0];
      if (a[0].isDict()) {
        ValueList keys;
        for (const auto& [key, item] : a[0].dict()) keys.emplace_back(key);
        return keys;
      }
      fail("list() of a " + typeName(a[0]));
    };
    return f;
  }();
  return functions;
}

// ------------------------------------------------------------------------------------ methods

ValueList split(const std::string& text, const ValueList& arguments) {
  ValueList parts;
  if (arguments.empty() || arguments[0].isNone()) {
    std::size_t start = text.find_first_not_of(" \t\r\n");
    while (start != std::string::npos) {
      const std::size_t end = text.find_first_of(" \t\r\n", start);
      parts.emplace_back(text.substr(start, end - start));
      start = end == std::string::npos ? end : text.find_first_not_of(" \t\r\n", end);
    }
    return parts;
  }
  const std::string& separator = arguments[0].string();
  if (separator.empty()) fail("split() with an empty separator");
  std::size_t start = 0;
  for (std::size_t found = text.find(separator); found != std::string::npos; found = text.find(separator, start)) {
    parts.emplace_back(text.substr(start, found - start));
    start = found + separator.size();
  }
  parts.emplace_back(text.substr(start));
  return parts;
}

std::string stripped(std::string text, bool left, bool right) {
  const char* spaces = " \t\r\n";
  if (right) text.erase(text.find_last_not_of(spaces) + 1);
  if (left) text.erase(0, std::min(text.size(), text.find_first_not_of(spaces)));
  return text;
}

Value stringMethod(const std::string& name, const std::string& text, const ValueList& a) {
  if (name == "split") return split(text, a);
  if (name == "strip" || name == "lstrip" || name == "rstrip") return stripped(text, name != "rstrip", name != "lstrip");
  if (name == "lower" || name == "upper") {
    std::string result = text;
    for (char& c : result) c = static_cast<char>(name == "lower" ? std::tolower(static_cast<unsigned char>(c)) : std::toupper(static_cast<unsigned char>(c)));
    return result;
  }
  if (name == "startswith") {
    requireCount("startswith", a, 1, 1);
    return text.rfind(a[0].string(), 0) == 0;
  }
  if (name == "endswith") {
    requireCount("endswith", a, 1, 1);
    const std::string& end = a[0].string();
    return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
  }
  if (name == "find") {
    requireCount("find", a, 1, 1);
    const std::size_t found = text.find(a[0].string());
    return found == std::string::npos ? -1LL : static_cast<long long>(found);
  }
  if (name == "replace") {
    requireCount("replace", a, 2, 2);
    const std::string& from = a[0].string();
    if (from.empty()) fail("replace() of an empty string");
    std::string result;
    std::size_t start = 0;
    for (std::size_t found = text.find(from); found != std::string::npos; found = text.find(from, start)) {
      result += text.substr(start, found - start) + a[1].string();
      start = found + from.size();
    }
    return result + text.substr(start);
  }
  if (name == "join") {
    requireCount("join", a, 1, 1);
    std::string result;
    const ValueList& items = a[0].list();
    for (std::size_t i = 0; i < items.size(); ++i) result += (i == 0 ? "" : text) + items[i].string();
    return result;
  }
  fail("'str' object has no attribute '" + name + "'");
}

Value dictMethod(const std::string& name, const ValueDict& dict, const ValueList& a) {
  if (name == "get") {
    requireCount("get", a, 1, 2);
    const Value* found = findKey(dict, a[0].string());
    return found != nullptr ? *found : (a.size() == 2 ? a[1] : Value());
  }
  ValueList items;
  for (const auto& [key, item] : dict) {
    if (name == "keys") items.emplace_back(key);
    if (name == "values") items.push_back(item);
    if (name == "items") items.emplace_back(ValueList{Value(key), item});
  }
  if (name != "keys" && name != "values" && name != "items") fail("'dict' object has no attribute '" + name + "'");
  return items;
}

}  // namespace

Value binaryOperation(std::string_view op, const Value& a, const Value& b) {
  if (op == "==") return equal(a, b);
  if (op == "!=") return !equal(a, b);
  if (op == "in") return contains(b, a);
  if (op == "not in") return !contains(b, a);
  if (op == "<") return compare(op, a, b) < 0;
  if (op == ">") return compare(op, a, b) > 0;
  if (op == "<=") return compare(op, a, b) <= 0;
  if (op == ">=") return compare(op, a, b) >= 0;
  if (op == "+" && a.isString() && b.isString()) {
    if (a.string().size() + b.string().size() > kMaxStringLength) fail("string longer than 16 MiB");
    spendWork((a.string().size() + b.string().size()) / 64 + 1);
    return a.string() + b.string();
  }
  if (op == "+" && a.isList() && b.isList()) {
    if (a.list().size() + b.list().size() > kMaxListLength) fail("list longer than 1000000 items");
    spendWork(a.list().size() + b.list().size() + 1);
    ValueList items = a.list();
    items.insert(items.end(), b.list().begin(), b.list().end());
    return items;
  }
  if (op == "*" && (a.isString() || a.isList()) && integral(b)) return repeated(a, b);
  if (op == "*" && (b.isString() || b.isList()) && integral(a)) return repeated(b, a);
  if (!a.isNumber() || !b.isNumber()) unsupported(op, a, b);
  if (op == "**") return power(a, b);
  return arithmetic(op, a, b);
}

Value unaryOperation(std::string_view op, const Value& a) {
  if (op == "not") return !isTrue(a);
  if (!a.isNumber()) fail("bad operand type for unary " + std::string(op) + ": '" + typeName(a) + "'");
  if (op == "+") return integral(a) ? Value(a.integer()) : a;
  if (integral(a)) return arithmetic("-", Value(0), a);
  return -a.number();
}

Value attribute(const Value& value, const std::string& name) {
  if (value.isDict()) {
    if (const Value* found = findKey(value.dict(), name)) return *found;
  }
  if (value.isFunction() && !value.function().self) {
    const std::string& space = value.function().name;
    if (space == "math" && (name == "pi" || name == "e" || name == "tau" || name == "inf" || name == "nan")) return *builtinName(name);
    return Function{space + "." + name, nullptr};
  }
  if (value.isString() || value.isDict() || value.isList()) return Function{name, std::make_shared<const Value>(value)};
  fail("'" + typeName(value) + "' object has no attribute '" + name + "'");
}

Value subscript(const Value& value, const Value& key) {
  if (value.isDict()) {
    if (!key.isString()) fail("dict keys are strings, got " + toRepr(key));
    if (const Value* found = findKey(value.dict(), key.string())) return *found;
    fail("key " + toRepr(key) + " is not in the dict");
  }
  if (value.isList()) return value.list()[position(key.integer(), value.list().size())];
  if (value.isString()) return std::string(1, value.string()[position(key.integer(), value.string().size())]);
  fail("'" + typeName(value) + "' object is not subscriptable");
}

std::optional<Value> builtinName(const std::string& name) {
  if (name == "pi") return Value(M_PI);
  if (name == "e") return Value(M_E);
  if (name == "tau") return Value(2.0 * M_PI);
  if (name == "inf") return Value(HUGE_VAL);
  if (name == "nan") return Value(std::nan(""));
  if (name == "math" || name == "xacro" || name == "load_yaml" || builtins().count(name) != 0) {
    return Value(Function{name, nullptr});
  }
  return std::nullopt;
}

Value callFunction(const Function& function, const ValueList& arguments, const ExpressionScope& scope) {
  if (function.self) {
    const Value& self = *function.self;
    if (self.isString()) return stringMethod(function.name, self.string(), arguments);
    if (self.isDict()) return dictMethod(function.name, self.dict(), arguments);
    fail("'" + typeName(self) + "' object has no method '" + function.name + "'");
  }
  std::string name = function.name;
  if (name.rfind("math.", 0) == 0) name = name.substr(5);
  if (const auto found = builtins().find(name); found != builtins().end()) return found->second(arguments);
  if (function.name.rfind("xacro.", 0) == 0 || function.name == "load_yaml") return scope.call(function.name, arguments);
  fail("'" + function.name + "' is not callable");
}

}  // namespace lang2manip::xacro
