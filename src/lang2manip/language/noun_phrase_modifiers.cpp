// NounPhraseReader: what may follow a noun: a modifier ("closest to the holder", "that is on the
// desk", "lying on the table", "furthest to the left"), an exception ("except the holder") or a
// negated relative clause ("that is not the eraser").

#include <utility>

#include "lang2manip/language/noun_phrase.hpp"
#include "lang2manip/language/vocabulary.hpp"

namespace lang2manip::language_detail {

std::size_t NounPhraseReader::exceptionWords(const Words& words, std::size_t at) {
  static const std::vector<Words> phrases{{"except"}, {"except", "for"}, {"but"}, {"other", "than"}, {"apart", "from"},
                                          {"excluding"}, {"save", "for"}, {"aside", "from"}};
  return longestPhraseAt(words, at, phrases);
}

std::size_t NounPhraseReader::negatedClauseWords(const Words& words, std::size_t at) {
  static const std::vector<Words> phrases{{"that", "is", "not"}, {"which", "is", "not"}, {"that", "isn't"}, {"which", "isn't"},
                                          {"that", "are", "not"}, {"which", "are", "not"}, {"that", "aren't"}, {"which", "aren't"}};
  return longestPhraseAt(words, at, phrases);
}

std::size_t NounPhraseReader::readModifier(const Words& words, std::size_t at, NounPhrase& phrase) const {
  if (phrase.pronoun != Pronoun::kNone || phrase.unknownNoun || at >= words.size()) return at;
  std::size_t p = at;
  bool relativeClause = false;
  static const std::vector<Words> leads{{"that", "is"},     {"which", "is"},   {"that", "are"},     {"which", "are"},  {"lying"},
                                        {"sitting"},        {"standing"},      {"resting"},         {"located"},       {"placed"},
                                        {"that", "lies"},   {"that", "sits"},  {"that", "stands"},  {"that", "rests"}, {"that", "is", "lying"},
                                        {"that", "is", "sitting"}, {"that", "is", "standing"}, {"that", "are", "lying"},
                                        // where it stood before the instruction began: references are read on the initial scene
                                        {"that", "was"}, {"which", "was"}, {"that", "were"}, {"which", "were"}, {"that", "was", "previously"},
                                        {"which", "was", "previously"}, {"that", "was", "originally"}, {"previously"}, {"originally"},
                                        {"that", "used", "to", "be"}, {"that", "stood"}, {"that", "was", "standing"}};
  std::size_t leadLength = 0;
  for (const Words& lead : leads) {
    if (lead.size() > leadLength && matchesAt(words, p, lead)) leadLength = lead.size();
  }
  if (leadLength > 0) {
    p += leadLength;
    relativeClause = true;
  }
  // "the object (that is) furthest to the left": the leftmost.
  for (const Words& side : {Words{"furthest", "to", "the", "left"}, Words{"farthest", "to", "the", "left"}, Words{"most", "to", "the", "left"},
                            Words{"furthest", "left"}, Words{"farthest", "left"}}) {
    if (matchesAt(words, p, side) && phrase.place == PlaceWord::kNone) {
      phrase.place = PlaceWord::kLeft;
      return p + side.size();
    }
  }
  for (const Words& side : {Words{"furthest", "to", "the", "right"}, Words{"farthest", "to", "the", "right"}, Words{"most", "to", "the", "right"},
                            Words{"furthest", "right"}, Words{"farthest", "right"}}) {
    if (matchesAt(words, p, side) && phrase.place == PlaceWord::kNone) {
      phrase.place = PlaceWord::kRight;
      return p + side.size();
    }
  }
  const bool selects = headIsAmbiguous(phrase) || phrase.isPlural();
  if (const std::size_t after = readBetweenOrSameAs(words, p, phrase, selects)) return after;
  if (const std::size_t after = p != at ? readBetweenOrSameAs(words, at, phrase, selects) : 0) return after;  // "that has the same colour as"
  if (const std::size_t after = readBesidePronoun(words, p, phrase, selects)) return after;
  NounModifier modifier;
  std::size_t length = 0;
  for (const Words& nearest : {Words{"closest", "to"}, Words{"nearest", "to"}, Words{"nearest"}}) {
    if (length == 0 && matchesAt(words, p, nearest)) modifier.kind = NounModifier::Kind::kNearestTo, length = nearest.size();
  }
  for (const Words& farthest : {Words{"farthest", "away", "from"}, Words{"furthest", "away", "from"}, Words{"farthest", "from"},
                                Words{"furthest", "from"}}) {
    if (length == 0 && matchesAt(words, p, farthest)) modifier.kind = NounModifier::Kind::kFarthestFrom, length = farthest.size();
  }
  const bool ambiguous = headIsAmbiguous(phrase);
  if (length != 0 && !(ambiguous || phrase.isPlural())) return at;  // "put the marker closest to ...": a place
  if (length == 0 && ambiguous && (matchesAt(words, p, {"on", "the", "left"}) || matchesAt(words, p, {"on", "the", "right"})) &&
      !matchesAt(words, p + 3, {"of"})) {
    phrase.place = words[p + 2] == "left" ? PlaceWord::kLeft : PlaceWord::kRight;  // "the thing on the right"
    return p + 3;
  }
  if (length == 0) {
    const auto relation = vocabulary::matchRelation(words, p);
    const bool beside = relation && relation->relation && *relation->relation != SpatialRelation::kIn &&
                        *relation->relation != SpatialRelation::kOn;
    // "in"/"on" say where the objects are only in a relative clause ("everything that is on the desk").
    const bool where = relation && relation->relation && relativeClause;
    if (!(beside || where) || !(ambiguous || phrase.isPlural())) return at;
    modifier.relation = *relation->relation;
    length = relation->length;
  }
  for (const Words& robot : {Words{"the", "robot", "base"}, Words{"the", "robot"}, Words{"the", "base"}, Words{"you"}}) {
    if (matchesAt(words, p + length, robot)) {
      phrase.modifier = std::move(modifier);  // no reference phrase: the robot
      return p + length + robot.size();
    }
  }
  if (matchesAt(words, p + length, {"each", "other"}) || matchesAt(words, p + length, {"one", "another"})) return at;  // an arrangement
  const std::optional<NounPhrase> reference = read(words, p + length);
  if (!reference) return at;
  // A plural phrase's place is where they go ("put the blocks next to the box") unless the
  // step goes on with another place.
  if (modifier.kind == NounModifier::Kind::kRelation && !ambiguous && !relativeClause &&
      !vocabulary::matchRelation(words, reference->end)) {
    return at;
  }
  modifier.reference = {*reference};
  phrase.modifier = std::move(modifier);
  return reference->end;
}

std::size_t NounPhraseReader::readBesidePronoun(const Words& words, std::size_t p, NounPhrase& phrase, bool selects) {
  static const std::vector<std::pair<Words, SpatialRelation>> sides{
      {{"to", "its", "left"}, SpatialRelation::kLeftOf},      {{"on", "its", "left"}, SpatialRelation::kLeftOf},
      {{"to", "its", "right"}, SpatialRelation::kRightOf},    {{"on", "its", "right"}, SpatialRelation::kRightOf},
      {{"in", "front", "of", "it"}, SpatialRelation::kInFrontOf}, {{"behind", "it"}, SpatialRelation::kBehind},
      {{"next", "to", "it"}, SpatialRelation::kNextTo},       {{"beside", "it"}, SpatialRelation::kNextTo}};
  if (!selects) return 0;
  for (const auto& [side, relation] : sides) {
    if (!matchesAt(words, p, side)) continue;
    NounPhrase it;
    it.begin = p + side.size() - 1;
    it.end = p + side.size();
    it.text = "it";
    it.pronoun = Pronoun::kIt;
    NounModifier modifier;
    modifier.relation = relation;
    modifier.reference = {it};
    phrase.modifier = std::move(modifier);
    const std::size_t after = p + side.size();
    return after + longestPhraseAt(words, after, {{"before"}, {"previously"}, {"earlier"}, {"originally"}, {"at", "first"}, {"at", "the", "start"}});
  }
  return 0;
}

std::size_t NounPhraseReader::readBetweenOrSameAs(const Words& words, std::size_t p, NounPhrase& phrase, bool selects) const {
  NounModifier modifier;
  if (const std::size_t between = longestPhraseAt(words, p, {{"between"}, {"in", "between"}}); between > 0 && selects) {
    // "the block between the red bowl and the blue bowl"; without several to choose from it is a place
    const std::optional<NounPhrase> first = read(words, p + between);
    const std::optional<NounPhrase> second = first && matchesAt(words, first->end, {"and"}) ? read(words, first->end + 1) : std::nullopt;
    if (!second) return 0;
    modifier.kind = NounModifier::Kind::kBetween;
    modifier.reference = {*first, *second};
    phrase.modifier = std::move(modifier);
    return second->end;
  }
  static const std::vector<Words> leads{{"with", "the", "same"}, {"of", "the", "same"}, {"in", "the", "same"}, {"having", "the", "same"},
                                        {"that", "has", "the", "same"}, {"that", "have", "the", "same"}, {"which", "has", "the", "same"},
                                        {"which", "have", "the", "same"}, {"that", "is", "the", "same"}, {"that", "are", "the", "same"},
                                        {"the", "same"}};
  const std::size_t lead = longestPhraseAt(words, p, leads);
  if (lead == 0 || p + lead + 1 >= words.size()) return 0;
  const std::string& property = words[p + lead];
  const std::string named = property == "color" ? "colour" : property == "type" ? "kind" : property;
  if ((named != "colour" && named != "shape" && named != "size" && named != "kind") || !matchesAt(words, p + lead + 1, {"as"})) return 0;
  const std::optional<NounPhrase> reference = read(words, p + lead + 2);
  if (!reference) return 0;
  modifier.kind = NounModifier::Kind::kSameAs;
  modifier.property = named;
  modifier.reference = {*reference};
  phrase.modifier = std::move(modifier);
  return reference->end;
}

}  // namespace lang2manip::language_detail
