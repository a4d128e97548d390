#include "lang2manip/language/clause_parser.hpp"
#include "lang2manip/language/clause_step.hpp"

#include <algorithm>

#include "lang2manip/language/goal_conflicts.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip::language_detail {
namespace {

bool isDirectional(SpatialRelation relation) {
  return relation != SpatialRelation::kIn && relation != SpatialRelation::kOn;
}

/// "a little" / "a lot" at words[at] before a side relation ("a little to the left of the bowl"):
/// the gap it means, `at` moved past it; nullopt otherwise.
std::optional<double> readVagueGap(const Words& words, std::size_t& at) {
  const auto magnitude = vocabulary::matchMagnitude(words, at);
  if (!magnitude) return std::nullopt;
  const auto following = vocabulary::matchRelation(words, at + magnitude->length);
  if (!following || !following->relation || !isDirectional(*following->relation)) return std::nullopt;
  at += magnitude->length;
  return magnitude->gap;
}

std::string verbList() {
  std::string text;
  for (const std::string& lemma : vocabulary::verbLemmas()) {
    if (!text.empty()) text += ", ";
    text += lemma;
  }
  return text;
}

}  // namespace


void StepParser::parse(const Words& words, const StepModifiers& modifiers) {
  clauseBefore_.clear();
  clauseStart_ = specification_.goals.size();
  if (!words.empty() && !sameAs(words, 0)) {
    if (const std::optional<Words> reordered = inVerbFirstOrder(words)) {
      parse(*reordered, modifiers);
      return;
    }
  }
  Step step(words);
  step.firstGoal = specification_.goals.size();
  if (words.empty()) {
    finish(step, modifiers);
    return;
  }
  if (const std::size_t same = sameAs(words, 0)) {
    parseSameAs(step, same);
  } else {
    readVerb(step);
    parsePredicate(step);
  }
  if (!step.atEnd()) {
    throwGroundingError(joinWords(words, step.at, words.size()),
                        "not understood in \"" + joinWords(words) + "\"");
  }
  finish(step, modifiers);
}

void StepParser::readVerb(Step& step) {
  const Words& words = step.words;
  const bool displacementOnly = vocabulary::matchLength(words, 0) || vocabulary::matchDirection(words, 0);
  if (auto verb = vocabulary::matchVerb(words, 0)) {
    step.verb = verb->verb;
    step.at = verb->length;
  } else if (lastVerb_ && (reader_.read(words, 0) || (displacementOnly && lastVerb_->pushes))) {
    step.verb = *lastVerb_;  // "..., then the eraser"
    step.elliptical = true;
  } else {
    throwGroundingError(joinWords(words), "\"" + words.front() +
                                              "\" is not an action the offline planner knows "
                                              "(actions: " + verbList() + ")");
  }
  lastVerb_ = step.verb;
  step.putsDown = step.verb.putsDown;
}

void StepParser::parsePredicate(Step& step) {
  if (step.verb.goesHome && vocabulary::matchHome(step.words, step.at)) {
    parseHome(step);
    return;
  }
  if (step.verb.keeps) {
    parseKeep(step);
    return;
  }
  if (step.verb.summarizes) {  // "tidy up: put everything in the holder": a heading, the steps say how
    step.at = step.words.size();
    return;
  }
  if (step.verb.handsOver || (step.verb.places && handsToPerson(step))) {
    parseHandOver(step);
    return;
  }
  if (step.verb.fills) {
    parseFill(step);
    return;
  }
  if (step.verb.swaps || step.verb.turns || step.verb.points || step.verb.replaces) {
    if (step.verb.swaps) parseSwap(step);
    if (step.verb.turns) parseTurn(step);
    if (step.verb.points) parsePoint(step);
    if (step.verb.replaces) parseReplace(step);
    return;
  }
  if (!step.verb.places && !step.verb.picks && !step.verb.pushes) {
    failStep(step, "the only place to " + step.verb.lemma + " is home");
  }
  if (step.elliptical && !reader_.read(step.words, step.at) && !discourse_.lastObjects.empty()) {
    step.objects = discourse_.lastObjects;  // "push it 5 cm left, then 3 cm forward": the same objects again
  } else {
    parseObjects(step);
  }
  if (!parsePlacement(step)) parseWithoutPlace(step);
  parseGappedRelations(step);
  parseGappedPlacements(step);
  skipSource(step);
  skipRejectedAlternative(step);
}


