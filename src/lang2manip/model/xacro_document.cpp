#include "lang2manip/model/xacro_document.hpp"

#include <cstdlib>

namespace lang2manip::xacro {

Scope* scopeOwning(Scope& scope, const std::string& name) {
  for (Scope* s = &scope; s != nullptr; s = s->parent) {
    if (s->properties.count(name) != 0) return s;
  }
  return nullptr;
}

const Macro* findMacro(const std::string& name, Scope& scope) {
  const std::size_t dot = name.find('.');
  for (Scope* s = &scope; s != nullptr; s = s->parent) {
    if (dot != std::string::npos) {
      const auto space = s->namespaces.find(name.substr(0, dot));
      if (space != s->namespaces.end()) return findMacro(name.substr(dot + 1), *space->second);
    } else if (const auto found = s->macros.find(name); found != s->macros.end()) {
      return &found->second;
    }
  }
  return nullptr;
}

void markOrigins(XmlDocument& document, int fileIndex) {
  struct Marker final : pugi::xml_tree_walker {
    const XmlDocument* document = nullptr;
    int file = 0;
    bool for_each(pugi::xml_node& node) override {
      if (node.type() == pugi::node_element) {
        node.append_attribute(kOriginAttribute) = (std::to_string(file) + ":" + std::to_string(document->lineOf(node))).c_str();
      }
      return true;
    }
  } marker;
  marker.document = &document;
  marker.file = fileIndex;
  pugi::xml_node root = document.root();
  root.append_attribute(kOriginAttribute) = (std::to_string(fileIndex) + ":" + std::to_string(document.lineOf(root))).c_str();
  root.traverse(marker);
}

void removeOrigins(pugi::xml_node node) {
  node.remove_attribute(kOriginAttribute);
  for (pugi::xml_node child : node.children()) {
    if (child.type() == pugi::node_element) removeOrigins(child);
  }
}

std::optional<std::pair<std::size_t, int>> originOf(const pugi::xml_node& node) {
  for (pugi::xml_node at = node; at; at = at.parent()) {
    const std::string origin = at.attribute(kOriginAttribute).value();
    const std::size_t colon = origin.find(':');
    if (colon == std::string::npos) continue;
    return std::pair{static_cast<std::size_t>(std::atoi(origin.c_str())), std::atoi(origin.c_str() + colon + 1)};
  }
  return std::nullopt;
}

}  // namespace lang2manip::xacro
