#pragma once
/// @file Internal to the xacro processor: what it works on. Names (properties, macros and
/// include namespaces in dynamically nested scopes) and the origin every element carries through
/// copies, so that an error in an expanded macro still names the file and line it came from.

#include <pugixml.hpp>

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lang2manip/model/xacro_support.hpp"
#include "lang2manip/model/xacro_value.hpp"
#include "lang2manip/model/xml_document.hpp"

namespace lang2manip::xacro {

/// A property: a value, text still to evaluate (lazy), or a block of elements.
struct Property {
  Value value;
  std::optional<std::string> text;
  pugi::xml_node block;
  bool contentOnly = false;
};

struct Macro {
  pugi::xml_node definition;
  std::vector<MacroParameter> parameters;
};

/// One level of names: the file's top level, a macro call or an include namespace. A macro
/// call's scope sees its caller's (xacro scopes dynamically).
struct Scope {
  Scope* parent = nullptr;
  std::map<std::string, Property> properties;
  std::map<std::string, Macro> macros;
  std::map<std::string, std::unique_ptr<Scope>> namespaces;
};

/// The innermost scope from `scope` outwards that defines property `name`, or nullptr.
Scope* scopeOwning(Scope& scope, const std::string& name);

/// Macro `name` ("ns.name" inside include namespace "ns") seen from `scope`, or nullptr.
const Macro* findMacro(const std::string& name, Scope& scope);

/// The attribute that carries each element's origin ("file index:line") through copies.
inline constexpr const char* kOriginAttribute = "lang2manip-xacro-origin";

/// Marks `document`'s root and every element below it as coming from file `fileIndex`.
void markOrigins(XmlDocument& document, int fileIndex);

/// Removes the origin attributes from `node` and every element below it.
void removeOrigins(pugi::xml_node node);

/// (file index, line) of the nearest marked element from `node` up, or nullopt.
std::optional<std::pair<std::size_t, int>> originOf(const pugi::xml_node& node);

}  // namespace lang2manip::xacro