bool StepParser::parsePlacement(Step& step) {
  return parsePutBack(step) || parseBetween(step) || parseWhereStands(step) || parseRelations(step) || parseDisplacement(step);
}



std::size_t StepParser::sameAs(const Words& words, std::size_t at) {
  static const std::vector<Words> phrases{
      tokenize("do the same with"), tokenize("do the same for"), tokenize("do the same to"),
      tokenize("do the same thing with"), tokenize("do the same thing for"),
      tokenize("do likewise with"), tokenize("same for"), tokenize("same with"),
      tokenize("repeat with"), tokenize("repeat for"), tokenize("repeat that with"),
      tokenize("repeat that for")};
  return longestPhraseAt(words, at, phrases);
}

void StepParser::parseSameAs(Step& step, std::size_t length) {
  if (!lastStepRelation_) {
    throwGroundingError(joinWords(step.words, 0, length),
                        "the previous step has no place to repeat");
  }
  step.at = length;
  const std::vector<NounPhrase> list = reader_.readList(step.words, step.at);
  if (list.empty()) failStep(step, "expected the object(s) to do the same with");
  step.at = list.back().end;
  step.objects = groundList(step, list);
  const RelationSpec relation = *lastStepRelation_;
  if (containsWord(step.objects, relation.target)) {
    throwGroundingError(joinWords(step.words), "cannot relate " + relation.target + " to itself");
  }
  addRelationGoals(step, relation);
}

void StepParser::parseHome(Step& step) {
  step.at += *vocabulary::matchHome(step.words, step.at);
  Goal goal;
  goal.kind = GoalKind::kAtConfiguration;
  goal.configuration = "home";
  specification_.goals.push_back(goal);
}

void StepParser::parseObjects(Step& step) {
  const std::vector<NounPhrase> list = reader_.readList(step.words, step.at);
  if (list.empty()) {
    failStep(step, "expected the object(s) to " + step.verb.lemma + " after \"" +
                       joinWords(step.words, 0, step.at) + "\"");
  }
  step.at = list.back().end;
  step.objects = groundList(step, list);
  for (const NounPhrase& phrase : list) {
    if (phrase.noun) discourse_.lastObjectNoun = phrase.noun->objects;
  }
  // Particles: "pick it up", "put it down", "put it back in the holder" (but "push it back
  // 3 cm" and "move it away" are directions).
  while (step.next("up") || step.next("down") || (step.next("over") && step.at + 1 == step.words.size()) ||
         ((step.next("back") || step.next("away")) &&
          vocabulary::matchRelation(step.words, step.at + 1))) {
    if (step.next("down")) step.putsDown = true;
    ++step.at;
  }
  skipSource(step);
}

std::vector<std::string> StepParser::groundList(Step& step, const std::vector<NounPhrase>& list) {
  std::vector<std::string> objects;
  const std::vector<std::string> destinations = peekDestinations(step, list.back().end);
  const NounPhrase& only = list.front();
  step.distributive = list.size() == 1 && only.quantity == Quantity::kIndefinite && !only.other && !only.isPlural() &&
                      only.pronoun == Pronoun::kNone && eachPlaceFollows(step.words, only.end);
  discourse_.stepReferences.clear();
  for (NounPhrase phrase : list) {
    if (step.distributive) phrase.quantity = Quantity::kAll;  // every candidate; the places choose
    const std::vector<std::string> grounded = groundMoved(phrase, destinations);
    for (const NounPhrase& reference : phrase.modifier ? phrase.modifier->reference : std::vector<NounPhrase>{}) {
      for (const std::string& object : reader_.ground(reference, discourse_, true, {})) discourse_.stepReferences.push_back(object);
    }
    const bool group = phrase.isPlural() && phrase.pronoun == Pronoun::kNone;
    if (group && list.size() == 1) step.listedExplicitly = false;
    for (const std::string& object : grounded) {
      if (containsWord(objects, object)) continue;
      objects.push_back(object);
      if (group) step.groupObjects.push_back(object);
    }
  }
  discourse_.mention(objects);
  return objects;
}

