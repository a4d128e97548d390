#pragma once
/// @file Internal to the xacro processor: the values of xacro's Python expressions (None, bool,
/// int, float, str, list, dict and functions), with Python's conversions to text and truth.

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace lang2manip::xacro {

/// An error in an expression or a value's use; the processor adds the file, line and macro.
class ExpressionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Longest string one expression or text may build (16 MiB; robot descriptions write a few KB).
inline constexpr std::size_t kMaxStringLength = std::size_t{1} << 24;

/// Most list items one operation may build.
inline constexpr std::size_t kMaxListLength = 1000000;

/// Most units of work (values printed, compared or copied, characters joined, YAML nodes read,
/// expressions evaluated) one expansion may do: a bound on the time of a description written to
/// blow up (shared lists repeated and printed, YAML aliases), far above what real ones need.
inline constexpr std::uint64_t kMaxXacroWork = 50'000'000;

/// Counts `units` of work against the budget active on this thread (nothing when none is).
/// @throws ExpressionError when the budget is spent.
void spendWork(std::uint64_t units);

/// A fresh work budget of kMaxXacroWork for this thread while it lives; nested budgets share the
/// outermost one (an expansion, or one expression evaluated on its own).
class WorkBudget {
 public:
  WorkBudget();
  ~WorkBudget();
  WorkBudget(const WorkBudget&) = delete;
  WorkBudget& operator=(const WorkBudget&) = delete;

 private:
  bool outermost_ = false;
};

struct Value;
using ValueList = std::vector<Value>;
/// Keys in insertion order, as Python dicts keep them.
using ValueDict = std::vector<std::pair<std::string, Value>>;

/// A function or method not yet called: `name` is qualified ("math.sin", "xacro.load_yaml",
/// "split"); `self` is the object of a method (null for a plain function or a namespace).
struct Function {
  std::string name;
  std::shared_ptr<const Value> self;
};

/// One value. Lists and dicts are shared and never modified after they are built.
struct Value {
  using Data = std::variant<std::monostate, bool, long long, double, std::string,
                            std::shared_ptr<const ValueList>, std::shared_ptr<const ValueDict>, Function>;
  Data data;

  Value() = default;
  Value(bool value) : data(value) {}                 // NOLINT(google-explicit-constructor)
  Value(long long value) : data(value) {}            // NOLINT(google-explicit-constructor)
  Value(int value) : data(static_cast<long long>(value)) {}  // NOLINT(google-explicit-constructor)
  Value(double value) : data(value) {}               // NOLINT(google-explicit-constructor)
  Value(std::string value) : data(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  Value(const char* value) : data(std::string(value)) {}  // NOLINT(google-explicit-constructor)
  Value(ValueList value) : data(std::make_shared<const ValueList>(std::move(value))) {}  // NOLINT
  Value(ValueDict value) : data(std::make_shared<const ValueDict>(std::move(value))) {}  // NOLINT
  Value(Function value) : data(std::move(value)) {}  // NOLINT(google-explicit-constructor)

  [[nodiscard]] bool isNone() const { return std::holds_alternative<std::monostate>(data); }
  [[nodiscard]] bool isBool() const { return std::holds_alternative<bool>(data); }
  [[nodiscard]] bool isInt() const { return std::holds_alternative<long long>(data); }
  [[nodiscard]] bool isFloat() const { return std::holds_alternative<double>(data); }
  /// bool, int or float (Python's bool is an int).
  [[nodiscard]] bool isNumber() const { return isBool() || isInt() || isFloat(); }
  [[nodiscard]] bool isString() const { return std::holds_alternative<std::string>(data); }
  [[nodiscard]] bool isList() const { return std::holds_alternative<std::shared_ptr<const ValueList>>(data); }
  [[nodiscard]] bool isDict() const { return std::holds_alternative<std::shared_ptr<const ValueDict>>(data); }
  [[nodiscard]] bool isFunction() const { return std::holds_alternative<Function>(data); }

  /// The number as a double; throws ExpressionError for other types.
  [[nodiscard]] double number() const;
  /// The integer of a bool or int; throws ExpressionError for other types.
  [[nodiscard]] long long integer() const;
  [[nodiscard]] const std::string& string() const;
  [[nodiscard]] const ValueList& list() const;
  [[nodiscard]] const ValueDict& dict() const;
  [[nodiscard]] const Function& function() const;
};

/// Python's type name: "NoneType", "bool", "int", "float", "str", "list", "dict", "function".
std::string typeName(const Value& value);

/// Python's str(): floats as repr() writes them ("0.5", "1.0", "1e-05"), True/False, None.
std::string toText(const Value& value);

/// Python's repr() (strings quoted), used inside lists and dicts.
std::string toRepr(const Value& value);

/// Python's truth value.
bool isTrue(const Value& value);

/// Python's ==.
bool equal(const Value& a, const Value& b);

/// The value of `key` in `dict`, or null.
const Value* findKey(const ValueDict& dict, std::string_view key);

/// What xacro makes of a property's or parameter's text: a quoted 'text' loses its quotes; an
/// integer or float literal (without underscores) becomes a number; "true"/"false" (any case)
/// a bool; anything else stays a string.
Value literalValue(const std::string& text);

}  // namespace lang2manip::xacro
