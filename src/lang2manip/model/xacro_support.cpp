#include "lang2manip/model/xacro_support.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/model/xml_document.hpp"

namespace lang2manip::xacro {
namespace {

namespace fs = std::filesystem;

bool isDirectory(const fs::path& path) {
  std::error_code error;
  return fs::is_directory(path, error);
}

/// The <name> a package.xml declares ("" when it cannot be read).
std::string declaredName(const fs::path& manifest) {
  std::error_code error;
  if (!fs::is_regular_file(manifest, error)) return "";
  std::string text;
  try {
    text = readTextFile(manifest, "package.xml");
  } catch (const InputError&) {
    return "";
  }
  const std::size_t open = text.find("<name>");
  const std::size_t close = text.find("</name>", open);
  if (open == std::string::npos || close == std::string::npos) return "";
  std::string name = text.substr(open + 6, close - open - 6);
  const auto first = name.find_first_not_of(" \t\r\n");
  const auto last = name.find_last_not_of(" \t\r\n");
  return first == std::string::npos ? "" : name.substr(first, last - first + 1);
}

bool isPackage(const fs::path& directory, const std::string& name) {
  const fs::path manifest = directory / "package.xml";
  std::error_code error;
  if (!fs::is_regular_file(manifest, error)) return false;
  return directory.filename() == name || declaredName(manifest) == name;
}

/// `name` at `root` or up to `depth` levels below it.
std::optional<fs::path> searchBelow(const fs::path& root, const std::string& name, int depth) {
  if (!isDirectory(root)) return std::nullopt;
  if (isPackage(root, name)) return root;
  if (depth == 0) return std::nullopt;
  std::error_code error;
  for (fs::directory_iterator entry(root, error), end; !error && entry != end; entry.increment(error)) {
    if (!entry->is_directory(error)) continue;
    if (auto found = searchBelow(entry->path(), name, depth - 1)) return found;
  }
  return std::nullopt;
}

std::vector<fs::path> pathList(const char* variable) {
  std::vector<fs::path> paths;
  const char* value = std::getenv(variable);
  if (value == nullptr) return paths;
  std::stringstream entries(value);
  std::string entry;
  while (std::getline(entries, entry, ':')) {
    if (!entry.empty()) paths.emplace_back(entry);
  }
  return paths;
}

int lineOf(const YAML::Mark& mark) { return mark.line >= 0 ? mark.line + 1 : 0; }

Value plainScalar(const std::string& text) {
  static const std::set<std::string> kNull = {"", "~", "null", "Null", "NULL"};
  static const std::set<std::string> kTrue = {"true", "True", "TRUE", "yes", "Yes", "YES", "on", "On", "ON"};
  static const std::set<std::string> kFalse = {"false", "False", "FALSE", "no", "No", "NO", "off", "Off", "OFF"};
  if (kNull.count(text) != 0) return Value();
  if (kTrue.count(text) != 0) return true;
  if (kFalse.count(text) != 0) return false;
  if (text == ".inf" || text == ".Inf" || text == "+.inf") return HUGE_VAL;
  if (text == "-.inf" || text == "-.Inf") return -HUGE_VAL;
  if (text == ".nan" || text == ".NaN") return std::nan("");
  if (text.find('_') != std::string::npos || text.find_first_not_of("0123456789+-.eE") != std::string::npos) {
    return text;
  }
  const Value number = literalValue(text);
  return number.isInt() || number.isFloat() ? number : Value(text);
}

/// Most values one YAML file may become (its aliases expanded): far above robot configuration files.
constexpr std::size_t kMaxYamlValues = 1000000;

Value fromYaml(const YAML::Node& node, const std::string& file, int depth, std::size_t& values) {
  spendWork(1);
  if (++values > kMaxYamlValues) {
    throw InputError(SourceLocation{file, lineOf(node.Mark())},
                     "YAML expands to more than " + std::to_string(kMaxYamlValues) + " values (aliases repeated without end?)");
  }
  if (depth > 100) throw InputError(SourceLocation{file, lineOf(node.Mark())}, "YAML nests more than 100 levels deep");
  if (node.IsMap()) {
    ValueDict dict;
    for (const auto& item : node) {
      dict.emplace_back(item.first.as<std::string>(), fromYaml(item.second, file, depth + 1, values));
    }
    return dict;
  }
  if (node.IsSequence()) {
    ValueList list;
    for (const auto& item : node) list.push_back(fromYaml(item, file, depth + 1, values));
    return list;
  }
  if (!node.IsScalar()) return Value();
  const std::string& text = node.Scalar();
  if (node.Tag() == "!degrees" || node.Tag() == "!radians") {
    const Value number = literalValue(text);
    if (!number.isInt() && !number.isFloat()) {
      throw InputError(SourceLocation{file, lineOf(node.Mark())}, node.Tag() + " needs a number, got \"" + text + "\"");
    }
    return node.Tag() == "!degrees" ? number.number() * M_PI / 180.0 : number.number();
  }
  return node.Tag() == "?" ? plainScalar(text) : Value(text);
}

/// The index just past the bracket closing the one at `open` ('{' or '('), skipping quoted
/// strings; npos when it is not closed.
std::size_t closingBracket(const std::string& text, std::size_t open) {
  const char opening = text[open];
  const char closing = opening == '{' ? '}' : ')';
  int depth = 0;
  for (std::size_t i = open; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\'' || c == '"') {
      const std::size_t end = text.find(c, i + 1);
      if (end == std::string::npos) return std::string::npos;
      i = end;
    } else if (c == opening) {
      ++depth;
    } else if (c == closing && --depth == 0) {
      return i + 1;
    }
  }
  return std::string::npos;
}

}  // namespace