void StepParser::skipSource(Step& step) {
  std::size_t length = 0;
  if (step.next("from")) length = 1;
  else if (matchesAt(step.words, step.at, {"out", "of"})) length = 2;
  else if (matchesAt(step.words, step.at, {"off", "of"})) length = 2;
  else if (step.next("off")) length = 1;
  if (length == 0) return;
  const std::optional<NounPhrase> source = reader_.read(step.words, step.at + length);
  if (!source) return;
  // The source only has to name an object; where things are comes from the scene.
  (void)reader_.ground(*source, discourse_, true, step.objects);
  step.at = source->end;
}

bool StepParser::parseRelations(Step& step) {
  bool any = false;
  while (parseRelation(step)) any = true;  // "on the desk next to the holder"
  if (!any) return false;
  auto& goals = specification_.goals;
  // "every object on the desk in the holder": where the objects stand now, not a first place.
  const std::size_t count = step.objects.size();
  while (count > 0 && goals.size() >= step.firstGoal + 2 * count) {
    const Goal& first = goals[step.firstGoal];
    const bool restsAlready = first.relation == SpatialRelation::kOn &&
                              std::all_of(step.objects.begin(), step.objects.end(), [&](const std::string& object) { return standsOn(object, first.target); });
    const bool placedAfter = std::any_of(goals.begin() + static_cast<std::ptrdiff_t>(step.firstGoal + count), goals.end(), [](const Goal& goal) {
      return goal.relation == SpatialRelation::kIn || goal.relation == SpatialRelation::kOn;
    });
    if (!restsAlready || !placedAfter) break;
    goals.erase(goals.begin() + static_cast<std::ptrdiff_t>(step.firstGoal), goals.begin() + static_cast<std::ptrdiff_t>(step.firstGoal + count));
  }
  // "in the holder on the desk": where the holder stands, not a second place for the objects.
  for (std::size_t i = step.firstGoal; i + step.objects.size() < goals.size(); ++i) {
    const Goal& first = goals[i];
    const Goal& second = goals[i + step.objects.size()];
    const bool locative = second.relation == SpatialRelation::kOn && first.relation &&
                          (*first.relation == SpatialRelation::kIn || *first.relation == SpatialRelation::kOn) &&
                          standsOn(first.target, second.target);
    if (locative) goals.erase(goals.begin() + static_cast<std::ptrdiff_t>(i + step.objects.size()));
  }
  refuseConflictingGoals({goals.begin() + static_cast<std::ptrdiff_t>(step.firstGoal), goals.end()}, joinWords(step.words));
  return true;
}


bool StepParser::parseRelation(Step& step) {
  if (parseAssignment(step) || parseArrangement(step) || parseRegion(step)) return true;
  const Words& words = step.words;
  std::size_t at = step.at;
  std::optional<double> distance;
  if (auto length = vocabulary::matchLength(words, at)) {
    distance = length->metres;
    at += length->length;
  }
  const std::optional<double> vagueGap = distance ? std::nullopt : readVagueGap(words, at);
  if (matchesAt(words, at, {"there"}) && lastRelation_) {
    RelationSpec relation = *lastRelation_;
    if (distance) relation.distance = distance;
    step.at = at + 1;
    addRelationGoals(step, relation);
    return true;
  }
  std::optional<vocabulary::RelationMatch> relation = vocabulary::matchRelation(words, at);
  if (!relation && distance && words.size() > at && words[at] == "from") {
    relation = vocabulary::RelationMatch{SpatialRelation::kNextTo, false, 1};
  }
  if (!relation) return false;
  const auto direction = vocabulary::matchDirection(words, at);
  if (direction && direction->length >= relation->length) return false;
  const bool alongALine = matchesAt(words, at, {"away", "from"}) || matchesAt(words, at, {"closer", "to"}) || matchesAt(words, at, {"nearer", "to"});
  if (distance && alongALine) return false;  // "2 cm away from the holder": a displacement
  if (relation->relation == SpatialRelation::kOn && parseEachOther(step, at + relation->length)) return true;
  const std::optional<NounPhrase> targetPhrase = reader_.read(words, at + relation->length);
  const bool stranded = at + relation->length == words.size();
  const bool inOrOn = relation->relation && !isDirectional(*relation->relation);
  if (!targetPhrase && stranded && inOrOn && !discourse_.lastTarget.empty()) {
    // "..., then put the eraser in": the latest target
    step.at = words.size();
    addRelationGoals(step, RelationSpec{*relation->relation, discourse_.lastTarget, distance});
    return true;
  }
  if (!targetPhrase) {
    throwGroundingError(joinWords(words, at, words.size()),
                        "expected an object after \"" +
                            joinWords(words, at, at + relation->length) + "\"");
  }
  step.at = targetPhrase->end;
  const bool intoSomething = relation->byTargetRole || relation->relation == SpatialRelation::kIn;
  const std::string target = groundTarget(step, *targetPhrase, intoSomething);
  RelationSpec spec;
  spec.target = target;
  spec.relation = relation->relation ? *relation->relation : relationByRole(target);
  if (spec.relation == SpatialRelation::kOn && relation->length == 1 && isOpenDish(target)) {
    spec.relation = SpatialRelation::kIn;  // "on the plate", "on the bowl": what is on a dish is in it
  }
  if (distance) {
    if (!isDirectional(spec.relation)) {
      throwGroundingError(joinWords(words, 0, step.at),
                          "a distance cannot go with \"" + spatialRelationWords(spec.relation) +
                              "\"");
    }
    spec.distance = distance;
  }
  if (vagueGap) spec.distance = gapAsDistance(step, spec, *vagueGap);
  addRelationGoals(step, spec);
  return true;
}

