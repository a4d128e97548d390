#include "lang2manip/language/planner_names.hpp"

#include <cctype>
#include <utility>

#include "lang2manip/planning/planner_catalog.hpp"

namespace lang2manip {
namespace {

// Spoken forms of registered planners, besides their registry names and aliases.
const std::vector<std::pair<const char*, std::vector<const char*>>>& spokenForms() {
  static const std::vector<std::pair<const char*, std::vector<const char*>>> forms{
      {"RRTConnect", {"rrt connect", "bidirectional rrt", "bi rrt"}},
      {"RRTstar", {"rrt star", "optimal rrt"}},
      {"InformedRRTstar", {"informed rrt star"}},
      {"RRTsharp", {"rrt sharp"}},
      {"RRTXstatic", {"rrt x"}},
      {"LazyRRT", {"lazy rrt"}},
      {"pRRT", {"parallel rrt"}},
      {"TRRT", {"t rrt", "transition rrt"}},
      {"BiTRRT", {"bi trrt", "bidirectional trrt", "trrt connect"}},
      {"LBTRRT", {"lbt rrt"}},
      {"SORRTstar", {"sorrt star"}},
      {"PRM", {"probabilistic roadmap"}},
      {"PRMstar", {"prm star"}},
      {"LazyPRM", {"lazy prm"}},
      {"LazyPRMstar", {"lazy prm star"}},
      {"SPARStwo", {"spars two"}},
      {"BiEST", {"bi est", "bidirectional est"}},
      {"ProjEST", {"proj est", "projection est"}},
      {"pSBL", {"parallel sbl"}},
      {"BKPIECE1", {"bi kpiece"}},
      {"LBKPIECE1", {"lazy bkpiece"}},
      {"FMT", {"fmt star"}},
      {"BFMT", {"bfmt star"}},
      {"BITstar", {"bit star"}},
      {"ABITstar", {"abit star"}},
      {"AITstar", {"ait star"}},
      {"RRTConnect", {"default planner"}},
  };
  return forms;
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
    for (const PlannerDescription& planner : plannerDescriptions()) {
      result.push_back({tokenize(lowerCase(planner.name)), planner.name});
      for (const std::string& alias : planner.aliases) result.push_back({tokenize(lowerCase(alias)), planner.name});
    }
    for (const auto& [name, forms] : spokenForms()) {
      for (const char* form : forms) result.push_back({tokenize(form), name});
    }
    return result;
  }();
  return phrases;
}

}  // namespace

std::optional<std::string> plannerNameFromWords(const std::string& name) {
  const Words words = tokenize(name);
  const std::optional<PlannerMatch> match = matchPlannerName(words, 0);
  if (!match || match->length != words.size()) return std::nullopt;
  return match->name;
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
