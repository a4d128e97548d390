#pragma once
/// @file Scenes with their movable objects moved at random, for the task-level benchmarks.

#include <optional>

#include "lang2manip/core/random.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// `scene` with every movable object shifted by up to `spread` (m) in x and y and turned by up to
/// `turn` (rad) about z, none overlapping another object's bounds; nullopt after 100 tries.
std::optional<Scene> randomizedScene(const Scene& scene, double spread, double turn, Random& random);

}  // namespace lang2manip
