#pragma once
/// @file A process-wide cache of allowed-collision matrices, one per (robot model, settings), so
/// that every checker built for the same model shares one sampling. Thread-safe.

#include <cstddef>
#include <functional>
#include <memory>

#include "lang2manip/collision/allowed_collision_matrix.hpp"
#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

/// The matrix of `model` for `settings`: computed by `compute` on the first request, shared
/// afterwards. The key is the model's identity (the object, not its name or file: two models
/// read from the same file are two entries) and every field of `settings`; an entry whose model
/// has been destroyed is never returned (a new model at the same address is computed afresh).
/// Concurrent first requests for one key run `compute` once; the others wait for its result.
/// When `compute` throws, every waiting caller gets the exception and the next request retries.
/// Deterministic: the matrix is whatever `compute` returns for that model (it must be a
/// function of the model and the settings only).
std::shared_ptr<const AllowedCollisionMatrix> cachedAllowedCollisionMatrix(
    const RobotModelPtr& model, const AllowedCollisionSettings& settings,
    const std::function<AllowedCollisionMatrix()>& compute);

/// Number of live entries in the cache (entries of destroyed models are not counted).
std::size_t allowedCollisionCacheSize();

}  // namespace lang2manip