std::optional<fs::path> findPackage(const std::string& name, const fs::path& nearFile,
                                    const std::vector<fs::path>& extraPaths) {
  if (name.empty() || name.find('/') != std::string::npos) return std::nullopt;
  std::vector<fs::path> roots = extraPaths;
  for (const char* variable : {"LANG2MANIP_PACKAGE_PATH", "ROS_PACKAGE_PATH"}) {
    for (const fs::path& path : pathList(variable)) roots.push_back(path);
  }
  for (const fs::path& root : roots) {
    if (auto found = searchBelow(root, name, 2)) return found;
  }
  std::error_code error;
  for (fs::path directory = fs::absolute(nearFile, error).parent_path(); !directory.empty();
       directory = directory.parent_path()) {
    if (isPackage(directory, name)) return directory;
    if (isPackage(directory / name, name)) return directory / name;
    if (directory == directory.root_path()) break;
  }
  return std::nullopt;
}

Value loadYamlValue(const fs::path& file) {
  const std::string text = readTextFile(file, "YAML file");
  try {
    std::size_t values = 0;
    return fromYaml(YAML::Load(text), file.string(), 0, values);
  } catch (const YAML::Exception& error) {
    throw InputError(SourceLocation{file.string(), lineOf(error.mark)}, "malformed YAML: " + error.msg);
  }
}

std::vector<MacroParameter> parseMacroParameters(const std::string& params) {
  std::vector<MacroParameter> parameters;
  std::size_t i = 0;
  while (true) {
    i = params.find_first_not_of(" \t\r\n", i);
    if (i == std::string::npos) break;
    std::string word;
    while (i < params.size() && std::string(" \t\r\n").find(params[i]) == std::string::npos) {
      if (params[i] == '\'' || params[i] == '"') {
        const std::size_t end = params.find(params[i], i + 1);
        if (end == std::string::npos) throw ExpressionError("params: a quote is not closed in \"" + params + "\"");
        word += params.substr(i, end - i + 1);
        i = end + 1;
      } else {
        word += params[i++];
      }
    }
    MacroParameter parameter;
    const std::size_t stars = word.find_first_not_of('*');
    if (stars == 1 || stars == 2) {
      parameter.kind = stars == 1 ? MacroParameter::Kind::kBlock : MacroParameter::Kind::kContent;
      word = word.substr(stars);
    }
    const std::size_t assign = word.find('=');
    if (assign != std::string::npos) {
      const bool colon = assign > 0 && word[assign - 1] == ':';
      std::string defaultText = word.substr(assign + 1);
      word = word.substr(0, colon ? assign - 1 : assign);
      if (defaultText.rfind('^', 0) == 0) {
        parameter.inherit = true;
        if (defaultText.rfind("^|", 0) == 0) parameter.defaultText = defaultText.substr(2);
      } else {
        parameter.defaultText = defaultText;
      }
    }
    if (word.empty() || word.find_first_of("*=:") != std::string::npos) {
      throw ExpressionError("params: malformed parameter in \"" + params + "\"");
    }
    parameter.name = word;
    parameters.push_back(parameter);
  }
  return parameters;
}

