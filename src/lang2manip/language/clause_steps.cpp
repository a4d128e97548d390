// StepParser: what is not a placement: handing over and keeping ("hand me X", "keep X on Y"),
// and the objects a step moves, read with where it puts them.

#include "lang2manip/language/clause_parser.hpp"
#include "lang2manip/language/clause_step.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip::language_detail {

void StepParser::parseHandOver(Step& step) {
  static const std::vector<Words> person{{"me"}, {"us"}, {"the", "user"}, {"the", "person"}, {"the", "human"}, {"the", "operator"}, {"here"}};
  auto skipPerson = [&step](std::size_t from) {
    for (const Words& words : person) {
      if (matchesAt(step.words, from, words)) return from + words.size();
    }
    return from;
  };
  step.at = skipPerson(step.at);  // "hand me the marker"
  parseObjects(step);
  if (parseGivenTurn(step)) return;  // "give the eraser a quarter turn"
  if (step.next("over")) ++step.at;
  if (step.next("here")) ++step.at;
  if (step.next("to")) {
    const std::size_t after = skipPerson(step.at + 1);
    if (after == step.at + 1) failStep(step, "a handover goes to a person (\"to me\"), not to an object");
    step.at = after;
  }
  if (step.objects.size() != 1) failStep(step, "the robot hands over one object at a time");
  Goal goal;
  goal.kind = GoalKind::kHandedOver;
  goal.object = step.objects.front();
  specification_.goals.push_back(goal);
}

void StepParser::parseKeep(Step& step) {
  parseObjects(step);
  Goal kept;
  kept.kind = GoalKind::kDisplaced;  // "where it is", "in place", "alone": not moved at all
  if (const auto relation = vocabulary::matchRelation(step.words, step.at); relation && relation->relation) {
    const std::optional<NounPhrase> target = reader_.read(step.words, step.at + relation->length);
    if (!target) failStep(step, "expected where to keep it");
    kept.kind = GoalKind::kRelation;
    kept.relation = *relation->relation;
    kept.target = groundTarget(step, *target, *relation->relation == SpatialRelation::kIn);
    step.at = target->end;
  }
  step.at = step.words.size();
  for (const std::string& object : step.objects) {
    kept.object = object;
    specification_.kept.push_back(kept);
  }
}

std::vector<std::string> StepParser::peekDestinations(const Step& step, std::size_t at) const {
  const Words& words = step.words;
  while (at < words.size() && (words[at] == "up" || words[at] == "down" || words[at] == "back" || words[at] == "away")) ++at;
  const std::size_t source = words.size() > at && (words[at] == "from" || words[at] == "off") ? 1
                             : matchesAt(words, at, {"out", "of"})                           ? 2
                                                                                             : 0;
  if (source > 0) {
    const std::optional<NounPhrase> phrase = reader_.read(words, at + source);
    if (!phrase) return {};
    at = phrase->end;
  }
  std::vector<std::string> targets;
  while (true) {  // "on the desk next to the holder"
    if (auto length = vocabulary::matchLength(words, at)) at += length->length;
    const std::optional<vocabulary::RelationMatch> relation = vocabulary::matchRelation(words, at);
    if (!relation) return targets;
    const auto direction = vocabulary::matchDirection(words, at);
    if (direction && direction->length >= relation->length) return targets;  // "to the left": a displacement
    const std::optional<NounPhrase> target = reader_.read(words, at + relation->length);
    if (!target || target->pronoun != Pronoun::kNone) return targets;
    try {
      const std::vector<std::string> names = reader_.ground(*target, discourse_, true, {});
      if (names.size() == 1) targets.push_back(names.front());
    } catch (const PlanningError&) {
      // the target's own error is reported when the relation is parsed
    }
    at = target->end;
  }
}

std::vector<std::string> StepParser::groundMoved(const NounPhrase& phrase, const std::vector<std::string>& destinations) const {
  try {
    std::vector<std::string> plain = reader_.ground(phrase, discourse_, false, {});
    // A destination named alone ("the red block on the red block") is refused later; picked
    // by a superlative or a place ("the object farthest from you"), it was not meant.
    const bool picked = phrase.modifier || phrase.size != SizeWord::kNone || phrase.place != PlaceWord::kNone;
    const bool includesDestination = std::any_of(destinations.begin(), destinations.end(),
                                                 [&plain](const std::string& name) { return containsWord(plain, name); });
    if (!includesDestination || (plain.size() == 1 && !picked)) return plain;
  } catch (const PlanningError&) {
    if (destinations.empty()) throw;
  }
  return reader_.ground(phrase, discourse_, false, {}, false, destinations);
}

}  // namespace lang2manip::language_detail
