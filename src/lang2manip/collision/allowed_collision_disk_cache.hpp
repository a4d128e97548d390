#pragma once
/// @file Allowed-collision matrices kept on disk between processes, so that a robot with mesh
/// links samples its matrix once per machine instead of once per command (seconds for a mesh
/// robot). Files are keyed by a digest of everything the matrix depends on; a file that does not
/// read back exactly is ignored and replaced. Safe with concurrent processes: a file is written
/// under a unique temporary name and renamed into place, so readers see a whole file or none.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "lang2manip/collision/allowed_collision_matrix.hpp"
#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

/// Bump when computeAllowedCollisionMatrix() or the link collision test it is given changes
/// what it returns for the same model and settings: older files then no longer match any key.
inline constexpr int kAllowedCollisionAlgorithmVersion = 4;

/// The directory the matrices are kept in: $LANG2MANIP_CACHE_DIR, else
/// $XDG_CACHE_HOME/lang2manip, else $HOME/.cache/lang2manip; nullopt when none is set or
/// LANG2MANIP_CACHE_DIR is "off" (no disk cache).
std::optional<std::filesystem::path> allowedCollisionCacheDirectory();

/// A hex digest of what the matrix of `model` depends on: every link's collision shapes (kind,
/// dimensions, pose, name, and a mesh's vertices, triangles and scale), every joint (type,
/// links, origin, axis, limits, mimic), the SRDF's disabled pairs, `settings` and
/// kAllowedCollisionAlgorithmVersion. Link, joint and shape names are part of it (capsule parts
/// are merged by name); visuals are not.
std::string allowedCollisionKey(const RobotModel& model, const AllowedCollisionSettings& settings);

/// The matrix stored under `key` in `directory` for `model`, or nullopt when there is none or it
/// does not read back (not a regular file or larger than any matrix, wrong format, another link
/// count or link names, an unknown reason).
std::optional<AllowedCollisionMatrix> readStoredAllowedCollisions(const std::filesystem::path& directory,
                                                                  const std::string& key,
                                                                  const RobotModel& model);

/// Stores `matrix` under `key` in `directory` (created when missing). Returns false, and leaves
/// no partial file, when the directory cannot be created or written.
bool storeAllowedCollisions(const std::filesystem::path& directory, const std::string& key,
                            const RobotModel& model, const AllowedCollisionMatrix& matrix);

/// The stored matrix for (`model`, `settings`) when allowedCollisionCacheDirectory() has one and
/// `confirms` holds of it (what the file claims is checked, not trusted: see
/// allowsNoMoreThan()), else `compute()`, stored for the next process. A stored matrix that is
/// not confirmed is replaced, with a warning; a directory that cannot be written logs one warning
/// and is skipped.
AllowedCollisionMatrix storedOrComputedAllowedCollisions(const RobotModel& model,
                                                         const AllowedCollisionSettings& settings,
                                                         const std::function<AllowedCollisionMatrix()>& compute,
                                                         const std::function<bool(const AllowedCollisionMatrix&)>& confirms);

}  // namespace lang2manip
