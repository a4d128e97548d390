#include "lang2manip/model/xacro_expression.hpp"

#include <cctype>
#include <cstring>
#include <vector>

#include "lang2manip/model/xacro_operations.hpp"

namespace lang2manip::xacro {
namespace {

enum class TokenKind { kNumber, kString, kName, kOperator, kEnd };

struct Token {
  TokenKind kind;
  std::string text;
};

bool isNameStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0 || c == '_'; }
bool isNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }

std::string stringLiteral(std::string_view text, std::size_t& i) {
  const char quote = text[i++];
  std::string value;
  while (i < text.size() && text[i] != quote) {
    char c = text[i++];
    if (c == '\\' && i < text.size()) {
      const char escaped = text[i++];
      c = escaped == 'n' ? '\n' : escaped == 't' ? '\t' : escaped;
    }
    value += c;
  }
  if (i >= text.size()) throw ExpressionError("string literal is not closed");
  ++i;
  return value;
}

std::size_t numberEnd(std::string_view text, std::size_t i) {
  while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) != 0 || text[i] == '.')) ++i;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    std::size_t j = i + 1;
    if (j < text.size() && (text[j] == '+' || text[j] == '-')) ++j;
    if (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j])) != 0) {
      i = j;
      while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) != 0) ++i;
    }
  }
  return i;
}

std::vector<Token> tokenize(std::string_view text) {
  static const char* const kTwoCharOperators[] = {"**", "//", "==", "!=", "<=", ">="};
  std::vector<Token> tokens;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c)) != 0) {
      ++i;
    } else if (std::isdigit(static_cast<unsigned char>(c)) != 0 ||
               (c == '.' && i + 1 < text.size() && std::isdigit(static_cast<unsigned char>(text[i + 1])) != 0)) {
      const std::size_t end = numberEnd(text, i);
      tokens.push_back({TokenKind::kNumber, std::string(text.substr(i, end - i))});
      i = end;
    } else if (c == '\'' || c == '"') {
      tokens.push_back({TokenKind::kString, stringLiteral(text, i)});
    } else if (isNameStart(c)) {
      std::size_t end = i;
      while (end < text.size() && isNameChar(text[end])) ++end;
      tokens.push_back({TokenKind::kName, std::string(text.substr(i, end - i))});
      i = end;
    } else {
      std::string op(1, c);
      for (const char* two : kTwoCharOperators) {
        if (text.compare(i, 2, two) == 0) op = two;
      }
      if (std::strchr("+-*/%()[]{},:.<>", c) == nullptr && op.size() == 1) {
        throw ExpressionError(std::string("unexpected character '") + c + "'");
      }
      tokens.push_back({TokenKind::kOperator, op});
      i += op.size();
    }
  }
  tokens.push_back({TokenKind::kEnd, ""});
  return tokens;
}

bool isKeyword(const std::string& name) {
  return name == "and" || name == "or" || name == "not" || name == "in" || name == "if" || name == "else" ||
         name == "is" || name == "lambda" || name == "for";
}

/// Recursive descent over Python's grammar, evaluating as it goes. With `live` false a
/// sub-expression is only parsed (the branch `and`, `or` or `if` does not take), so it neither
/// looks names up nor calls anything.
class Evaluator {
 public:
  Evaluator(std::string_view text, const ExpressionScope& scope) : tokens_(tokenize(text)), close_(tokens_.size(), 0), scope_(scope) {
    std::vector<std::size_t> open;
    for (std::size_t i = 0; i < tokens_.size(); ++i) {
      if (tokens_[i].kind != TokenKind::kOperator) continue;
      const std::string& symbol = tokens_[i].text;
      if (symbol == "(" || symbol == "[" || symbol == "{") open.push_back(i);
      if ((symbol == ")" || symbol == "]" || symbol == "}") && !open.empty()) {
        close_[open.back()] = i;
        open.pop_back();
      }
    }
  }

  Value run() {
    Value value = ternary(true);
    if (peek().kind != TokenKind::kEnd) throw ExpressionError("unexpected '" + peek().text + "' after the expression");
    return value;
  }

