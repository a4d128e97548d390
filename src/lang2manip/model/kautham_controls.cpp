#include "lang2manip/model/kautham_controls.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/model/xml_document.hpp"

namespace lang2manip {
namespace {

// Splits "robot/dof" at the last "/".
std::pair<std::string, std::string> splitDofName(const std::string& name,
                                                 const SourceLocation& where) {
  const std::size_t slash = name.rfind('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == name.size()) {
    throw InputError(where, "DOF name \"" + name +
                                "\" is not of the form <robot or obstacle name>/<dof>");
  }
  return {name.substr(0, slash), name.substr(slash + 1)};
}

int dofIndex(ControlSet& set, const XmlDocument& document, const pugi::xml_node& dof) {
  const SourceLocation where = document.where(dof);
  const auto [entity, name] = splitDofName(document.requiredAttribute(dof, "name"), where);
  const int existing = set.findDof(entity, name);
  if (existing >= 0) return existing;
  set.dofs.push_back(ControlledDof{entity, name, 0.5, where.line});
  return static_cast<int>(set.dofs.size()) - 1;
}

void readOffsets(ControlSet& set, const XmlDocument& document) {
  for (const pugi::xml_node& offset : document.root().children("Offset")) {
    for (const pugi::xml_node& dof : offset.children("DOF")) {
      const int index = dofIndex(set, document, dof);
      set.dofs[static_cast<std::size_t>(index)].offset = document.requiredNumberAttribute(dof, "value");
    }
  }
}

void readControls(ControlSet& set, const XmlDocument& document) {
  std::set<std::string> names;
  for (const pugi::xml_node& node : document.root().children("Control")) {
    Control control;
    control.name = document.requiredAttribute(node, "name");
    control.eigValue = document.numberAttribute(node, "eigValue", 1.0);
    control.line = document.lineOf(node);
    if (!names.insert(control.name).second) {
      throw InputError(document.where(node), "control \"" + control.name + "\" is defined twice");
    }
    for (const pugi::xml_node& dof : node.children("DOF")) {
      const double value = document.requiredNumberAttribute(dof, "value");
      control.coefficients.emplace_back(dofIndex(set, document, dof), value);
    }
    if (control.coefficients.empty()) {
      throw InputError(document.where(node), "control \"" + control.name + "\" moves no <DOF>");
    }
    set.controls.push_back(std::move(control));
  }
}

ControlSet readControls(const XmlDocument& document) {
  if (std::string(document.root().name()) != "ControlSet") {
    throw InputError(document.where(document.root()),
                     std::string("the root element is <") + document.root().name() +
                         ">, not <ControlSet>: not a Kautham control file");
  }
  ControlSet set;
  set.source = document.sourceName();
  readOffsets(set, document);
  readControls(set, document);
  return set;
}

}  // namespace

std::vector<double> ControlSet::dofValues(const std::vector<double>& c,
                                          const std::string& what) const {
  if (c.size() != controls.size()) {
    throw InputError(what + " has " + std::to_string(c.size()) + " control values; the control set " +
                     (source.empty() ? std::string("(default controls)") : source) + " has " +
                     std::to_string(controls.size()));
  }
  std::vector<double> p(dofs.size());
  for (std::size_t d = 0; d < dofs.size(); ++d) p[d] = dofs[d].offset;
  for (std::size_t j = 0; j < controls.size(); ++j) {
    if (!std::isfinite(c[j]) || c[j] < 0.0 || c[j] > 1.0) {
      throw InputError(what + ": value " + exactNumber(c[j]) + " of control \"" +
                       controls[j].name + "\" is outside [0, 1]");
    }
    for (const auto& [dof, coefficient] : controls[j].coefficients) {
      p[static_cast<std::size_t>(dof)] += controls[j].eigValue * coefficient * (c[j] - 0.5);
    }
  }
  for (double& value : p) value = std::clamp(value, 0.0, 1.0);
  return p;
}

int ControlSet::findDof(const std::string& entity, const std::string& dof) const {
  for (std::size_t d = 0; d < dofs.size(); ++d) {
    if (dofs[d].entity == entity && dofs[d].dof == dof) return static_cast<int>(d);
  }
  return -1;
}

std::vector<std::string> ControlSet::controlNames() const {
  std::vector<std::string> names;
  for (const Control& control : controls) names.push_back(control.name);
  return names;
}

ControlSet readControlFile(const std::filesystem::path& path) {
  if (path.extension() != ".cntr") {
    throw InputError(SourceLocation{path.string(), 0},
                     "a control file must be a Kautham .cntr file (got extension \"" +
                         path.extension().string() + "\")");
  }
  return readControls(XmlDocument::loadFile(path, "control file"));
}

ControlSet readControlString(const std::string& xml, const std::string& sourceName) {
  return readControls(XmlDocument::loadString(xml, sourceName, "control file"));
}

std::string writeControlString(const ControlSet& controls) {
  // Every DOF goes into <Offset>, 0.5 included: that keeps the DOF order, and a DOF that only
  // has an offset (e.g. a base X3 fixing a yaw) would otherwise be lost.
  std::string xml = "<?xml version=\"1.0\"?>\n<ControlSet>\n  <Offset>\n";
  for (const ControlledDof& dof : controls.dofs) {
    xml += "    <DOF name=\"" + xmlEscaped(dof.fullName()) + "\" value=\"" + exactNumber(dof.offset) +
           "\"/>\n";
  }
  xml += "  </Offset>\n";
  for (const Control& control : controls.controls) {
    xml += "  <Control name=\"" + xmlEscaped(control.name) + "\" eigValue=\"" +
           exactNumber(control.eigValue) + "\">\n";
    for (const auto& [dof, coefficient] : control.coefficients) {
      xml += "    <DOF name=\"" + xmlEscaped(controls.dofs[static_cast<std::size_t>(dof)].fullName()) +
             "\" value=\"" + exactNumber(coefficient) + "\"/>\n";
    }
    xml += "  </Control>\n";
  }
  return xml + "</ControlSet>\n";
}

}  // namespace lang2manip