std::vector<TextPart> splitText(const std::string& text) {
  std::vector<TextPart> parts;
  const auto literal = [&](const std::string& piece) {
    if (piece.empty()) return;
    if (parts.empty() || parts.back().kind != TextPart::Kind::kLiteral) parts.push_back({TextPart::Kind::kLiteral, ""});
    parts.back().text += piece;
  };
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t dollar = text.find('$', i);
    if (dollar == std::string::npos) {
      literal(text.substr(i));
      break;
    }
    literal(text.substr(i, dollar - i));
    const char next = dollar + 1 < text.size() ? text[dollar + 1] : '\0';
    const char after = dollar + 2 < text.size() ? text[dollar + 2] : '\0';
    if (next == '$' && (after == '{' || after == '(')) {
      literal(std::string("$") + after);
      i = dollar + 3;
    } else if (next == '{' || next == '(') {
      const std::size_t end = closingBracket(text, dollar + 1);
      if (end == std::string::npos) {
        throw ExpressionError(std::string(next == '{' ? "${" : "$(") + " is not closed in \"" + text.substr(dollar, 80) + "\"");
      }
      parts.push_back({next == '{' ? TextPart::Kind::kExpression : TextPart::Kind::kSubstitution,
                       text.substr(dollar + 2, end - dollar - 3)});
      i = end;
    } else {
      literal("$");
      i = dollar + 1;
    }
  }
  return parts;
}

std::string substitutionArgument(const std::string& command, const SubstitutionContext& context) {
  std::istringstream words(command);
  std::string verb;
  std::string first;
  words >> verb >> first;
  std::string rest;
  std::getline(words, rest);
  const std::size_t start = rest.find_first_not_of(' ');
  rest = start == std::string::npos ? "" : rest.substr(start);
  if (verb == "arg") {
    const auto found = context.arguments.find(first);
    if (found == context.arguments.end()) {
      throw ExpressionError("undefined argument '" + first + "' (declare it with <xacro:arg> or pass " + first + ":=VALUE)");
    }
    return found->second;
  }
  if (verb == "find") {
    const auto package = findPackage(first, context.currentFile, context.packagePaths);
    if (!package) {
      throw ExpressionError("package '" + first + "' not found (searched LANG2MANIP_PACKAGE_PATH, ROS_PACKAGE_PATH and the directories above " +
                            context.currentFile.string() + " for its package.xml)");
    }
    return package->string();
  }
  if (verb == "env" || verb == "optenv") {
    if (const char* value = std::getenv(first.c_str())) return value;
    if (verb == "optenv") return rest;
    throw ExpressionError("environment variable '" + first + "' is not set");
  }
  if (verb == "dirname") return context.currentFile.parent_path().string();
  if (verb == "eval") return context.evaluate(command.substr(command.find("eval") + 4));
  throw ExpressionError("$(" + verb + " ...) is not supported (arg, find, env, optenv, dirname and eval are)");
}

Value callXacroFunction(const std::string& name, const ValueList& arguments, const fs::path& currentFile,
                        const std::string& location) {
  const std::string function = name.rfind("xacro.", 0) == 0 ? name.substr(6) : name;
  std::string message;
  for (const Value& argument : arguments) message += toText(argument);
  if (function == "load_yaml") {
    if (arguments.size() != 1) throw ExpressionError("load_yaml() takes 1 argument");
    fs::path file = arguments[0].string();
    if (file.is_relative()) file = currentFile.parent_path() / file;
    return loadYamlValue(file);
  }
  if (function == "warning" || function == "message" || function == "print_location") {
    if (function == "warning") logWarning(location + ": xacro warning: " + message);
    return Value();
  }
  if (function == "error" || function == "fatal") throw ExpressionError("xacro error: " + message);
  throw ExpressionError("'" + name + "' is not a function of xacro");
}

}  // namespace lang2manip::xacro
