#pragma once
/// @file Internal: checks a URDF's XML before urdfdom sees it, so that every problem is reported
/// with its line (urdfdom reports none): element and attribute shapes, numbers, duplicate names,
/// unknown links, several parents, several roots, cycles.

#include "lang2manip/model/xml_document.hpp"

namespace lang2manip {

/// Most links a robot may have: far above any real robot (humanoids have about a hundred), and a
/// bound on the work and stack depth of reading and understanding one.
inline constexpr int kMaxRobotLinks = 4096;

/// Throws InputError "<file>:<line>: <what>" on the first problem found (more than kMaxRobotLinks
/// links among them).
void checkUrdfStructure(const XmlDocument& urdf);

}  // namespace lang2manip
