#pragma once
/// @file A planner and its parameters, set from strings under OMPL's names ("range",
/// "goal_bias") or Kautham's ("Range", "Goal Bias", "_Max Planning Time", "_Simplify Solution").
/// Values are checked against the planner's published ranges.

#include <string>
#include <utility>
#include <vector>

namespace lang2manip {

/// A parameter that was accepted but changes nothing, and why (a Kautham-only planner setting).
struct IgnoredParameter {
  std::string name;
  std::string value;
  std::string reason;
};

/// How sampling planners draw valid states (OMPL's valid state samplers). Gaussian, obstacle-
/// based and bridge-test samplers put more samples near obstacles, where narrow passages are.
enum class ValidStateSampler { kUniform, kGaussian, kObstacleBased, kBridgeTest };

/// "uniform", "gaussian", "obstacle_based", "bridge_test".
std::string validStateSamplerName(ValidStateSampler sampler);

/// Path simplification, as Kautham's `_Simplify Solution`.
enum class SimplifyLevel { kNone = 0, kSmooth = 1, kShortcutAndSmooth = 2 };

class PlannerSettings {
 public:
  /// RRTConnect with OMPL's defaults, 10 s, shortcut and smooth.
  PlannerSettings();

  /// Selects a planner by name or alias (see planner_registry.hpp) and clears the planner-
  /// specific parameters; the common ones (time, simplification, ...) are kept.
  void setPlanner(const std::string& name);
  [[nodiscard]] const std::string& planner() const noexcept { return planner_; }

  /// Sets one parameter from its string value. Common parameters: `_Max Planning Time` (s, > 0),
  /// `_Simplify Solution` (0, 1, 2), `_Optimize` (0/1: optimizing planners refine until the time
  /// limit instead of stopping at their first solution), `_Incremental` (0/1: keep the planner's
  /// graph between queries), and Kautham's display options `_Speed Factor`, `_Cspace Drawn`,
  /// `_Path Drawn` (accepted and kept; they do not change planning), `_Valid State Sampler`
  /// (validStateSamplerName(); Kautham's PRM `Sampler` 3 (Gaussian) and 4 (Gaussian-like) set it
  /// to gaussian). Planner parameters by OMPL's
  /// name or Kautham's ("Goal Bias" = goal_bias). Throws InputError for an unknown name (listing
  /// the valid ones), a value of the wrong type or outside the published range. Kautham's own
  /// planner parameters (kautham_planner_parameters.hpp: omplPRM's DistanceThreshold, ...) set
  /// their OMPL counterpart or, with a number as value, are listed in ignoredParameters().
  void setParameter(const std::string& name, const std::string& value);

  /// The Kautham parameters accepted without effect since the planner was chosen.
  [[nodiscard]] const std::vector<IgnoredParameter>& ignoredParameters() const noexcept { return ignored_; }

  /// Every parameter name setParameter() accepts for the current planner (Kautham's common
  /// names and OMPL's names of the planner's parameters).
  [[nodiscard]] std::vector<std::string> parameterNames() const;

  [[nodiscard]] double maxPlanningTime() const noexcept { return maxPlanningTime_; }
  [[nodiscard]] SimplifyLevel simplifyLevel() const noexcept { return simplifyLevel_; }
  [[nodiscard]] bool optimize() const noexcept { return optimize_; }
  [[nodiscard]] bool incremental() const noexcept { return incremental_; }
  [[nodiscard]] double speedFactor() const noexcept { return speedFactor_; }
  [[nodiscard]] ValidStateSampler validStateSampler() const noexcept { return validStateSampler_; }
  /// The planner-specific parameters by OMPL name, in the order they were set.
  [[nodiscard]] const std::vector<std::pair<std::string, std::string>>& omplParameters() const noexcept {
    return omplParameters_;
  }

 private:
  bool setCommonParameter(const std::string& key, const std::string& name, const std::string& value);
  void setOmplParameter(const std::string& name, const std::string& value);

  std::string planner_;
  double maxPlanningTime_ = 10.0;
  SimplifyLevel simplifyLevel_ = SimplifyLevel::kShortcutAndSmooth;
  bool optimize_ = false;
  bool incremental_ = false;
  double speedFactor_ = 1.0;
  ValidStateSampler validStateSampler_ = ValidStateSampler::kUniform;
  std::vector<std::pair<std::string, std::string>> omplParameters_;
  std::vector<IgnoredParameter> ignored_;
};

}  // namespace lang2manip
