#include <algorithm>
#include <cmath>
#include <numeric>

#include "lang2manip/language/noun_phrase.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"

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
  if (size == SizeWord::kTall) return object.bounds.sizes().z();
  if (size == SizeWord::kShort) return -object.bounds.sizes().z();
  if (size == SizeWord::kLong) return object.dimensions.maxCoeff();
  switch (place) {
    case PlaceWord::kLeft: return object.position.y();
    case PlaceWord::kRight: return -object.position.y();
    case PlaceWord::kNear: return -object.position.head<2>().norm();
    case PlaceWord::kFar: return object.position.head<2>().norm();
    case PlaceWord::kNone: break;
  }
  return 0.0;
}

/// True when `a` stands in `relation` to `b`, by the conventions of the symbolic state (in and on:
/// its centre over `b`, resting on `b`'s top or inside its box).
bool standsIn(const ObjectDescriptor& a, SpatialRelation relation, const ObjectDescriptor& b) {
  const SpatialOptions conventions;
  if (relation == SpatialRelation::kNextTo) return boxGap(a.bounds, b.bounds) <= conventions.nearDistance;
  const bool above = a.position.x() >= b.bounds.min().x() && a.position.x() <= b.bounds.max().x() &&
                     a.position.y() >= b.bounds.min().y() && a.position.y() <= b.bounds.max().y();
  if (relation == SpatialRelation::kOn) return above && std::abs(a.bounds.min().z() - b.bounds.max().z()) <= conventions.distanceTolerance;
  if (relation == SpatialRelation::kIn) return above && a.bounds.min().z() >= b.bounds.min().z() - conventions.distanceTolerance &&
                                               a.bounds.min().z() < b.bounds.max().z();
  const std::vector<SpatialRelation> relations = directionalRelations(a.position - b.position, conventions.directionMargin);
  return std::find(relations.begin(), relations.end(), relation) != relations.end();
}

}  // namespace

std::vector<std::string> NounPhraseReader::applyModifier(const NounPhrase& phrase, std::vector<std::string> names,
                                                         const Discourse& discourse) const {
  const NounModifier& modifier = *phrase.modifier;
  if (modifier.kind == NounModifier::Kind::kBetween) return between(phrase, std::move(names), discourse);
  if (modifier.kind == NounModifier::Kind::kSameAs) return sameAs(phrase, std::move(names), discourse);
  ObjectDescriptor robot;
  robot.name = "the robot";
  robot.bounds.extend(Vector3::Zero());
  const ObjectDescriptor* referred = &robot;
  if (!modifier.reference.empty()) {
    const NounPhrase& referencePhrase = modifier.reference.front();
    const std::vector<std::string> references = ground(referencePhrase, discourse, true, {});
    if (references.size() != 1) {
      throwGroundingError(referencePhrase.text, "names " + std::to_string(references.size()) + " objects; a place is relative to one");
    }
    referred = &descriptor(references.front());
  }
  const ObjectDescriptor& reference = *referred;
  std::erase(names, reference.name);
  if (modifier.kind == NounModifier::Kind::kRelation) {
    std::erase_if(names, [&](const std::string& name) { return !standsIn(descriptor(name), modifier.relation, reference); });
    if (names.empty()) {
      throwGroundingError(phrase.text, "no object is " + spatialRelationWords(modifier.relation) + " " + reference.name);
    }
    return names;
  }
  const double sign = modifier.kind == NounModifier::Kind::kNearestTo ? 1.0 : -1.0;
  auto gap = [&](const std::string& name) { return sign * boxGap(descriptor(name).bounds, reference.bounds); };
  std::stable_sort(names.begin(), names.end(), [&](const std::string& a, const std::string& b) { return gap(a) < gap(b); });
  std::size_t kept = phrase.quantity == Quantity::kExactly ? static_cast<std::size_t>(phrase.count) : 1;
  if (phrase.isPlural() && phrase.quantity != Quantity::kExactly) kept = (names.size() + 1) / 2;
  if (names.size() > kept && std::abs(gap(names[kept - 1]) - gap(names[kept])) < 1e-6) {
    throwGroundingError(phrase.text, "it is ambiguous: " + names[kept - 1] + " and " + names[kept] + " are as far from " +
                                         reference.name + "; say which");
  }
  names.resize(std::min(kept, names.size()));
  return names;
}

