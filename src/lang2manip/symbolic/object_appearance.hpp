#pragma once
/// @file How an object looks, in words: the colour names of a documented palette (with the muted
/// shades of the tabletop benchmarks, Code as Policies and Ravens, so that their red is red) and a
/// category from its shape ("cube", "box", "cylinder", "ball", "bowl", "tray", "cup", "table").
/// Shared by the observation an LLM reads and the offline planner's object descriptors.

#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// The nearest named colour of an RGB colour (components 0..1): one of colourNames().
std::string nearestColourName(const Vector3& rgb);

/// The colour names of the palette: "black", "grey", "white", "red", "green", "blue", "yellow",
/// "orange", "purple", "pink", "brown", "cyan".
std::vector<std::string> colourNames();

/// The colour words of the object's name ("red_block": red), which its author chose; else the
/// nearest named colour of the material of its largest visual (or collision) shape; empty when it
/// has none.
std::vector<std::string> objectColours(const SceneObject& object);

/// A category from the collision shapes: a single box is a "cube" (sides within 20 % of each other),
/// a "plate" (height under a quarter of its width) or a "box"; a cylinder a "cylinder"; a sphere a
/// "ball"; a container a "bowl" (opening at least as wide as deep), a "tray" (depth under a quarter
/// of its opening) or a "cup"; a support a "table"; empty for anything else.
std::string objectCategory(const SceneObject& object);

}  // namespace lang2manip