std::string StepParser::groundTarget(Step& step, const NounPhrase& phrase, bool intoSomething) {
  std::vector<std::string> targets = reader_.ground(phrase, discourse_, true, step.objects, intoSomething);
  // "and the eraser on the desk next to it": "it" is not the desk this clause already named but
  // the object of the clause before.
  const bool namedInClause = targets.size() == 1 && phrase.pronoun == Pronoun::kIt &&
                             std::any_of(specification_.goals.begin() + static_cast<std::ptrdiff_t>(clauseStart_), specification_.goals.end(),
                                         [&](const Goal& goal) { return goal.target == targets.front() && containsWord(step.objects, goal.object); });
  if (namedInClause && clauseBefore_.size() == 1) targets = clauseBefore_;
  if (targets.size() != 1) {
    throwGroundingError(phrase.text, "a relation needs one target object, but it names " +
                                         std::to_string(targets.size()));
  }
  if (phrase.noun) discourse_.lastTargetNoun = phrase.noun->objects;
  const std::string& target = targets.front();
  discourse_.lastTarget = target;
  discourse_.mention({target});
  const bool inGroup = containsWord(step.groupObjects, target);
  std::erase(step.groupObjects, target);
  if (containsWord(step.objects, target)) {
    if (!inGroup) {
      throwGroundingError(joinWords(step.words), "cannot relate " + target + " to itself");
    }
    std::erase(step.objects, target);
    if (step.objects.empty()) {
      throwGroundingError(joinWords(step.words), "no object is left once " + target +
                                                     " (the target) is left out");
    }
  }
  return target;
}

SpatialRelation StepParser::relationByRole(const std::string& target) const {
  switch (reader_.descriptor(target).role) {
    case ObjectRole::kContainer: return SpatialRelation::kIn;
    case ObjectRole::kSupport: return SpatialRelation::kOn;
    case ObjectRole::kNone: break;
  }
  return SpatialRelation::kNextTo;
}

void StepParser::addRelationGoals(Step& step, const RelationSpec& relation) {
  if (relation.relation == SpatialRelation::kIn &&
      reader_.descriptor(relation.target).role != ObjectRole::kContainer) {
    throwGroundingError(joinWords(step.words), relation.target + " is not a container");
  }
  step.target = relation.target;
  lastRelation_ = relation;
  if (step.verb.stacks) {
    addStackGoals(step, relation.target, relation.region);
    return;
  }
  for (const std::string& object : step.objects) addGoal(object, relation);
}

void StepParser::addStackGoals(Step& step, const std::optional<std::string>& base, const std::optional<SurfaceRegion>& region) {
  std::vector<std::string> order = step.objects;
  if (!step.listedExplicitly) {
    std::stable_sort(order.begin(), order.end(), [this](const std::string& a, const std::string& b) {
      return reader_.descriptor(a).volume > reader_.descriptor(b).volume;
    });
  }
  if (base) order.insert(order.begin(), *base);
  if (order.size() < 2) failStep(step, "stacking needs at least two objects");
  for (std::size_t i = 1; i < order.size(); ++i) {
    Goal goal;
    goal.kind = GoalKind::kRelation;
    goal.object = order[i];
    goal.relation = SpatialRelation::kOn;
    goal.target = order[i - 1];
    if (i == 1 && base) goal.region = region;
    specification_.goals.push_back(goal);
  }
}


