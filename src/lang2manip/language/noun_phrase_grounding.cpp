#include <algorithm>
#include <numeric>

#include "lang2manip/language/noun_phrase.hpp"

namespace lang2manip::language_detail {
namespace {


bool hasColours(const ObjectDescriptor& object, const std::vector<std::string>& colours) {
  return std::all_of(colours.begin(), colours.end(), [&object](const std::string& colour) {
    return containsWord(object.colours, colour);
  });
}

/// The score a size or place word ranks objects by (higher = more so).
double score(const ObjectDescriptor& object, SizeWord size, PlaceWord place) {
  if (size == SizeWord::kBig) return object.volume;
  if (size == SizeWord::kSmall) return -object.volume;
  switch (place) {
    case PlaceWord::kLeft: return object.position.y();
    case PlaceWord::kRight: return -object.position.y();
    case PlaceWord::kNear: return -object.position.head<2>().norm();
    case PlaceWord::kFar: return object.position.head<2>().norm();
    case PlaceWord::kNone: break;
  }
  return 0.0;
}

}  // namespace

std::vector<std::string> NounPhraseReader::ground(const NounPhrase& phrase,
                                                  const Discourse& discourse, bool asTarget,
                                                  const std::vector<std::string>& actedOn,
                                                  bool preferContainer) const {
  if (phrase.pronoun != Pronoun::kNone) {
    return groundPronoun(phrase, discourse, asTarget, actedOn, preferContainer);
  }
  if (phrase.unknownNoun) {
    throwGroundingError(phrase.text, "no object matches (objects: " + objectList() + ")");
  }
  const std::vector<std::string> byNoun = candidates(phrase, discourse, asTarget);
  std::vector<std::string> names = narrow(phrase, byNoun);
  if (byNoun.empty() && phrase.other) {
    throwGroundingError(phrase.text, "there is no other one: already mentioned " +
                                         joinAlternatives(discourse.mentioned));
  }
  if (names.empty()) {
    std::string why = "no object matches (objects: " + objectList() + ")";
    if (!byNoun.empty() && byNoun.size() < objects_.size()) {
      why = "no object matches; by its noun it could only be " + describe(byNoun);
    }
    throwGroundingError(phrase.text, why);
  }
  if (phrase.everything || phrase.quantity == Quantity::kAll) return names;
  if (phrase.quantity == Quantity::kExactly) {
    if (static_cast<int>(names.size()) != phrase.count) {
      throwGroundingError(phrase.text, std::to_string(phrase.count) + " objects were meant but " +
                                           std::to_string(names.size()) + " match: " +
                                           describe(names));
    }
    return names;
  }
  if (phrase.isPlural()) return names;
  if (phrase.quantity == Quantity::kIndefinite) {
    for (const std::string& name : names) {
      if (!containsWord(discourse.mentioned, name)) return {name};
    }
    return {names.front()};
  }
  if (names.size() > 1) {
    throwGroundingError(phrase.text, "it is ambiguous: it could be " + joinAlternatives(names) +
                                         "; say which (by name, colour, size or place)");
  }
  return names;
}

std::vector<std::string> NounPhraseReader::groundPronoun(
    const NounPhrase& phrase, const Discourse& discourse, bool asTarget,
    const std::vector<std::string>& actedOn, bool preferContainer) const {
  if (phrase.pronoun == Pronoun::kThem) {
    if (discourse.lastObjects.empty()) {
      throwGroundingError(phrase.text, "nothing was mentioned before that it could refer to");
    }
    if (phrase.quantity == Quantity::kExactly &&
        static_cast<int>(discourse.lastObjects.size()) != phrase.count) {
      throwGroundingError(phrase.text, "it refers to " + joinAlternatives(discourse.lastObjects) +
                                           ", not " + std::to_string(phrase.count) + " objects");
    }
    return discourse.lastObjects;
  }
  // "it": the object acted on last, else the latest target; as the target of "in", a container.
  std::vector<std::string> previous;
  for (const std::string& object : discourse.lastObjects) {
    if (!asTarget || !containsWord(actedOn, object)) previous.push_back(object);
  }
  if (asTarget && !discourse.lastTarget.empty() && !containsWord(actedOn, discourse.lastTarget) &&
      !containsWord(previous, discourse.lastTarget)) {
    if (previous.empty()) previous.push_back(discourse.lastTarget);
    else if (preferContainer) previous.push_back(discourse.lastTarget);
  }
  if (preferContainer) {
    std::vector<std::string> containers;
    for (const std::string& object : previous) {
      if (descriptor(object).role == ObjectRole::kContainer) containers.push_back(object);
    }
    if (!containers.empty()) previous = containers;
  }
  if (previous.empty()) {
    throwGroundingError(phrase.text, "nothing was mentioned before that it could refer to");
  }
  if (previous.size() > 1) {
    throwGroundingError(phrase.text, "it could refer to " + joinAlternatives(previous) + "; say which");
  }
  return previous;
}

std::vector<std::string> NounPhraseReader::candidates(const NounPhrase& phrase,
                                                      const Discourse& discourse,
                                                      bool asTarget) const {
  std::vector<std::string> names;
  if (phrase.noun) {
    names = phrase.noun->objects;
  } else if (phrase.one && !(discourse.lastObjectNoun.empty() && discourse.lastTargetNoun.empty())) {
    const bool targetNoun = asTarget ? !discourse.lastTargetNoun.empty()
                                     : discourse.lastObjectNoun.empty();
    names = targetNoun ? discourse.lastTargetNoun : discourse.lastObjectNoun;
  } else {
    for (const ObjectDescriptor& object : objects_) names.push_back(object.name);
    if (phrase.everything || !asTarget) {
      std::erase_if(names, [this](const std::string& name) { return !descriptor(name).movable; });
    }
  }
  if (phrase.other) {
    std::erase_if(names, [&discourse](const std::string& name) {
      return containsWord(discourse.mentioned, name);
    });
  }
  return names;
}

std::vector<std::string> NounPhraseReader::narrow(const NounPhrase& phrase,
                                                  std::vector<std::string> names) const {
  std::erase_if(names, [this, &phrase](const std::string& name) {
    return !hasColours(descriptor(name), phrase.colours);
  });
  if ((phrase.size == SizeWord::kNone && phrase.place == PlaceWord::kNone) || names.size() < 2) {
    return names;
  }
  std::vector<double> scores;
  for (const std::string& name : names) {
    scores.push_back(score(descriptor(name), phrase.size, phrase.place));
  }
  if (phrase.isPlural()) {
    const double mean = std::accumulate(scores.begin(), scores.end(), 0.0) /
                        static_cast<double>(scores.size());
    std::vector<std::string> kept;
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (scores[i] > mean) kept.push_back(names[i]);
    }
    return kept;
  }
  const double best = *std::max_element(scores.begin(), scores.end());
  constexpr double kTie = 1e-9;
  std::vector<std::string> kept;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (scores[i] >= best - kTie * std::max(1.0, std::abs(best))) kept.push_back(names[i]);
  }
  return kept;
}

}  // namespace lang2manip::language_detail
