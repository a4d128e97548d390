#pragma once
/// @file Internal to the model module: pugixml documents with line numbers for messages and
/// strict attribute access. Not part of the public API (pugixml is a private dependency).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <pugixml.hpp>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/types.hpp"

namespace lang2manip {

/// Deepest element nesting accepted in any XML input (URDF, SRDF, Kautham files nest under 10).
inline constexpr int kMaxXmlDepth = 100;

/// A parsed XML file that can say on which line a node starts. Documents nested deeper than
/// kMaxXmlDepth are refused at load.
class XmlDocument {
 public:
  /// Reads and parses `path`. Throws InputError "<path>: cannot read ..." or
  /// "<path>:<line>: malformed XML: <reason>" on failure. `what` names the kind of file.
  static XmlDocument loadFile(const std::filesystem::path& path, const std::string& what);
  /// Parses `text`; `sourceName` stands for the file in messages.
  static XmlDocument loadString(const std::string& text, const std::string& sourceName,
                                const std::string& what);

  [[nodiscard]] pugi::xml_node root() const { return document_->document_element(); }
  [[nodiscard]] const std::string& sourceName() const { return sourceName_; }
  [[nodiscard]] const std::string& text() const { return text_; }

  /// 1-based line on which `node` starts (0 when unknown).
  [[nodiscard]] int lineOf(const pugi::xml_node& node) const;
  [[nodiscard]] SourceLocation where(const pugi::xml_node& node) const {
    return {sourceName_, lineOf(node)};
  }

  /// The attribute's value; throws InputError "<file>:<line>: <element> needs attribute <name>".
  std::string requiredAttribute(const pugi::xml_node& node, const char* name) const;
  /// A finite number from an attribute, or `fallback` when the attribute is absent.
  [[nodiscard]] double numberAttribute(const pugi::xml_node& node, const char* name,
                                       double fallback) const;
  /// A finite number from a required attribute.
  double requiredNumberAttribute(const pugi::xml_node& node, const char* name) const;

 private:
  XmlDocument() = default;
  void parse(const std::string& what);

  std::shared_ptr<pugi::xml_document> document_;
  std::string sourceName_;
  std::string text_;
  std::vector<std::size_t> lineStarts_;
};

/// `text` with XML special characters escaped, for attribute values and text.
std::string xmlEscaped(const std::string& text);

/// `value` with enough digits (%.17g) to read back exactly.
std::string exactNumber(double value);

/// Reads a whole file; throws InputError "<path>: <what> does not exist" (or "is a directory, not a
/// file", "is a character device, ...", "cannot be read", too large: see kMaxTextFileBytes).
std::string readTextFile(const std::filesystem::path& path, const std::string& what);

}  // namespace lang2manip