void StepParser::parseWithoutPlace(Step& step) {
  if (step.verb.stacks) {
    addStackGoals(step, std::nullopt);
    return;
  }
  if (step.elliptical && lastStepRelation_) {
    addRelationGoals(step, *lastStepRelation_);
    return;
  }
  if (step.putsDown) {
    std::vector<std::string> supports;
    for (const ObjectDescriptor& object : reader_.objects()) {
      if (object.role == ObjectRole::kSupport) supports.push_back(object.name);
    }
    if (supports.size() != 1) failStep(step, "say where to put it down");
    addRelationGoals(step, RelationSpec{SpatialRelation::kOn, supports.front(), std::nullopt});
    return;
  }
  if (!step.verb.picks) {
    failStep(step, "say where to " + step.verb.lemma + " it (e.g. \"in the holder\")");
  }
  for (const std::string& object : step.objects) {
    Goal goal;
    goal.kind = GoalKind::kHolding;
    goal.object = object;
    specification_.goals.push_back(goal);
  }
}

void StepParser::parseGappedRelations(Step& step) {
  // "put the marker in the holder and the eraser on the desk"
  while (step.target.size() > 0 && (step.next("and") || step.next(","))) {
    const std::size_t restart = step.at;
    std::size_t at = step.at + 1;
    if (matchesAt(step.words, at, {"and"})) ++at;
    if (vocabulary::matchRelation(step.words, at)) {  // "on the desk and next to the holder"; refused when they conflict
      step.at = at;
      if (!parseRelation(step)) {
        step.at = restart;
        return;
      }
      refuseConflictingGoals({specification_.goals.begin() + static_cast<std::ptrdiff_t>(step.firstGoal), specification_.goals.end()},
                             joinWords(step.words));
      continue;
    }
    const std::vector<NounPhrase> list = reader_.readList(step.words, at);
    if (list.empty()) return;
    step.at = list.back().end;
    std::vector<std::string> previous = step.objects;
    clauseBefore_ = previous;
    clauseStart_ = specification_.goals.size();
    step.objects = groundList(step, list);
    if (step.atEnd() && lastRelation_) {
      addRelationGoals(step, *lastRelation_);  // "..., and the eraser too"
      return;
    }
    const std::size_t firstOfClause = specification_.goals.size();
    if (parseRelation(step)) {  // "and the eraser on the desk next to it"
      while (parseRelation(step)) {
      }
      refuseConflictingGoals({specification_.goals.begin() + static_cast<std::ptrdiff_t>(firstOfClause), specification_.goals.end()},
                             joinWords(step.words));
      continue;
    }
    {
      step.at = restart;
      step.objects = previous;
      return;
    }
  }
}

void StepParser::finish(Step& step, const StepModifiers& modifiers) {
  const bool modifiersOnly = step.words.empty();
  std::vector<std::string> acted = step.objects;
  if (modifiersOnly) acted = discourse_.lastObjects;
  bool home = false;
  for (std::size_t i = step.firstGoal; i < specification_.goals.size(); ++i) {
    home = home || specification_.goals[i].kind == GoalKind::kAtConfiguration;
  }
  if (modifiers.grasp) {
    if (acted.empty()) throwGroundingError("grasp", "no object was named to grasp that way");
    for (const std::string& object : acted) specification_.grasps[object] = *modifiers.grasp;
  }
  if (!modifiers.planner.empty()) {
    if (modifiers.plannerForAll || (modifiersOnly && !modifiers.grasp)) {
      specification_.defaultPlanner = modifiers.planner;
    } else {
      for (const std::string& object : acted) specification_.planners[object] = modifiers.planner;
      if (home) specification_.planners[""] = modifiers.planner;
    }
  }
  if (modifiersOnly) return;
  lastStepRelation_.reset();
  if (!step.target.empty()) lastStepRelation_ = lastRelation_;
  if (!step.objects.empty()) {
    discourse_.lastObjects = step.objects;
    discourse_.mention(step.objects);
  }
  if (!step.target.empty()) {
    discourse_.lastTarget = step.target;
    discourse_.mention({step.target});
  }
}

void StepParser::failStep(const Step& step, const std::string& why) const {
  throwGroundingError(joinWords(step.words), why);
}

}  // namespace lang2manip::language_detail
