#pragma once
/// @file Internal: checks a URDF's XML before urdfdom sees it, so that every problem is reported
/// with its line (urdfdom reports none): element and attribute shapes, numbers, duplicate names,
/// unknown links, several parents, several roots, cycles.

#include "lang2manip/model/xml_document.hpp"

namespace lang2manip {

/// Throws InputError "<file>:<line>: <what>" on the first problem found.
void checkUrdfStructure(const XmlDocument& urdf);

}  // namespace lang2manip