std::vector<std::string> NounPhraseReader::between(const NounPhrase& phrase, std::vector<std::string> names, const Discourse& discourse) const {
  std::vector<Eigen::Vector2d> ends;
  for (const NounPhrase& end : phrase.modifier->reference) {
    const std::vector<std::string> named = ground(end, discourse, true, {});
    if (named.size() != 1) throwGroundingError(end.text, "names " + std::to_string(named.size()) + " objects; \"between\" needs one at each end");
    std::erase(names, named.front());
    ends.push_back(descriptor(named.front()).position.head<2>());
  }
  const Eigen::Vector2d along = ends[1] - ends[0];
  if (along.norm() < 1e-3) throwGroundingError(phrase.text, "its two ends stand at the same place");
  // Between: over the middle 90 % of the segment joining the ends' centres, within kBetweenWidth of it.
  std::vector<std::pair<double, std::string>> offSegment;
  for (const std::string& name : names) {
    const Eigen::Vector2d p = descriptor(name).position.head<2>();
    const double t = (p - ends[0]).dot(along) / along.squaredNorm();
    const double off = (p - (ends[0] + t * along)).norm();
    if (t > 0.05 && t < 0.95 && off <= kBetweenWidth) offSegment.emplace_back(off, name);
  }
  std::stable_sort(offSegment.begin(), offSegment.end());
  if (offSegment.empty()) throwGroundingError(phrase.text, "nothing of that kind stands between them");
  if (phrase.isPlural()) {
    names.clear();
    for (const auto& [off, name] : offSegment) names.push_back(name);
    return names;
  }
  if (offSegment.size() > 1 && offSegment[1].first - offSegment[0].first < kClearlyCloser) {
    throwGroundingError(phrase.text, "it is ambiguous: " + offSegment[0].second + " and " + offSegment[1].second + " both stand between them; say which");
  }
  return {offSegment.front().second};
}

std::vector<std::string> NounPhraseReader::sameAs(const NounPhrase& phrase, std::vector<std::string> names, const Discourse& discourse) const {
  const NounModifier& modifier = *phrase.modifier;
  const std::vector<std::string> named = ground(modifier.reference.front(), discourse, true, {});
  if (named.size() != 1) throwGroundingError(modifier.reference.front().text, "names " + std::to_string(named.size()) + " objects; \"the same as\" compares with one");
  const ObjectDescriptor& reference = descriptor(named.front());
  std::erase(names, reference.name);
  std::erase_if(names, [&](const std::string& name) {
    const ObjectDescriptor& object = descriptor(name);
    if (modifier.property == "colour") return object.colours.empty() || reference.colours.empty() || object.colours.front() != reference.colours.front();
    if (modifier.property == "shape") return object.shape != reference.shape;
    if (modifier.property == "size") return object.sizeClass != reference.sizeClass;
    return object.category != reference.category;
  });
  if (names.empty()) throwGroundingError(phrase.text, "nothing else has the same " + modifier.property + " as " + reference.name);
  return names;
}

