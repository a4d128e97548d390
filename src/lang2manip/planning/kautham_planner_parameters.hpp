#pragma once
/// @file Kautham's own parameters of its OMPL geometric planners (those of Kautham's omplPRM,
/// omplKPIECE, omplRRTStar, omplTRRT, ... that OMPL does not publish under that name): each one
/// either sets an OMPL parameter or is accepted with the reason it has no effect here, so that
/// Kautham problem files run unchanged. Facts from Kautham's planner sources (src/planner/omplg).

#include <optional>
#include <string>

namespace lang2manip {

/// What one of Kautham's planner parameters does in lang2manip.
struct KauthamParameterMeaning {
  /// The OMPL parameter it sets with the same value ("" when it sets none).
  std::string omplName;
  /// Why it has no effect ("" when it has one, or when its value is the one lang2manip does).
  std::string noEffect;
  /// The valid state sampler it selects (validStateSamplerName(); "" when it selects none).
  std::string validStateSampler;
};

/// The meaning of Kautham parameter `name` (any case, leading underscores ignored) with `value`
/// for planner `canonicalPlanner` (see planner_registry.hpp), or nullopt when Kautham gives that
/// planner no such parameter. Value-dependent: Kautham's PRM "Sampler ..." 0 (uniform random)
/// and 3/4 (Gaussian, Gaussian-like) select a valid state sampler, 1 and 2 (Halton, SDK) have no
/// effect; RRT* "Optimize ..." 1 (path length) is what lang2manip does, other values have none.
std::optional<KauthamParameterMeaning> kauthamPlannerParameter(const std::string& canonicalPlanner,
                                                               const std::string& name,
                                                               const std::string& value);

}  // namespace lang2manip
