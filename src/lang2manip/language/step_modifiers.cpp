#include <algorithm>
#include <utility>

#include "lang2manip/language/clause_parser.hpp"
#include "lang2manip/language/planner_names.hpp"
#include "lang2manip/planning/planner_catalog.hpp"

namespace lang2manip::language_detail {
namespace {

struct PhraseList {
  std::vector<Words> phrases;

  PhraseList(std::initializer_list<const char*> list) {
    for (const char* phrase : list) phrases.push_back(tokenize(phrase));
  }

  /// Length of the longest phrase ending just before words[end].
  [[nodiscard]] std::size_t longestEndingAt(const Words& words, std::size_t end) const {
    std::size_t best = 0;
    for (const Words& phrase : phrases) {
      if (phrase.size() <= end && phrase.size() > best && matchesAt(words, end - phrase.size(), phrase)) {
        best = phrase.size();
      }
    }
    return best;
  }

  /// Length of the longest phrase starting at words[at].
  [[nodiscard]] std::size_t longestAt(const Words& words, std::size_t at) const { return longestPhraseAt(words, at, phrases); }
};

const std::vector<std::pair<Words, GraspDirection>>& graspPhrases() {
  static const std::vector<std::pair<Words, GraspDirection>> phrases = [] {
    std::vector<std::pair<Words, GraspDirection>> list;
    auto add = [&list](GraspDirection direction, std::initializer_list<const char*> texts) {
      for (const char* text : texts) list.emplace_back(tokenize(text), direction);
    };
    add(GraspDirection::kTop, {"top grasp", "top down grasp", "top grip", "overhead grasp",
                               "vertical grasp", "from the top", "from top", "from above",
                               "from overhead", "top down", "from the top down", "top-down grip"});
    add(GraspDirection::kSide, {"side grasp", "side grip", "lateral grasp", "horizontal grasp",
                                "from the side", "from side", "from the sides", "sideways grasp",
                                "from one side"});
    add(GraspDirection::kFront, {"front grasp", "front grip", "frontal grasp", "from the front",
                                 "from front"});
    return list;
  }();
  return phrases;
}

const PhraseList& graspLeadIns() {
  static const PhraseList list{
      "with a", "with an", "with the", "using a", "using the", "use a", "with", "using",
      "grasping it", "grasping them", "grasp it", "grab it", "grabbing it", "holding it",
      "by grasping it", "picking it up", "pick it up", "grasped", "grasping", "and grasp it",
      "and grab it", "by grasping", "grabbing them", "grasp them", "grab them", "and use a"};
  return list;
}

const PhraseList& plannerLeadIns() {
  static const PhraseList list{
      "using the", "using", "with the", "with", "via", "via the", "use", "use the",
      "plan with", "plan with the", "planning with", "planned with", "and use", "and use the",
      "by", "through", "using planner", "with planner", "with the planner", "using the planner",
      "plan the motions with", "plan the motion with", "plan all motions with"};
  return list;
}

const PhraseList& plannerTrailers() {
  static const PhraseList list{"planner", "algorithm", "motion planner", "for planning",
                               "for motion planning", "planner for the motion"};
  return list;
}

const PhraseList& forAllTrailers() {
  static const PhraseList list{"for everything", "for all motions", "for all moves",
                               "for every motion", "for all the motions", "for all actions",
                               "for every action", "for all of it", "throughout"};
  return list;
}

void erase(Words& words, std::size_t begin, std::size_t end) {
  words.erase(words.begin() + static_cast<std::ptrdiff_t>(begin),
              words.begin() + static_cast<std::ptrdiff_t>(end));
}

/// True when "from ..." at words[at] says where an ordinal just before counts from ("the second
/// block from the top"), not how to grasp.
bool countsAnOrdinal(const Words& words, std::size_t at) {
  static const Words ordinals{"first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth", "ninth", "tenth", "last"};
  if (words[at] != "from") return false;
  for (std::size_t back = 1; back <= 3 && back <= at; ++back) {
    if (containsWord(ordinals, words[at - back])) return true;
  }
  return false;
}

std::optional<GraspDirection> extractGrasp(Words& words) {
  for (std::size_t at = 0; at < words.size(); ++at) {
    if (countsAnOrdinal(words, at)) continue;
    for (const auto& [phrase, direction] : graspPhrases()) {
      if (!matchesAt(words, at, phrase)) continue;
      std::size_t end = at + phrase.size();
      if (end < words.size() && words[end] == "grasp") ++end;  // "top-down grasp"
      const std::size_t begin = at - graspLeadIns().longestEndingAt(words, at);
      erase(words, begin, end);
      return direction;
    }
  }
  return std::nullopt;
}

std::string knownPlannerList() {
  std::string text;
  for (const std::string& name : plannerNames()) {
    if (!text.empty()) text += ", ";
    text += name;
  }
  return text;
}

void rejectUnknownPlanner(const Words& words) {
  for (std::size_t at = 0; at < words.size(); ++at) {
    if (words[at] != "planner" && words[at] != "algorithm") continue;
    std::size_t begin = at;
    while (begin > 0 && words[begin - 1] != "using" && words[begin - 1] != "with" &&
           words[begin - 1] != "use" && at - begin < 4) {
      --begin;
    }
    std::size_t nameBegin = begin;
    if (nameBegin < at && words[nameBegin] == "the") ++nameBegin;
    const std::string name = joinWords(words, nameBegin, at);
    throwGroundingError(joinWords(words, begin > 0 ? begin - 1 : begin, at + 1),
                        "unknown motion planner \"" + name + "\" (known: " + knownPlannerList() +
                            ")");
  }
}

}  // namespace

StepModifiers extractModifiers(Words& words) {
  StepModifiers modifiers;
  modifiers.grasp = extractGrasp(words);
  for (std::size_t at = 0; at < words.size(); ++at) {
    const std::optional<PlannerMatch> match = matchPlannerName(words, at);
    if (!match) continue;
    const std::size_t leadIn = plannerLeadIns().longestEndingAt(words, at);
    std::size_t end = at + match->length;
    end += plannerTrailers().longestAt(words, end);
    if (const std::size_t forAll = forAllTrailers().longestAt(words, end)) {
      modifiers.plannerForAll = true;
      end += forAll;
    }
    modifiers.planner = match->name;
    erase(words, at - leadIn, end);
    break;
  }
  rejectUnknownPlanner(words);
  return modifiers;
}

}  // namespace lang2manip::language_detail
