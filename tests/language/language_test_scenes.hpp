#pragma once
/// @file Scenes for the language tests: the built-in desk scene and richer scenes built in code
/// (blocks and cups of several colours and sizes, a box, two markers), with helpers to stack
/// and fill them.

#include <string>
#include <vector>

#include "lang2manip/language/object_descriptor.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip::test {

/// The two scenes instruction tables refer to.
enum class SceneId { kDesk, kWorkbench };
/// Short names for the tables.
inline constexpr SceneId D = SceneId::kDesk;
inline constexpr SceneId W = SceneId::kWorkbench;

/// The object descriptors of scene `scene` (computed once).
std::vector<ObjectDescriptor> descriptorsFor(SceneId scene);

/// The paper's scene (panda_desk): desk, marker, eraser, holder.
Scene deskScene();

/// A table (support) with red_block and blue_block (4 cm cubes), green_block (6 cm cube),
/// white_cup (large) and yellow_cup (small) (containers), box (a container), marker_1 (red) and
/// marker_2 (black), all resting on the table; no robot, so places are in the world frame
/// (x forward, y left).
Scene workbenchScene();

/// Moves `object` so it rests on top of `support` (centred).
void restOn(Scene& scene, const std::string& object, const std::string& support);

/// Moves `object` into the cavity of `container` (centred, on its floor).
void putInside(Scene& scene, const std::string& object, const std::string& container);

}  // namespace lang2manip::test
