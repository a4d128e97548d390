#include "lang2manip/planning/kautham_planner_parameters.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <vector>

namespace lang2manip {
namespace {

struct Entry {
  const char* planner;
  const char* name;
  const char* omplName;
  const char* noEffect;
};

constexpr const char* kNoPotential = "it weighs Kautham's <Potential> cost map, which lang2manip does not read";
constexpr const char* kKauthamObjective = "it tunes Kautham's clearance and PMD objectives; paths are optimized for length";

// Kautham's planner-specific parameters (src/planner/omplg/ompl*planner.cpp). OMPL's own names
// ("Range" = range, "Goal Bias" = goal_bias, ...) are found without this table.
const std::vector<Entry>& entries() {
  static const std::vector<Entry> table = {
      {"PRM", "DistanceThreshold", "",
       "Kautham filters roadmap connections by distance; lang2manip's PRM tries its max_nearest_neighbors nearest"},
      {"PRM", "MinGrowTime", "", "OMPL's PRM shares its time between growing and expanding the roadmap 2:1"},
      {"PRM", "MinExpandTime", "", "OMPL's PRM shares its time between growing and expanding the roadmap 2:1"},
      {"PRM", "BounceDistanceThreshold", "", "the roadmap's random bounce walks are not bounded by a distance"},
      {"PRM", "BounceSteps", "", "Kautham's PRM ignores it too (it always bounces 5 steps)"},
      {"PRM", "Sampler 0(r) 1(h) 2(sdk) 3(g)", "",
       "samples are uniform random (Kautham's Halton and SDK samplers are not implemented)"},
      {"PRM", "Sampler 0(r) 1(h) 2(sdk) 3(g) 4(gl)", "",
       "samples are uniform random (Kautham's Halton and SDK samplers are not implemented)"},
      {"KPIECE1", "maxNumSteps", "", "Kautham's multi-step growth is not part of OMPL's KPIECE1"},
      {"KPIECE1", "failedExpansionScoreFactor", "failed_expansion_score_factor", ""},
      {"KPIECE1", "Cell Size", "", "the projection keeps OMPL's default cell sizes"},
      {"RRTstar", "Path Bias", "", "sampling near the path found is Kautham's own"},
      {"RRTstar", "Path Sampling Range Factor", "", "sampling near the path found is Kautham's own"},
      {"RRTstar", "Node Rejection", "new_state_rejection", ""},
      {"RRTstar", "DelayCC (0/1)", "delay_collision_checking", ""},
      {"RRTstar", "K-Neigh Factor", "rewire_factor", ""},
      {"RRTstar", "Optimize none(0)/dist(1)/clear(2)/PMD(3)", "", kKauthamObjective},
      {"RRTstar", "KP", "", kKauthamObjective},
      {"RRTstar", "KI", "", kKauthamObjective},
      {"RRTstar", "KD", "", kKauthamObjective},
      {"RRTstar", "Path Length Weight", "", kKauthamObjective},
      {"RRTstar", "lengthweight(0..1)", "", kKauthamObjective},
      {"RRTstar", "penalizationweight", "", kKauthamObjective},
      {"RRTstar", "orientationweight", "", kKauthamObjective},
      {"RRTstar", "disablePMDControlsFromSampling", "", kKauthamObjective},
      {"TRRT", "Max States Failed", "", "OMPL 1.5's TRRT has no such setting"},
      {"TRRT", "T Change Factor", "temp_change_factor", ""},
      {"TRRT", "Frontier Threshold", "frontier_threshold", ""},
      {"TRRT", "Frontier Nodes Ratio", "frontier_node_ratio", ""},
      {"TRRT", "Init Temp", "init_temperature", ""},
      {"TRRT", "Min Temp", "", "OMPL 1.5's TRRT has no minimum temperature"},
      {"TRRT", "K Constant", "", kNoPotential},
      {"TRRT", "Path Length Weight", "", kNoPotential},
      {"BiTRRT", "Max States Succeed", "", "OMPL 1.5's BiTRRT has no such setting"},
      {"BiTRRT", "Max States Failed", "", "OMPL 1.5's BiTRRT has no such setting"},
      {"BiTRRT", "Temp Change Factor", "temp_change_factor", ""},
      {"BiTRRT", "Frontier Threshold", "frontier_threshold", ""},
      {"BiTRRT", "Frontier Node Ratio", "frontier_node_ratio", ""},
      {"BiTRRT", "Init Temp", "init_temperature", ""},
      {"BiTRRT", "Min Temp", "", "OMPL 1.5's BiTRRT has no minimum temperature"},
      {"BiTRRT", "K Constant", "", kNoPotential},
      {"BiTRRT", "Path Length Weight", "", kNoPotential},
  };
  return table;
}

/// Lower case, leading underscores and repeated spaces dropped.
std::string key(const std::string& name) {
  std::string result;
  std::size_t i = name.find_first_not_of('_');
  for (; i < name.size(); ++i) {
    const char c = static_cast<char>(std::tolower(static_cast<unsigned char>(name[i])));
    if (c == ' ' && (result.empty() || result.back() == ' ')) continue;
    result += c;
  }
  while (!result.empty() && result.back() == ' ') result.pop_back();
  return result;
}

/// The number `value` starts with, or nullopt.
std::optional<double> numberOf(const std::string& value) {
  char* end = nullptr;
  const double number = std::strtod(value.c_str(), &end);
  if (end == value.c_str()) return std::nullopt;
  return number;
}

}  // namespace

std::optional<KauthamParameterMeaning> kauthamPlannerParameter(const std::string& canonicalPlanner,
                                                               const std::string& name,
                                                               const std::string& value) {
  const std::string wanted = key(name);
  const auto found = std::find_if(entries().begin(), entries().end(), [&](const Entry& entry) {
    return entry.planner == canonicalPlanner && key(entry.name) == wanted;
  });
  if (found == entries().end()) return std::nullopt;
  KauthamParameterMeaning meaning{found->omplName, found->noEffect, ""};
  const std::optional<double> number = numberOf(value);
  const bool sampler = wanted.rfind("sampler", 0) == 0;
  const bool defaultChoice = number && ((sampler && *number == 0.0) ||
                                        (wanted.rfind("optimize", 0) == 0 && *number == 1.0));
  if (defaultChoice) meaning.noEffect.clear();
  if (sampler && number && (*number == 0.0 || *number == 3.0 || *number == 4.0)) {
    meaning.noEffect.clear();
    meaning.validStateSampler = *number == 0.0 ? "uniform" : "gaussian";
  }
  return meaning;
}

}  // namespace lang2manip
