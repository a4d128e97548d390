#include <pugixml.hpp>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/model/xacro.hpp"
#include "lang2manip/model/xacro_document.hpp"
#include "lang2manip/model/xacro_expression.hpp"
#include "lang2manip/model/xacro_support.hpp"
#include "lang2manip/model/xml_document.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;
using xacro::ExpressionError;
using xacro::findMacro;
using xacro::Macro;
using xacro::MacroParameter;
using xacro::Property;
using xacro::Scope;
using xacro::scopeOwning;
using xacro::TextPart;
using xacro::Value;
using xacro::ValueList;

constexpr const char* kOrigin = xacro::kOriginAttribute;

bool hasPrefix(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

class XacroProcessor {
 public:
  explicit XacroProcessor(const XacroOptions& options) : options_(options), arguments_(options.arguments) {}

  std::string run(const fs::path& path) {
    const xacro::WorkBudget budget;
    pugi::xml_node root = output_.append_copy(load(path).root());
    processChildren(root, top_);
    for (pugi::xml_attribute attribute : root.attributes()) attribute.set_value(text(attribute.value(), top_, root).c_str());
    for (pugi::xml_attribute attribute = root.first_attribute(); attribute;) {
      const pugi::xml_attribute next = attribute.next_attribute();
      if (hasPrefix(attribute.name(), "xmlns:xacro") || std::string(attribute.name()) == kOrigin) root.remove_attribute(attribute);
      attribute = next;
    }
    xacro::removeOrigins(root);
    std::ostringstream stream;
    output_.save(stream, "  ", pugi::format_indent);
    return stream.str();
  }

 private:
  // ------------------------------------------------------------------------------- documents

  /// Parses `path` and marks every element with its origin.
  XmlDocument load(const fs::path& path) {
    XmlDocument document = XmlDocument::loadFile(path, "xacro file");
    xacro::markOrigins(document, static_cast<int>(files_.size()));
    files_.push_back(path);
    return document;
  }

  SourceLocation where(const pugi::xml_node& node) const {
    const auto origin = xacro::originOf(node);
    if (origin && origin->first < files_.size()) return {files_[origin->first].string(), origin->second};
    return {files_.empty() ? "" : files_.front().string(), 0};
  }

  fs::path currentFile(const pugi::xml_node& node) const { return fs::path(where(node).file); }

  /// An error of another file (a YAML or included file) raised here: its message, prefixed with
  /// this element's place unless it is already an error of this processor.
  [[noreturn]] void rethrowInContext(const pugi::xml_node& node, const InputError& error) const {
    if (inContext_) throw error;
    fail(node, error.what());
  }

  [[noreturn]] void fail(const pugi::xml_node& node, const std::string& what) const {
    inContext_ = true;
    std::string context;
    for (auto call = calls_.rbegin(); call != calls_.rend(); ++call) {
      context += " (in macro '" + call->first + "' called at " + call->second.toString() + ")";
    }
    throw InputError(where(node), what + context);
  }

  // ---------------------------------------------------------------------------------- names

  std::optional<Value> lookup(const std::string& name, Scope& scope, const pugi::xml_node& at) {
    Scope* owner = scopeOwning(scope, name);
    if (owner == nullptr) {
      for (Scope* s = &scope; s != nullptr; s = s->parent) {
        if (const auto found = s->namespaces.find(name); found != s->namespaces.end()) return namespaceValue(*found->second, at);
      }
      return std::nullopt;
    }
    Property& property = owner->properties[name];
    if (property.block) throw ExpressionError("property '" + name + "' is a block: insert it with <xacro:insert_block>");
    if (property.text) {
      if (evaluating_.count(owner) != 0 && evaluating_[owner].count(name) != 0) {
        throw ExpressionError("property '" + name + "' is defined in terms of itself");
      }
      evaluating_[owner].insert(name);
      const std::string text = *property.text;
      Value value = typed(evaluate(text, *owner, at));
      evaluating_[owner].erase(name);
      Property& stored = owner->properties[name];
      stored.value = value;
      stored.text.reset();
    }
    return owner->properties[name].value;
  }

  Value namespaceValue(Scope& space, const pugi::xml_node& at) {
    xacro::ValueDict items;
    for (auto& [name, property] : space.properties) {
      if (!property.block) items.emplace_back(name, *lookup(name, space, at));
    }
    return items;
  }

  // -------------------------------------------------------------------------------- text

  static Value typed(const Value& value) { return value.isString() ? xacro::literalValue(value.string()) : value; }

  /// The value of `text`: the typed value of a lone ${}, else the joined string.
  Value evaluate(const std::string& text, Scope& scope, const pugi::xml_node& at) {
    const std::vector<TextPart> parts = xacro::splitText(text);
    if (parts.size() == 1 && parts[0].kind == TextPart::Kind::kExpression) return expression(parts[0].text, scope, at);
    std::string result;
    for (const TextPart& part : parts) {
      if (part.kind == TextPart::Kind::kLiteral) result += part.text;
      if (part.kind == TextPart::Kind::kExpression) result += xacro::toText(expression(part.text, scope, at));
      if (part.kind == TextPart::Kind::kSubstitution) result += substitution(xacro::toText(evaluate(part.text, scope, at)), scope, at);
      if (result.size() > xacro::kMaxStringLength) throw ExpressionError("text longer than 16 MiB");
    }
    xacro::spendWork(result.size() / 64 + 1);
    return result;
  }

  std::string text(const std::string& raw, Scope& scope, const pugi::xml_node& at) {
    if (raw.find('$') == std::string::npos) return raw;
    try {
      std::string result = xacro::toText(evaluate(raw, scope, at));
      outputBytes_ += result.size();
      if (outputBytes_ > kMaxOutputBytes) fail(at, "expansion exceeds " + std::to_string(kMaxOutputBytes >> 20) + " MiB of text");
      return result;
    } catch (const ExpressionError& error) {
      fail(at, "\"" + raw.substr(0, 120) + "\": " + error.what());
    } catch (const InputError& error) {
      rethrowInContext(at, error);
    }
  }

  /// The Python code of a ${} with its $() substitutions made first, as xacro does.
  Value expression(const std::string& raw, Scope& scope, const pugi::xml_node& at) {
    std::string code = raw;
    if (raw.find("$(") != std::string::npos) {
      code.clear();
      for (const TextPart& part : xacro::splitText(raw)) {
        if (part.kind == TextPart::Kind::kLiteral) code += part.text;
        if (part.kind == TextPart::Kind::kExpression) code += "${" + part.text + "}";
        if (part.kind == TextPart::Kind::kSubstitution) code += substitution(xacro::toText(evaluate(part.text, scope, at)), scope, at);
      }
    }
    xacro::ExpressionScope expressionScope;
    expressionScope.lookup = [&](const std::string& name) { return lookup(name, scope, at); };
    expressionScope.call = [&](const std::string& name, const ValueList& arguments) { return call(name, arguments, at); };
    return xacro::evaluateExpression(code, expressionScope);
  }

  Value call(const std::string& name, const ValueList& arguments, const pugi::xml_node& at) {
    return xacro::callXacroFunction(name, arguments, currentFile(at), where(at).toString());
  }

  std::string substitution(const std::string& command, Scope& scope, const pugi::xml_node& at) {
    const xacro::SubstitutionContext context{arguments_, currentFile(at), options_.packagePaths,
                                             [&](const std::string& code) { return xacro::toText(expression(code, scope, at)); }};
    return xacro::substitutionArgument(command, context);
  }

  // ------------------------------------------------------------------------------ elements

  void processChildren(pugi::xml_node parent, Scope& scope) {
    if (++depth_ > kMaxXacroDepth) fail(parent, "elements nest more than " + std::to_string(kMaxXacroDepth) + " levels deep");
    for (pugi::xml_node node = parent.first_child(); node;) {
      const pugi::xml_node next = node.next_sibling();
      if (node.type() == pugi::node_element) {
        if (++elements_ > kMaxXacroElements) fail(node, "expansion exceeds " + std::to_string(kMaxXacroElements) + " elements");
        element(node, scope);
      } else if (node.type() == pugi::node_pcdata || node.type() == pugi::node_cdata) {
        node.set_value(text(node.value(), scope, node).c_str());
      }
      node = next;
    }
    --depth_;
  }

  /// Moves the children of `container` before it and removes it.
  static void unwrap(pugi::xml_node container) {
    pugi::xml_node parent = container.parent();
    while (pugi::xml_node child = container.first_child()) parent.insert_move_before(child, container);
    parent.remove_child(container);
  }

  std::string attribute(const pugi::xml_node& node, const char* name, Scope& scope, bool required = true) {
    const pugi::xml_attribute found = node.attribute(name);
    if (!found) {
      if (required) fail(node, std::string("<") + node.name() + "> needs attribute \"" + name + "\"");
      return "";
    }
    return text(found.value(), scope, node);
  }

  bool condition(const pugi::xml_node& node, Scope& scope) {
    const std::string raw = node.attribute("value").value();
    Value value;
    try {
      value = typed(evaluate(raw, scope, node));
    } catch (const ExpressionError& error) {
      fail(node, "\"" + raw.substr(0, 120) + "\": " + error.what());
    } catch (const InputError& error) {
      rethrowInContext(node, error);
    }
    if (value.isBool() || value.isInt() || value.isFloat()) return xacro::isTrue(value);
    fail(node, std::string("<") + node.name() + "> value \"" + raw.substr(0, 120) + "\" is " + xacro::toRepr(value) + ", not a boolean");
  }

  void element(pugi::xml_node node, Scope& scope) {
    const std::string name = node.name();
    if (!hasPrefix(name, "xacro:")) {
      for (pugi::xml_attribute attribute : node.attributes()) {
        if (std::string(attribute.name()) != kOrigin) attribute.set_value(text(attribute.value(), scope, node).c_str());
      }
      processChildren(node, scope);
      return;
    }
    const std::string verb = name.substr(6);
    if (verb == "property") return defineProperty(node, scope);
    if (verb == "macro") return defineMacro(node, scope);
    if (verb == "arg") return defineArgument(node, scope);
    if (verb == "include") return include(node, scope);
    if (verb == "if" || verb == "unless") {
      if (condition(node, scope) == (verb == "if")) {
        processChildren(node, scope);
        unwrap(node);
      } else {
        node.parent().remove_child(node);
      }
      return;
    }
    if (verb == "insert_block") return insertBlock(node, scope);
    if (verb == "element") return makeElement(node, scope);
    if (verb == "attribute") {
      node.parent().append_attribute(attribute(node, "name", scope).c_str()) = attribute(node, "value", scope).c_str();
      node.parent().remove_child(node);
      return;
    }
    const std::string macroName = verb == "call" ? attribute(node, "macro", scope) : verb;
    const Macro* macro = findMacro(macroName, scope);
    if (macro == nullptr) fail(node, "unknown macro or xacro element \"xacro:" + macroName + "\"");
    callMacro(node, *macro, macroName, scope);
  }

  void defineProperty(pugi::xml_node node, Scope& scope) {
    const std::string name = attribute(node, "name", scope);
    Scope* target = &scope;
    const std::string where = node.attribute("scope").value();
    if (where == "parent" && scope.parent != nullptr) target = scope.parent;
    if (where == "global") {
      while (target->parent != nullptr) target = target->parent;
    }
    const bool hasDefault = node.attribute("default") && !node.attribute("value");
    if (hasDefault && scopeOwning(scope, name) != nullptr) {
      node.parent().remove_child(node);
      return;
    }
    Property property;
    const char* valueAttribute = hasDefault ? "default" : "value";
    if (node.attribute(valueAttribute)) {
      const std::string raw = node.attribute(valueAttribute).value();
      const bool lazy = std::string(node.attribute("lazy_eval").value()) != "false";
      if (lazy && target == &scope) {
        property.text = raw;
      } else {
        try {
          property.value = typed(evaluate(raw, scope, node));
        } catch (const ExpressionError& error) {
          fail(node, "property \"" + name + "\": " + error.what());
        } catch (const InputError& error) {
          rethrowInContext(node, error);
        }
      }
    } else {
      property.block = store_.append_copy(node);
    }
    target->properties[name] = property;
    node.parent().remove_child(node);
  }

  void defineMacro(pugi::xml_node node, Scope& scope) {
    Macro macro;
    macro.definition = store_.append_copy(node);
    try {
      macro.parameters = xacro::parseMacroParameters(node.attribute("params").value());
    } catch (const ExpressionError& error) {
      fail(node, error.what());
    }
    const std::string name = attribute(node, "name", scope);
    scope.macros[name] = macro;
    node.parent().remove_child(node);
  }

  void defineArgument(pugi::xml_node node, Scope& scope) {
    const std::string name = attribute(node, "name", scope);
    if (arguments_.count(name) == 0 && node.attribute("default")) arguments_[name] = attribute(node, "default", scope);
    node.parent().remove_child(node);
  }

  void include(pugi::xml_node node, Scope& scope) {
    fs::path file = attribute(node, "filename", scope);
    if (file.is_relative()) file = currentFile(node).parent_path() / file;
    if (static_cast<int>(calls_.size()) + includes_ >= kMaxXacroNesting) {
      fail(node, "includes and macro calls nest more than " + std::to_string(kMaxXacroNesting) + " levels (a file that includes itself?)");
    }
    Scope* target = &scope;
    if (const std::string space = attribute(node, "ns", scope, false); !space.empty()) {
      auto& slot = scope.namespaces[space];
      if (!slot) slot = std::make_unique<Scope>();
      slot->parent = &scope;
      target = slot.get();
    }
    XmlDocument document = [&] {
      try {
        return load(file);
      } catch (const InputError& error) {
        fail(node, std::string("<xacro:include>: ") + error.what());
      }
    }();
    pugi::xml_node container = node.parent().insert_child_before("lang2manip-include", node);
    for (pugi::xml_node child : document.root().children()) container.append_copy(child);
    ++includes_;
    processChildren(container, *target);
    --includes_;
    unwrap(container);
    node.parent().remove_child(node);
  }

  void insertBlock(pugi::xml_node node, Scope& scope) {
    const std::string name = attribute(node, "name", scope);
    Scope* owner = scopeOwning(scope, name);
    if (owner == nullptr || !owner->properties[name].block) fail(node, "no block named \"" + name + "\" to insert");
    const Property& block = owner->properties[name];
    pugi::xml_node container = node.parent().insert_child_before("lang2manip-block", node);
    if (block.contentOnly || std::string(block.block.name()) == "xacro:property") {
      for (pugi::xml_node child : block.block.children()) container.append_copy(child);
    } else {
      container.append_copy(block.block);
    }
    processChildren(container, scope);
    unwrap(container);
    node.parent().remove_child(node);
  }

  void makeElement(pugi::xml_node node, Scope& scope) {
    const std::string name = attribute(node, "xacro:name", scope);
    if (name.empty()) fail(node, "<xacro:element> needs a non-empty xacro:name");
    pugi::xml_node made = node.parent().insert_child_before(name.c_str(), node);
    for (pugi::xml_attribute attribute : node.attributes()) {
      if (std::string(attribute.name()) != "xacro:name") made.append_attribute(attribute.name()) = attribute.value();
    }
    for (pugi::xml_node child : node.children()) made.append_copy(child);
    node.parent().remove_child(node);
    element(made, scope);
  }

  void callMacro(pugi::xml_node node, const Macro& macro, const std::string& name, Scope& caller) {
    if (static_cast<int>(calls_.size()) + includes_ >= kMaxXacroNesting) {
      fail(node, "macro calls nest more than " + std::to_string(kMaxXacroNesting) + " levels (a macro that calls itself?)");
    }
    // The call's blocks are expanded where they are written, in the caller's scope, as ROS's
    // xacro does: a block that inserts the caller's own block of the same name is that block.
    calls_.emplace_back(name, where(node));
    processChildren(node, caller);
    calls_.pop_back();
    Scope scope;
    scope.parent = &caller;
    bindParameters(node, macro, name, caller, scope);
    calls_.emplace_back(name, where(node));
    pugi::xml_node container = node.parent().insert_child_before("lang2manip-macro", node);
    for (pugi::xml_node child : macro.definition.children()) container.append_copy(child);
    processChildren(container, scope);
    calls_.pop_back();
    unwrap(container);
    node.parent().remove_child(node);
  }

  void bindParameters(const pugi::xml_node& node, const Macro& macro, const std::string& name, Scope& caller, Scope& scope) {
    std::map<std::string, std::string> given;
    for (pugi::xml_attribute attribute : node.attributes()) {
      const std::string key = attribute.name();
      if (key != kOrigin && !(key == "macro" && hasPrefix(node.name(), "xacro:call"))) given[key] = attribute.value();
    }
    for (const auto& entry : given) {
      const std::string& key = entry.first;
      const bool known = std::any_of(macro.parameters.begin(), macro.parameters.end(), [&](const MacroParameter& p) {
        return p.name == key && p.kind == MacroParameter::Kind::kValue;
      });
      if (!known) fail(node, "macro '" + name + "' has no parameter '" + key + "'");
    }
    pugi::xml_node block = node.first_child();
    for (const MacroParameter& parameter : macro.parameters) {
      Property property;
      if (parameter.kind != MacroParameter::Kind::kValue) {
        while (block && block.type() != pugi::node_element) block = block.next_sibling();
        if (!block) fail(node, "macro '" + name + "' needs a block for its parameter '" + parameter.name + "'");
        property.block = block;
        property.contentOnly = parameter.kind == MacroParameter::Kind::kContent;
        block = block.next_sibling();
      } else if (const auto found = given.find(parameter.name); found != given.end()) {
        property.value = valueOf(found->second, caller, node);
      } else if (parameter.inherit && scopeOwning(caller, parameter.name) != nullptr) {
        property.value = valueOf("${" + parameter.name + "}", caller, node);
      } else if (parameter.defaultText) {
        property.value = valueOf(*parameter.defaultText, scope, node);
      } else {
        fail(node, "macro '" + name + "' needs parameter '" + parameter.name + "'");
      }
      scope.properties[parameter.name] = property;
    }
  }

  Value valueOf(const std::string& raw, Scope& scope, const pugi::xml_node& at) {
    try {
      return typed(evaluate(raw, scope, at));
    } catch (const ExpressionError& error) {
      fail(at, "\"" + raw.substr(0, 120) + "\": " + error.what());
    } catch (const InputError& error) {
      rethrowInContext(at, error);
    }
  }

  const XacroOptions& options_;
  std::map<std::string, std::string> arguments_;
  std::vector<fs::path> files_;
  pugi::xml_document output_;
  pugi::xml_document store_;
  Scope top_;
  std::vector<std::pair<std::string, SourceLocation>> calls_;
  int includes_ = 0;
  int elements_ = 0;
  int depth_ = 0;
  std::size_t outputBytes_ = 0;
  static constexpr std::size_t kMaxOutputBytes = std::size_t{256} << 20;
  /// Set once this processor has thrown: its errors pass through the outer handlers unchanged.
  mutable bool inContext_ = false;
  std::map<const Scope*, std::set<std::string>> evaluating_;
};

}  // namespace

bool isXacroFile(const std::filesystem::path& path) { return path.extension() == ".xacro"; }

std::string expandXacroFile(const std::filesystem::path& path, const XacroOptions& options) {
  return XacroProcessor(options).run(path);
}

std::pair<std::string, std::string> parseXacroArgument(const std::string& text) {
  const std::size_t assign = text.find(":=");
  if (assign == std::string::npos || assign == 0) {
    throw InputError("xacro argument \"" + text + "\" is not NAME:=VALUE");
  }
  return {text.substr(0, assign), text.substr(assign + 2)};
}

}  // namespace lang2manip
