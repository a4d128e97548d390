#include "lang2manip/language/planner_names.hpp"

#include <cctype>
#include <utility>

namespace lang2manip {
namespace {

struct PlannerEntry {
  const char* name;
  /// Spoken forms and Kautham names besides the name itself and "ompl" + name.
  std::vector<const char*> aliases;
};

const std::vector<PlannerEntry>& plannerTable() {
  static const std::vector<PlannerEntry> table{
      {"RRTConnect", {"rrt connect", "rrt-connect", "bidirectional rrt", "bi rrt"}},
      {"RRT", {}},
      {"RRTstar", {"rrt*", "rrt star", "omplrrtstar", "optimal rrt"}},
      {"InformedRRTstar", {"informed rrt*", "informed rrt star"}},
      {"RRTsharp", {"rrt#", "rrt sharp"}},
      {"RRTXstatic", {"rrtx", "rrt x"}},
      {"LazyRRT", {"lazy rrt"}},
      {"pRRT", {"parallel rrt"}},
      {"TRRT", {"t rrt", "transition rrt"}},
      {"BiTRRT", {"bi trrt", "bidirectional trrt"}},
      {"LBTRRT", {"lbt rrt"}},
      {"SORRTstar", {"sorrt*", "sorrt star"}},
      {"PRM", {"probabilistic roadmap"}},
      {"PRMstar", {"prm*", "prm star"}},
      {"LazyPRM", {"lazy prm"}},
      {"LazyPRMstar", {"lazy prm*", "lazy prm star"}},
      {"SPARS", {}},
      {"SPARStwo", {"spars2", "spars two"}},
      {"EST", {}},
      {"BiEST", {"bi est", "bidirectional est"}},
      {"ProjEST", {"proj est", "projection est"}},
      {"SBL", {}},
      {"pSBL", {"parallel sbl"}},
      {"KPIECE1", {"kpiece", "omplkpiece"}},
      {"BKPIECE1", {"bkpiece", "bi kpiece"}},
      {"LBKPIECE1", {"lbkpiece", "lazy bkpiece"}},
      {"STRIDE", {}},
      {"PDST", {}},
      {"FMT", {"fmt*", "fmt star"}},
      {"BFMT", {"bfmt*", "bfmt star"}},
      {"BITstar", {"bit*", "bit star"}},
      {"ABITstar", {"abit*", "abit star"}},
      {"AITstar", {"ait*", "ait star"}},
      {"EITstar", {"eit*", "eit star"}},
      {"CForest", {"c forest"}},
      {"AnytimePathShortening", {"anytime path shortening"}},
      {"omplTRRTConnect", {"trrt connect"}},
      {"omplLazyTRRT", {"lazy trrt"}},
      {"omplTSRRT", {"tsrrt"}},
      {"omplRRTStarPMD", {"rrt* pmd", "rrt star pmd"}},
      {"omplRRTConnectEUROC", {"rrt connect euroc"}},
      {"omplDefault", {"default planner"}},
  };
  return table;
}

struct PlannerPhrase {
  Words words;
  std::string name;
};

std::string lowerCase(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

const std::vector<PlannerPhrase>& plannerPhrases() {
  static const std::vector<PlannerPhrase> phrases = [] {
    std::vector<PlannerPhrase> result;
    for (const PlannerEntry& entry : plannerTable()) {
      const std::string name = entry.name;
      const std::string lower = lowerCase(name);
      result.push_back({tokenize(lower), name});
      if (lower.rfind("ompl", 0) != 0) result.push_back({tokenize("ompl" + lower), name});
      for (const char* alias : entry.aliases) result.push_back({tokenize(alias), name});
    }
    return result;
  }();
  return phrases;
}

}  // namespace

std::optional<std::string> canonicalPlannerName(const std::string& name) {
  const Words words = tokenize(name);
  const std::optional<PlannerMatch> match = matchPlannerName(words, 0);
  if (!match || match->length != words.size()) return std::nullopt;
  return match->name;
}

std::vector<std::string> knownPlannerNames() {
  std::vector<std::string> names;
  for (const PlannerEntry& entry : plannerTable()) names.emplace_back(entry.name);
  return names;
}

std::optional<PlannerMatch> matchPlannerName(const Words& words, std::size_t at) {
  std::optional<PlannerMatch> best;
  for (const PlannerPhrase& phrase : plannerPhrases()) {
    if (matchesAt(words, at, phrase.words) && (!best || phrase.words.size() > best->length)) {
      best = PlannerMatch{phrase.name, phrase.words.size()};
    }
  }
  return best;
}

}  // namespace lang2manip