 private:
  const Token& peek() const { return tokens_[next_]; }
  bool at(const char* text) const { return peek().kind != TokenKind::kString && peek().text == text; }
  bool accept(const char* text) {
    if (!at(text)) return false;
    ++next_;
    return true;
  }
  void expect(const char* text) {
    if (!accept(text)) {
      throw ExpressionError(std::string("expected '") + text + "'" +
                            (peek().kind == TokenKind::kEnd ? " at the end" : ", got '" + peek().text + "'"));
    }
  }

  /// Counts nesting for kMaxExpressionDepth.
  struct Depth {
    explicit Depth(int& depth) : depth_(depth) {
      if (++depth_ > kMaxExpressionDepth) throw ExpressionError("expression nested more than 100 levels deep");
    }
    ~Depth() { --depth_; }
    Depth(const Depth&) = delete;
    Depth& operator=(const Depth&) = delete;
    int& depth_;
  };

  /// Whether the conditional expression starting at token `start` has an "if" of its own
  /// (bracketed groups are skipped whole, so this is linear in the expression).
  bool hasCondition(std::size_t start) const {
    for (std::size_t i = start; tokens_[i].kind != TokenKind::kEnd; ++i) {
      const Token& token = tokens_[i];
      if (token.kind == TokenKind::kName && (token.text == "if" || token.text == "else")) return token.text == "if";
      if (token.kind != TokenKind::kOperator) continue;
      if (token.text == "(" || token.text == "[" || token.text == "{") {
        if (close_[i] == 0) return false;  // unbalanced: the parser reports it
        i = close_[i];
      } else if (token.text == ")" || token.text == "]" || token.text == "}" || token.text == "," || token.text == ":") {
        return false;
      }
    }
    return false;
  }

  /// `a if c else b`: c first, then only the branch taken is evaluated (a is parsed past first).
  Value ternary(bool live) {
    const Depth depth(depth_);
    if (!hasCondition(next_)) return logicalOr(live);
    const std::size_t start = next_;
    (void)logicalOr(false);
    expect("if");
    const bool condition = isTrue(logicalOr(live));
    expect("else");
    Value otherwise = ternary(live && !condition);
    if (!(live && condition)) return otherwise;
    const std::size_t end = next_;
    next_ = start;
    Value value = logicalOr(true);
    next_ = end;
    return value;
  }

  Value logicalOr(bool live) {
    Value value = logicalAnd(live);
    while (accept("or")) {
      const bool decided = live && isTrue(value);
      Value right = logicalAnd(live && !decided);
      if (live && !decided) value = right;
    }
    return value;
  }

  Value logicalAnd(bool live) {
    Value value = logicalNot(live);
    while (accept("and")) {
      const bool decided = live && !isTrue(value);
      Value right = logicalNot(live && !decided);
      if (live && !decided) value = right;
    }
    return value;
  }

  Value logicalNot(bool live) {
    if (accept("not")) {
      const Depth depth(depth_);
      Value operand = logicalNot(live);
      return live ? unaryOperation("not", operand) : Value();
    }
    return comparison(live);
  }

  /// The comparison operator at the cursor ("" when none), consumed.
  std::string comparisonOperator() {
    for (const char* op : {"==", "!=", "<=", ">=", "<", ">", "in"}) {
      if (accept(op)) return op;
    }
    if (at("not") && tokens_[next_ + 1].text == "in") {
      next_ += 2;
      return "not in";
    }
    if (accept("is")) return accept("not") ? "!=" : "==";
    return "";
  }

  Value comparison(bool live) {
    Value left = arithmetic(live);
    std::string op = comparisonOperator();
    if (op.empty()) return left;
    bool result = true;
    for (; !op.empty(); op = comparisonOperator()) {
      Value right = arithmetic(live);
      if (live && result) result = isTrue(binaryOperation(op, left, right));
      left = right;
    }
    return live ? Value(result) : Value();
  }

  Value arithmetic(bool live) {
    Value value = term(live);
    while (at("+") || at("-")) {
      const std::string op = tokens_[next_++].text;
      Value right = term(live);
      if (live) value = binaryOperation(op, value, right);
    }
    return value;
  }

