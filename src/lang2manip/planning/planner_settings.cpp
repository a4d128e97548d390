#include "lang2manip/planning/planner_settings.hpp"

#include <algorithm>
#include <cctype>
#include <map>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/planning/kautham_planner_parameters.hpp"
#include "lang2manip/planning/motion_planner.hpp"
#include "lang2manip/planning/planner_registry.hpp"

namespace lang2manip {
namespace {

// Kautham's common parameters as a key: lowercase, no leading underscore, no "(0/1)" suffix.
std::string commonKey(std::string name) {
  const auto suffix = name.find(" (");
  if (suffix != std::string::npos) name.erase(suffix);
  while (!name.empty() && name.front() == '_') name.erase(name.begin());
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name;
}

// Kautham's planner parameter names that do not follow "Goal Bias" -> "goal_bias".
const std::map<std::string, std::string>& kauthamParameterAliases() {
  static const std::map<std::string, std::string> aliases = {
      {"MaxNearestNeighbors", "max_nearest_neighbors"},
      {"Thread Count", "thread_count"},
      {"Delay CC", "delay_collision_checking"},
  };
  return aliases;
}

std::string omplStyleName(const std::string& name) {
  const auto alias = kauthamParameterAliases().find(name);
  if (alias != kauthamParameterAliases().end()) return alias->second;
  std::string result;
  for (const char c : name) {
    result += c == ' ' ? '_' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return result;
}

const std::vector<std::string>& commonParameterNames() {
  static const std::vector<std::string> names = {
      "_Max Planning Time", "_Simplify Solution", "_Optimize (0/1)", "_Incremental (0/1)",
      "_Speed Factor",      "_Cspace Drawn",      "_Path Drawn (0/1)", "_Valid State Sampler"};
  return names;
}


struct OmplParameterInfo {
  bool known = false;
  std::string rangeSuggestion;
};

// Sets the parameter on a throwaway planner to learn whether OMPL accepts the value.
OmplParameterInfo trySetOnPlanner(const std::string& planner, const std::string& name,
                                  const std::string& value, bool& accepted) {
  routeOmplMessagesToLog();
  auto space = std::make_shared<ompl::base::RealVectorStateSpace>(2);
  space->setBounds(0.0, 1.0);
  auto si = std::make_shared<ompl::base::SpaceInformation>(space);
  auto instance = createOmplPlanner(planner, si);
  OmplParameterInfo info;
  if (!instance->params().hasParam(name)) return info;
  info.known = true;
  info.rangeSuggestion = instance->params()[name].getRangeSuggestion();
  try {
    accepted = instance->params().setParam(name, value);
  } catch (const std::exception&) {  // OMPL throws for text that is not a number
    accepted = false;
  }
  return info;
}

// OMPL publishes ranges as "min:step:max" or "0,1" (a flag).
void checkAgainstRange(const std::string& name, const std::string& value, const std::string& range) {
  const std::string what = "parameter \"" + name + "\"";
  if (range == "0,1") {
    if (value != "0" && value != "1" && value != "true" && value != "false") {
      throw InputError(what + " is a flag (0 or 1), got \"" + value + "\"");
    }
    return;
  }
  const auto first = range.find(':');
  const auto last = range.rfind(':');
  if (first == std::string::npos || first == last) return;
  const double number = parseFiniteNumber(value, what, {});
  const double low = parseFiniteNumber(range.substr(0, first), what + " range", {});
  const double high = parseFiniteNumber(range.substr(last + 1), what + " range", {});
  if (number < low || number > high) {
    throw InputError(what + " = " + value + " is outside its range [" + range.substr(0, first) +
                     ", " + range.substr(last + 1) + "]");
  }
}

constexpr ValidStateSampler kValidStateSamplers[] = {ValidStateSampler::kUniform, ValidStateSampler::kGaussian,
                                                     ValidStateSampler::kObstacleBased, ValidStateSampler::kBridgeTest};

ValidStateSampler parseValidStateSampler(const std::string& value, const std::string& what) {
  std::string names;
  for (const ValidStateSampler sampler : kValidStateSamplers) {
    if (value == validStateSamplerName(sampler)) return sampler;
    names += (names.empty() ? "" : ", ") + validStateSamplerName(sampler);
  }
  throw InputError(what + " must be one of " + names + ", got \"" + value + "\"");
}

}  // namespace

std::string validStateSamplerName(ValidStateSampler sampler) {
  switch (sampler) {
    case ValidStateSampler::kUniform: return "uniform";
    case ValidStateSampler::kGaussian: return "gaussian";
    case ValidStateSampler::kObstacleBased: return "obstacle_based";
    case ValidStateSampler::kBridgeTest: return "bridge_test";
  }
  return "unknown";
}

PlannerSettings::PlannerSettings() : planner_("RRTConnect") {}

void PlannerSettings::setPlanner(const std::string& name) {
  planner_ = canonicalPlannerName(name);
  omplParameters_.clear();
  ignored_.clear();
}

std::vector<std::string> PlannerSettings::parameterNames() const {
  std::vector<std::string> names = commonParameterNames();
  for (const std::string& name : omplParameterNames(planner_)) names.push_back(name);
  return names;
}

void PlannerSettings::setParameter(const std::string& name, const std::string& value) {
  const std::string key = commonKey(name);
  const std::string text(trimmed(value));
  if (setCommonParameter(key, name, text)) return;
  if (const auto meaning = kauthamPlannerParameter(planner_, name, text)) {
    parseFiniteNumber(text, "parameter \"" + name + "\" of " + planner_, {});  // Kautham's values are numbers
    if (!meaning->validStateSampler.empty()) {
      validStateSampler_ = parseValidStateSampler(meaning->validStateSampler, name);
      return;
    }
    if (!meaning->omplName.empty()) {
      setOmplParameter(meaning->omplName, text);
      return;
    }
    ignored_.erase(std::remove_if(ignored_.begin(), ignored_.end(),
                                  [&](const IgnoredParameter& old) { return old.name == name; }),
                   ignored_.end());
    if (!meaning->noEffect.empty()) ignored_.push_back({name, text, meaning->noEffect});
    return;
  }
  setOmplParameter(name, text);
}

bool PlannerSettings::setCommonParameter(const std::string& key, const std::string& name,
                                         const std::string& value) {
  const std::string what = "parameter \"" + name + "\"";
  if (key == "max planning time") {
    const double seconds = parseFiniteNumber(value, what, {});
    if (seconds <= 0.0) throw InputError(what + " must be a positive number of seconds, got " + value);
    maxPlanningTime_ = seconds;
  } else if (key == "simplify solution") {
    if (value != "0" && value != "1" && value != "2") {
      throw InputError(what + " must be 0 (none), 1 (smooth) or 2 (shortcut and smooth), got \"" +
                       value + "\"");
    }
    simplifyLevel_ = static_cast<SimplifyLevel>(value[0] - '0');
  } else if (key == "optimize") {
    optimize_ = parseFlag(value, what, {});
  } else if (key == "incremental") {
    incremental_ = parseFlag(value, what, {});
  } else if (key == "speed factor") {
    speedFactor_ = parseFiniteNumber(value, what, {});
    if (speedFactor_ <= 0.0) throw InputError(what + " must be positive, got " + value);
  } else if (key == "valid state sampler") {
    validStateSampler_ = parseValidStateSampler(value, what);
  } else if (key == "cspace drawn" || key == "path drawn") {
    parseFlag(value, what, {});
  } else {
    return false;
  }
  return true;
}

void PlannerSettings::setOmplParameter(const std::string& name, const std::string& value) {
  const std::string undecorated = name.substr(std::min(name.size(), name.find_first_not_of('_')));
  for (const std::string& candidate : {name, omplStyleName(name), omplStyleName(undecorated)}) {
    bool accepted = false;
    const OmplParameterInfo info = trySetOnPlanner(planner_, candidate, value, accepted);
    if (!info.known) continue;
    if (!accepted) {
      throw InputError("parameter \"" + name + "\" of " + planner_ + ": invalid value \"" + value +
                       "\" (range " + info.rangeSuggestion + ")");
    }
    checkAgainstRange(name, value, info.rangeSuggestion);
    omplParameters_.emplace_back(candidate, value);
    return;
  }
  throw InputError("unknown parameter \"" + name + "\" for planner " + planner_ +
                   "; valid parameters: " + joinedNames(parameterNames()));
}

}  // namespace lang2manip