std::vector<std::string> NounPhraseReader::ground(const NounPhrase& phrase,
                                                  const Discourse& discourse, bool asTarget,
                                                  const std::vector<std::string>& actedOn,
                                                  bool preferContainer,
                                                  const std::vector<std::string>& excluded) const {
  if (phrase.pronoun != Pronoun::kNone) {
    return groundPronoun(phrase, discourse, asTarget, actedOn, preferContainer);
  }
  if (phrase.unknownNoun) {
    throwGroundingError(phrase.text, "no object matches (objects: " + objectList() + ")");
  }
  std::vector<std::string> byNoun = candidates(phrase, discourse, asTarget);
  std::vector<std::string> exceptions;
  for (const NounPhrase& exception : phrase.except) {
    for (const std::string& name : ground(exception, discourse, false, {})) exceptions.push_back(name);
  }
  std::erase_if(byNoun, [&](const std::string& name) {
    return containsWord(excluded, name) || containsWord(exceptions, name) || (phrase.movableOnly && !descriptor(name).movable);
  });
  const bool relative = phrase.modifier && (phrase.modifier->kind == NounModifier::Kind::kRelation || phrase.modifier->kind == NounModifier::Kind::kSameAs);
  std::vector<std::string> names = narrow(phrase, relative ? applyModifier(phrase, byNoun, discourse) : byNoun);
  if (phrase.modifier && !relative && !names.empty()) names = applyModifier(phrase, names, discourse);
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
  // "it": as a target, what the step's objects were named by ("all objects the colour of the
  // bowl into it"); else the object acted on last, else the latest target; as the target of
  // "in", a container.
  if (asTarget) {
    std::vector<std::string> referred;
    for (const std::string& object : discourse.stepReferences) {
      if (!containsWord(actedOn, object)) referred.push_back(object);
    }
    if (referred.size() == 1) return referred;
  }
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
  bool namedOne = false;  // "one" stands for a noun that named a single object ("the marker")
  if (phrase.noun) {
    names = phrase.noun->objects;
  } else if (phrase.one && !(discourse.lastObjectNoun.empty() && discourse.lastTargetNoun.empty())) {
    const bool targetNoun = asTarget ? !discourse.lastTargetNoun.empty()
                                     : discourse.lastObjectNoun.empty();
    names = targetNoun ? discourse.lastTargetNoun : discourse.lastObjectNoun;
    namedOne = names.size() == 1;
  } else {
    for (const ObjectDescriptor& object : objects_) names.push_back(object.name);
    if (phrase.everything || !asTarget) {
      std::erase_if(names, [this](const std::string& name) { return !descriptor(name).movable; });
    }
  }
  if (phrase.same) {  // the one named before: as a target, the latest target; else the latest mentioned
    if (asTarget && containsWord(names, discourse.lastTarget)) return {discourse.lastTarget};
    for (auto it = discourse.mentioned.rbegin(); it != discourse.mentioned.rend(); ++it) {
      if (containsWord(names, *it)) return {*it};
    }
    throwGroundingError(phrase.text, "nothing of that kind was named before");
  }
  if (phrase.other) {
    const auto mentioned = [&discourse](const std::string& name) { return containsWord(discourse.mentioned, name); };
    std::erase_if(names, mentioned);
    if (names.empty() && phrase.one && namedOne) {  // "the marker ..., then the other one": another movable object
      for (const ObjectDescriptor& object : objects_) {
        if (object.movable && !mentioned(object.name)) names.push_back(object.name);
      }
    }
  }
  return names;
}

std::vector<std::string> NounPhraseReader::ranked(const NounPhrase& phrase, std::vector<std::string> names) const {
  const auto along = [&](const std::string& name) {
    const Vector3& p = descriptor(name).position;
    switch (phrase.rankFrom) {
      case RankFrom::kLeft: return p.y();
      case RankFrom::kRight: return -p.y();
      case RankFrom::kTop: return p.x();
      case RankFrom::kBottom: return -p.x();
    }
    return 0.0;
  };
  if (!phrase.rankFromGiven && phrase.rank != kMiddleRank) {
    throwGroundingError(phrase.text, "counted from where? say \"from the left\" (right, top or bottom)");
  }
  std::stable_sort(names.begin(), names.end(), [&](const std::string& a, const std::string& b) { return along(a) > along(b); });
  const auto count = static_cast<int>(names.size());
  if (phrase.rank == kMiddleRank) {
    if (count % 2 == 0) throwGroundingError(phrase.text, "there is no middle one of " + std::to_string(count) + ": " + describe(names));
    return {names[static_cast<std::size_t>(count / 2)]};
  }
  const int index = phrase.rank == kLastRank ? count - 1 : phrase.rank - 1;
  if (index >= count) {
    throwGroundingError(phrase.text, "there " + std::string(count == 1 ? "is" : "are") + " only " + std::to_string(count) + ": " + describe(names));
  }
  return {names[static_cast<std::size_t>(index)]};
}

std::vector<std::string> NounPhraseReader::narrow(const NounPhrase& phrase,
                                                  std::vector<std::string> names) const {
  std::erase_if(names, [this, &phrase](const std::string& name) {
    const ObjectDescriptor& object = descriptor(name);
    return !hasColours(object, phrase.colours) || (!phrase.shapes.empty() && !containsWord(phrase.shapes, object.shape));
  });
  if (phrase.rank != 0) return ranked(phrase, std::move(names));
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