  Value term(bool live) {
    Value value = factor(live);
    while (at("*") || at("/") || at("//") || at("%")) {
      const std::string op = tokens_[next_++].text;
      Value right = factor(live);
      if (live) value = binaryOperation(op, value, right);
    }
    return value;
  }

  Value factor(bool live) {
    if (at("-") || at("+")) {
      const std::string op = tokens_[next_++].text;
      const Depth depth(depth_);
      Value operand = factor(live);
      return live ? unaryOperation(op, operand) : Value();
    }
    Value base = primary(live);
    if (!accept("**")) return base;
    const Depth depth(depth_);
    Value exponent = factor(live);
    return live ? binaryOperation("**", base, exponent) : Value();
  }

  Value primary(bool live) {
    Value value = atom(live);
    while (true) {
      if (accept(".")) {
        if (peek().kind != TokenKind::kName) throw ExpressionError("expected a name after '.'");
        const std::string name = tokens_[next_++].text;
        if (live) value = attribute(value, name);
      } else if (accept("[")) {
        const Depth depth(depth_);
        Value key = ternary(live);
        expect("]");
        if (live) value = subscript(value, key);
      } else if (accept("(")) {
        const Depth depth(depth_);
        ValueList arguments = sequence(live, ")");
        if (live) value = callFunction(value.function(), arguments, scope_);
      } else {
        return value;
      }
    }
  }

  ValueList sequence(bool live, const char* close) {
    ValueList items;
    while (!accept(close)) {
      items.push_back(ternary(live));
      if (!accept(",")) {
        expect(close);
        break;
      }
    }
    return items;
  }

  Value atom(bool live) {
    const Token token = peek();
    ++next_;
    switch (token.kind) {
      case TokenKind::kNumber: return number(token.text);
      case TokenKind::kString: {
        std::string text = token.text;
        while (peek().kind == TokenKind::kString) text += tokens_[next_++].text;
        return text;
      }
      case TokenKind::kName: return name(token.text, live);
      case TokenKind::kEnd: throw ExpressionError("expression ends too early");
      case TokenKind::kOperator: break;
    }
    const Depth depth(depth_);
    if (token.text == "(") {
      Value value = ternary(live);
      expect(")");
      return value;
    }
    if (token.text == "[") return sequence(live, "]");
    if (token.text == "{") return dictionary(live);
    throw ExpressionError("unexpected '" + token.text + "'");
  }

  Value dictionary(bool live) {
    ValueDict items;
    while (!accept("}")) {
      Value key = ternary(live);
      expect(":");
      Value item = ternary(live);
      if (live) items.emplace_back(toText(key), item);
      if (!accept(",")) {
        expect("}");
        break;
      }
    }
    return items;
  }

  static Value number(const std::string& text) {
    const Value value = literalValue(text);
    if (!value.isInt() && !value.isFloat()) throw ExpressionError("malformed number '" + text + "'");
    return value;
  }

  Value name(const std::string& text, bool live) {
    if (text == "True") return true;
    if (text == "False") return false;
    if (text == "None") return Value();
    if (isKeyword(text)) throw ExpressionError("unexpected '" + text + "'");
    if (!live) return Value();
    if (std::optional<Value> value = scope_.lookup(text)) return *value;
    if (std::optional<Value> value = builtinName(text)) return *value;
    throw ExpressionError("name '" + text + "' is not defined");
  }

  std::vector<Token> tokens_;
  /// For an opening bracket token, the index of its closing one (0 when there is none).
  std::vector<std::size_t> close_;
  std::size_t next_ = 0;
  int depth_ = 0;
  const ExpressionScope& scope_;
};

}  // namespace

Value evaluateExpression(std::string_view text, const ExpressionScope& scope) {
  if (text.size() > kMaxExpressionLength) {
    throw ExpressionError("expression longer than " + std::to_string(kMaxExpressionLength) + " characters");
  }
  const WorkBudget budget;
  spendWork(text.size() / 16 + 1);
  return Evaluator(text, scope).run();
}

}  // namespace lang2manip::xacro
