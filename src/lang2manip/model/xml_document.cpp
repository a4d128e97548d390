#include "lang2manip/model/xml_document.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "lang2manip/core/file_checks.hpp"
#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {

std::string readTextFile(const std::filesystem::path& path, const std::string& what) {
  requireRegularFile(path, what);
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (!error && size > kMaxTextFileBytes) {
    throw InputError(SourceLocation{path.string(), 0},
                     what + " is " + std::to_string(size >> 20) + " MiB, more than the " +
                         std::to_string(kMaxTextFileBytes >> 20) + " MiB read as text");
  }
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream contents;
  if (!stream || !(contents << stream.rdbuf())) {
    if (stream && !error && size == 0) return {};
    throw InputError(SourceLocation{path.string(), 0}, what + " cannot be read");
  }
  return contents.str();
}

namespace {

/// Stops pugixml's (iterative) traversal at the first node nested deeper than kMaxXmlDepth, so
/// that the recursive readers after it (urdfdom's TinyXML among them) never see such a document.
class DepthLimit final : public pugi::xml_tree_walker {
 public:
  bool for_each(pugi::xml_node& node) override {
    if (depth() < kMaxXmlDepth) return true;
    tooDeep = node;
    return false;
  }
  pugi::xml_node tooDeep;
};

}  // namespace

XmlDocument XmlDocument::loadFile(const std::filesystem::path& path, const std::string& what) {
  XmlDocument document;
  document.sourceName_ = path.string();
  document.text_ = readTextFile(path, what);
  document.parse(what);
  return document;
}

XmlDocument XmlDocument::loadString(const std::string& text, const std::string& sourceName,
                                    const std::string& what) {
  XmlDocument document;
  document.sourceName_ = sourceName;
  document.text_ = text;
  document.parse(what);
  return document;
}

void XmlDocument::parse(const std::string& what) {
  lineStarts_.push_back(0);
  for (std::size_t i = 0; i < text_.size(); ++i) {
    if (text_[i] == '\n') lineStarts_.push_back(i + 1);
  }
  document_ = std::make_shared<pugi::xml_document>();
  const pugi::xml_parse_result result =
      document_->load_buffer(text_.data(), text_.size(), pugi::parse_default | pugi::parse_comments);
  if (!result) {
    const auto offset = static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, result.offset));
    const auto line = static_cast<int>(
        std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset) - lineStarts_.begin());
    throw InputError(SourceLocation{sourceName_, line},
                     "malformed XML in " + what + ": " + result.description());
  }
  if (!document_->document_element()) {
    throw InputError(SourceLocation{sourceName_, 0}, what + " has no XML root element");
  }
  DepthLimit depthLimit;
  if (!document_->traverse(depthLimit)) {
    throw InputError(where(depthLimit.tooDeep), what + " nests elements more than " +
                                                    std::to_string(kMaxXmlDepth) + " levels deep");
  }
}

int XmlDocument::lineOf(const pugi::xml_node& node) const {
  const std::ptrdiff_t offset = node.offset_debug();
  if (offset < 0) return 0;
  return static_cast<int>(std::upper_bound(lineStarts_.begin(), lineStarts_.end(),
                                           static_cast<std::size_t>(offset)) -
                          lineStarts_.begin());
}

std::string XmlDocument::requiredAttribute(const pugi::xml_node& node, const char* name) const {
  const pugi::xml_attribute attribute = node.attribute(name);
  if (!attribute) {
    throw InputError(where(node), std::string("<") + node.name() + "> needs attribute \"" + name +
                                      "\"");
  }
  return attribute.value();
}

double XmlDocument::numberAttribute(const pugi::xml_node& node, const char* name,
                                    double fallback) const {
  const pugi::xml_attribute attribute = node.attribute(name);
  if (!attribute) return fallback;
  return parseFiniteNumber(attribute.value(),
                           std::string("<") + node.name() + "> attribute " + name, where(node));
}

double XmlDocument::requiredNumberAttribute(const pugi::xml_node& node, const char* name) const {
  requiredAttribute(node, name);
  return numberAttribute(node, name, 0.0);
}

std::string xmlEscaped(const std::string& text) {
  std::string escaped;
  for (const char c : text) {
    switch (c) {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      case '\'': escaped += "&apos;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

std::string exactNumber(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

}  // namespace lang2manip
