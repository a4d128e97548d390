// StepParser: rearrangements and turns: "swap X and Y", "put X where Y is", "replace Y with X",
// "turn X by 90 degrees clockwise", "point X at Y".

#include <algorithm>
#include <cmath>
#include <utility>

#include "lang2manip/language/clause_parser.hpp"
#include "lang2manip/language/clause_step.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip::language_detail {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;
/// "turn it a little": a turn of this many degrees.
constexpr double kSmallTurnDegrees = 15.0;

std::vector<Words> phrasesOf(std::initializer_list<const char*> texts) {
  std::vector<Words> phrases;
  for (const char* text : texts) phrases.push_back(tokenize(text));
  return phrases;
}

/// A turn's size (rad, unsigned) and its length in words.
struct TurnAmount {
  double radians = 0.0;
  std::size_t length = 0;
};

std::optional<TurnAmount> matchNamedTurn(const Words& words, std::size_t at) {
  static const std::vector<std::pair<Words, double>> named = [] {
    std::vector<std::pair<Words, double>> list;
    const std::pair<const char*, double> table[] = {
        {"a quarter turn", 90},      {"quarter turn", 90},         {"a quarter of a turn", 90}, {"a quarter", 90},
        {"a half turn", 180},        {"half a turn", 180},         {"half turn", 180},          {"a half", 180},
        {"around", 180},             {"round", 180},               {"all the way around", 180}, {"sideways", 90},
        {"a full turn", 360},        {"a whole turn", 360},        {"full circle", 360},        {"thirty", 30},
        {"forty five", 45},          {"fortyfive", 45},            {"sixty", 60},               {"ninety", 90},
        {"a hundred and eighty", 180}, {"one hundred and eighty", 180}, {"a hundred eighty", 180},
        {"one hundred eighty", 180}, {"a right angle", 90}};
    for (const auto& [text, degrees] : table) list.emplace_back(tokenize(text), degrees);
    return list;
  }();
  std::optional<TurnAmount> best;
  for (const auto& [phrase, degrees] : named) {
    if (matchesAt(words, at, phrase) && (!best || phrase.size() > best->length)) best = TurnAmount{degrees * kDegree, phrase.size()};
  }
  return best;
}

/// "90 degrees", "45 deg", "90°", "1.57 radians", "ninety degrees", "a quarter turn", "around";
/// a bare number is in degrees.
std::optional<TurnAmount> matchTurnAmount(const Words& words, std::size_t at) {
  const std::size_t approximately = vocabulary::matchApproximation(words, at);
  at += approximately;
  std::optional<TurnAmount> amount;
  if (at < words.size()) {
    if (const std::optional<double> number = numberValue(words[at])) amount = TurnAmount{*number * kDegree, 1};
  }
  if (!amount) amount = matchNamedTurn(words, at);
  if (!amount) return std::nullopt;
  const std::size_t unit = at + amount->length;
  static const std::vector<Words> degrees = phrasesOf({"degrees", "degree", "deg", "degs", "\xc2\xb0"});
  static const std::vector<Words> radians = phrasesOf({"radians", "radian", "rad", "rads"});
  if (const std::size_t length = longestPhraseAt(words, unit, degrees)) {
    amount->length += length;
  } else if (const std::size_t radianLength = longestPhraseAt(words, unit, radians)) {
    amount->radians /= kDegree;
    amount->length += radianLength;
  }
  amount->length += approximately;
  return amount;
}

/// +1 counter-clockwise (seen from above; "to the left"), -1 clockwise, with its length.
std::optional<std::pair<double, std::size_t>> matchTurnSense(const Words& words, std::size_t at) {
  static const std::vector<Words> counter = phrasesOf({"counterclockwise", "counter clockwise", "anticlockwise", "anti clockwise",
                                                       "to the left", "left", "leftward", "leftwards", "ccw"});
  static const std::vector<Words> clockwise = phrasesOf({"clockwise", "to the right", "right", "rightward", "rightwards", "cw"});
  const std::size_t left = longestPhraseAt(words, at, counter);
  const std::size_t right = longestPhraseAt(words, at, clockwise);
  if (left == 0 && right == 0) return std::nullopt;
  return left >= right ? std::make_pair(1.0, left) : std::make_pair(-1.0, right);
}

}  // namespace

void StepParser::parseTurn(Step& step) {
  parseObjects(step);
  if (parsePointing(step, true)) return;
  const Words& words = step.words;
  std::optional<TurnAmount> amount;
  std::optional<double> sense;
  static const std::vector<Words> slightly = phrasesOf({"a little", "a bit", "slightly", "a little bit", "a touch"});
  bool small = false;
  for (int part = 0; part < 3; ++part) {  // the amount and the sense, in either order
    if (const std::size_t length = longestPhraseAt(words, step.at, slightly)) {
      small = true;
      step.at += length;
    }
    if (step.next(",")) ++step.at;
    if (const auto found = matchTurnSense(words, step.at); found && !sense) {
      sense = found->first;
      step.at += found->second;
    }
    const std::size_t by = (step.next("by") || step.next("through")) ? 1 : 0;
    if (const auto found = matchTurnAmount(words, step.at + by); found && !amount) {
      amount = found;
      step.at += by + found->length;
    }
  }
  if (!amount && small) amount = TurnAmount{kSmallTurnDegrees * kDegree, 0};
  if (!amount) failStep(step, "say how far to " + step.verb.lemma + " it (\"by 90 degrees\", \"a quarter turn\") or what it should point at");
  addTurnGoals(step, sense.value_or(1.0) * amount->radians);
}

void StepParser::addTurnGoals(const Step& step, double angle) {
  if (angle == 0.0) failStep(step, "a turn of zero leaves it as it was");
  if (std::abs(angle) >= 360.0 * kDegree - 1e-9) failStep(step, "a full turn (or more) leaves it as it was; say a turn below 360 degrees");
  for (const std::string& object : step.objects) {
    Goal goal;
    goal.kind = GoalKind::kTurned;
    goal.object = object;
    goal.angle = angle;
    specification_.goals.push_back(goal);
  }
}

bool StepParser::parseGivenTurn(Step& step) {
  const Words& words = step.words;
  std::size_t at = step.at;
  static const std::vector<Words> article = phrasesOf({"a", "an", "a turn of", "a rotation of", "a spin of"});
  std::optional<TurnAmount> amount = matchTurnAmount(words, at);
  if (!amount) {
    at += longestPhraseAt(words, at, article);
    amount = matchTurnAmount(words, at);
  }
  if (!amount) return false;
  at += amount->length;
  static const std::vector<Words> noun = phrasesOf({"turn", "rotation", "spin", "twist"});
  at += longestPhraseAt(words, at, noun);
  std::optional<double> sense;
  if (const auto found = matchTurnSense(words, at)) {
    sense = found->first;
    at += found->second;
  }
  step.at = at;
  addTurnGoals(step, sense.value_or(1.0) * amount->radians);
  return true;
}

/// A direction to point along, as the yaw of a line in the base frame (front and back are one
/// line, so are left and right), with its length; nullopt when none.
std::optional<std::pair<double, std::size_t>> matchHeading(const Words& words, std::size_t at) {
  static const std::vector<std::pair<Words, double>> table = [] {
    std::vector<std::pair<Words, double>> list;
    const std::pair<const char*, double> entries[] = {
        {"forward", 0.0}, {"forwards", 0.0}, {"ahead", 0.0}, {"straight ahead", 0.0}, {"away from the robot", 0.0},
        {"away from you", 0.0}, {"toward the robot", 0.0}, {"towards the robot", 0.0}, {"toward you", 0.0}, {"towards you", 0.0},
        {"at the robot", 0.0}, {"at you", 0.0}, {"backward", 0.0}, {"backwards", 0.0}, {"to the front", 0.0}, {"to the back", 0.0},
        {"front", 0.0}, {"to the left", 90.0}, {"to the right", 90.0}, {"left", 90.0}, {"right", 90.0}, {"sideways", 90.0},
        {"to the side", 90.0}, {"the left", 90.0}, {"the right", 90.0}};
    for (const auto& [text, degrees] : entries) list.emplace_back(tokenize(text), degrees * kDegree);
    return list;
  }();
  std::optional<std::pair<double, std::size_t>> best;
  for (const auto& [phrase, yaw] : table) {
    if (matchesAt(words, at, phrase) && (!best || phrase.size() > best->second)) best = std::make_pair(yaw, phrase.size());
  }
  return best;
}

bool StepParser::parsePointing(Step& step, bool afterTurn) {
  static const std::vector<Words> connectors =
      phrasesOf({"at", "to", "toward", "towards", "in the direction of", "to face", "to point at", "to point to", "to point toward",
                 "to point towards", "so that it faces", "so it faces", "so that it points at", "so it points at",
                 "so that it points to", "so it points to", "so that it points toward", "so it points toward",
                 "so that it points towards", "so it points towards", "so that it is facing", "so it is facing", "facing",
                 "so that they face", "so they face", "so that they point at", "so they point at", "to face toward",
                 "to face towards", "so that it points", "so it points", "to point", "so they point", "so that they point"});
  static const std::vector<Words> alignments = phrasesOf({"with", "parallel to", "parallel with", "in line with", "the same way as"});
  std::size_t length = longestPhraseAt(step.words, step.at, connectors);
  if (afterTurn && (length == 0 || (length == 1 && (step.next("to") || step.next("at"))))) {
    if (length == 0 || !matchHeading(step.words, step.at + 1)) return false;
  }
  // "point the marker forward", "so that it points to the left"
  std::size_t from = step.at + length;
  std::optional<std::pair<double, std::size_t>> heading = matchHeading(step.words, from);
  if (!heading && !afterTurn) heading = matchHeading(step.words, from = step.at);
  if (heading) {
    step.at = from + heading->second;
    addFacingGoals(step, "", heading->first);
    return true;
  }
  if (length == 0 && step.verb.lemma == "align") length = longestPhraseAt(step.words, step.at, alignments);
  if (length == 0) return false;
  const std::optional<NounPhrase> phrase = reader_.read(step.words, step.at + length);
  if (!phrase) failStep(step, "expected what to point it at after \"" + joinWords(step.words, step.at, step.at + length) + "\"");
  step.at = phrase->end;
  const std::string target = groundTarget(step, *phrase, false);
  if (step.verb.lemma == "align") {  // "align the marker with the eraser": along the eraser's long side
    const std::optional<double> side = reader_.descriptor(target).longSideYaw;
    if (!side) failStep(step, target + " has no long side to align with (its footprint is square or round)");
    addFacingGoals(step, "", *side);
    return true;
  }
  addFacingGoals(step, target, 0.0);
  return true;
}

void StepParser::addFacingGoals(const Step& step, const std::string& target, double heading) {
  for (const std::string& object : step.objects) {
    Goal goal;
    goal.kind = GoalKind::kFacing;
    goal.object = object;
    goal.target = target;
    if (target.empty()) goal.angle = heading;
    specification_.goals.push_back(goal);
  }
}

void StepParser::parsePoint(Step& step) {
  parseObjects(step);
  if (!parsePointing(step, false)) failStep(step, "say what to " + step.verb.lemma + " it at (\"at the holder\")");
}

void StepParser::parseSwap(Step& step) {
  static const std::vector<Words> placesOf =
      phrasesOf({"the positions of", "the places of", "the spots of", "the locations of", "the position of", "the place of",
                 "places of", "positions of", "places between", "places with"});
  step.at += longestPhraseAt(step.words, step.at, placesOf);
  std::vector<NounPhrase> list = reader_.readList(step.words, step.at);
  if (list.empty()) failStep(step, "expected the two objects to " + step.verb.lemma);
  step.at = list.back().end;
  if (list.size() == 1 && (step.next("with") || step.next("and"))) {
    const std::optional<NounPhrase> other = reader_.read(step.words, step.at + 1);
    if (!other) failStep(step, "expected the object to " + step.verb.lemma + " it with");
    list.push_back(*other);
    step.at = other->end;
  }
  static const std::vector<Words> trailing = phrasesOf({"around", "round", "over", "places", "positions", "spots", "their places",
                                                        "their positions", "places with each other", "with each other"});
  step.at += longestPhraseAt(step.words, step.at, trailing);
  std::vector<std::string> objects;
  for (const NounPhrase& phrase : list) {
    for (const std::string& name : reader_.ground(phrase, discourse_, false, {})) {
      if (!containsWord(objects, name)) objects.push_back(name);
    }
  }
  if (objects.size() != 2) failStep(step, "a swap exchanges the places of exactly two objects, not " + std::to_string(objects.size()));
  step.objects = objects;
  addPlaceGoal(objects[0], objects[1]);
  addPlaceGoal(objects[1], objects[0]);
}

void StepParser::parseFill(Step& step) {
  const std::optional<NounPhrase> container = reader_.read(step.words, step.at);
  if (!container) failStep(step, "expected what to fill");
  step.at = container->end;
  const std::string target = groundTarget(step, *container, true);
  if (!step.next("with")) failStep(step, "say what to fill " + target + " with (\"with the marker\")");
  ++step.at;
  const std::vector<NounPhrase> list = reader_.readList(step.words, step.at);
  if (list.empty()) failStep(step, "expected the object(s) to fill " + target + " with");
  step.at = list.back().end;
  for (const NounPhrase& phrase : list) {
    for (const std::string& name : reader_.ground(phrase, discourse_, false, {}, false, {target})) {
      if (!containsWord(step.objects, name)) step.objects.push_back(name);
    }
  }
  addRelationGoals(step, RelationSpec{SpatialRelation::kIn, target, std::nullopt});
}

void StepParser::parseReplace(Step& step) {
  parseObjects(step);
  if (step.objects.size() != 1) failStep(step, "one object at a time can be replaced");
  if (!step.next("with") && !step.next("by")) failStep(step, "say what to replace it with (\"with the eraser\")");
  const std::optional<NounPhrase> phrase = reader_.read(step.words, step.at + 1);
  if (!phrase) failStep(step, "expected the object to replace it with");
  step.at = phrase->end;
  const std::string replaced = step.objects.front();
  const std::string replacement = groundTarget(step, *phrase, false);
  addPlaceGoal(replacement, replaced);
  step.objects = {replacement};
}

bool StepParser::parseWhereStands(Step& step) {
  static const std::vector<Words> before =
      phrasesOf({"where", "to where", "into where", "over to where", "back to where", "in the place of", "in place of",
                 "to the place of", "at the place of", "into the place of", "in the position of", "to the position of",
                 "at the position of", "into the position of", "in the spot of", "to the spot of", "on the spot of",
                 "at the spot of", "to the location of", "at the location of", "in the location of", "to the spot where",
                 "to the place where", "to the position where", "in the spot where", "in the place where", "at the spot where",
                 "at the place where", "at the position where", "into the spot where", "on the spot where", "onto the spot where"});
  static const std::vector<Words> being = phrasesOf({"is", "stands", "was", "stood", "sits", "sat", "lies", "lay", "is standing",
                                                     "is now", "is right now", "currently is", "is currently", "used to be",
                                                     "is sitting", "is lying", "is placed", "is located"});
  const std::size_t length = longestPhraseAt(step.words, step.at, before);
  if (length == 0) return parsePossessivePlace(step);
  const std::optional<NounPhrase> phrase = reader_.read(step.words, step.at + length);
  if (!phrase) failStep(step, "expected the object whose place to take");
  step.at = phrase->end + longestPhraseAt(step.words, phrase->end, being);
  const std::string owner = groundTarget(step, *phrase, false);
  if (step.objects.size() != 1) failStep(step, "only one object can stand where " + owner + " stands");
  addPlaceGoal(step.objects.front(), owner);
  return true;
}

bool StepParser::parsePutBack(Step& step) {
  static const std::vector<Words> back = phrasesOf(
      {"back", "back down", "back where it was", "back down where it was", "down where it was", "where it was", "back where it came from",
       "back in its place", "back to its place", "back in place", "back into place", "back to where it was", "back to its spot",
       "back to its position", "back where they were", "back down where they were", "where they were", "back in their places",
       "back to their places", "down again", "back down again", "back where it started", "back to where it started"});
  const std::size_t length = longestPhraseAt(step.words, step.at, back);
  if (length == 0 || step.at + length != step.words.size()) return false;
  step.at += length;
  for (const std::string& object : step.objects) {
    const ObjectDescriptor& descriptor = reader_.descriptor(object);
    Goal goal;
    goal.kind = GoalKind::kAtPosition;
    goal.object = object;
    goal.position = descriptor.origin;
    specification_.goals.push_back(goal);
  }
  return true;
}

bool StepParser::parseBetween(Step& step) {
  static const std::vector<Words> between = phrasesOf({"between", "in between", "halfway between", "midway between", "in the middle between"});
  static const std::vector<Words> halfway = phrasesOf({"halfway to", "halfway towards", "halfway toward", "half way to", "half way towards",
                                                       "midway to", "midway towards", "half the way to"});
  const std::size_t towards = longestPhraseAt(step.words, step.at, halfway);
  const std::size_t length = towards > 0 ? towards : longestPhraseAt(step.words, step.at, between);
  if (length == 0) return false;
  const std::vector<NounPhrase> list = reader_.readList(step.words, step.at + length);
  std::vector<std::string> ends;
  for (const NounPhrase& phrase : list) {
    for (const std::string& name : reader_.ground(phrase, discourse_, true, step.objects)) {
      if (!containsWord(ends, name)) ends.push_back(name);
    }
  }
  const char* what = towards > 0 ? "\"halfway to\" needs one object" : "\"between\" needs two objects";
  if (ends.size() != (towards > 0 ? 1u : 2u)) failStep(step, std::string(what) + ", got " + std::to_string(ends.size()));
  if (std::any_of(ends.begin(), ends.end(), [&](const std::string& end) { return containsWord(step.objects, end); })) {
    failStep(step, towards > 0 ? "an object cannot go halfway to itself" : "an object cannot go between itself and another");
  }
  if (step.objects.size() != 1) {
    failStep(step, towards > 0 ? "one object at a time goes halfway to " + ends[0] : "only one object fits between " + ends[0] + " and " + ends[1]);
  }
  step.at = list.back().end;
  // "halfway to X": the middle of where the object stands and X, on the support it stands on.
  if (towards > 0) ends.insert(ends.begin(), step.objects.front());
  const ObjectDescriptor& mover = reader_.descriptor(step.objects.front());
  const ObjectDescriptor& a = reader_.descriptor(ends[0]);
  const ObjectDescriptor& b = reader_.descriptor(ends[1]);
  const Vector3 middle = (a.bounds.center() + b.bounds.center()) / 2.0;
  const double floor = towards > 0 ? mover.bounds.min().z() : std::min(a.bounds.min().z(), b.bounds.min().z());
  Goal goal;
  goal.kind = GoalKind::kAtPosition;
  goal.object = step.objects.front();
  goal.position = Vector3(mover.origin.x() + middle.x() - mover.bounds.center().x(), mover.origin.y() + middle.y() - mover.bounds.center().y(),
                          mover.origin.z() + floor - mover.bounds.min().z());
  specification_.goals.push_back(goal);
  return true;
}

bool StepParser::parsePossessivePlace(Step& step) {
  static const std::vector<Words> prepositions = phrasesOf({"to", "at", "in", "into", "on", "onto", "over to", "back to"});
  static const std::vector<std::string> places{"place", "position", "spot", "location", "old place", "former place"};
  const std::size_t preposition = longestPhraseAt(step.words, step.at, prepositions);
  if (preposition == 0) return false;
  // "the eraser's place": the phrase read with the possessive's "'s" dropped.
  Words plain = step.words;
  std::size_t owner = plain.size();
  for (std::size_t i = step.at + preposition; i < plain.size(); ++i) {
    const std::string& word = plain[i];
    if (word.size() > 2 && word.compare(word.size() - 2, 2, "'s") == 0) {
      plain[i] = word.substr(0, word.size() - 2);
      owner = i;
      break;
    }
  }
  if (owner + 1 >= plain.size()) return false;
  std::size_t placeLength = 0;
  for (const std::string& place : places) {
    const Words words = tokenize(place);
    if (matchesAt(plain, owner + 1, words)) placeLength = std::max(placeLength, words.size());
  }
  if (placeLength == 0) return false;
  const std::optional<NounPhrase> phrase = reader_.read(plain, step.at + preposition);
  if (!phrase || phrase->end != owner + 1) return false;
  const std::string name = groundTarget(step, *phrase, false);
  if (step.objects.size() != 1) failStep(step, "only one object can stand where " + name + " stands");
  step.at = owner + 1 + placeLength;
  addPlaceGoal(step.objects.front(), name);
  return true;
}

void StepParser::addPlaceGoal(const std::string& object, const std::string& owner) {
  if (object == owner) throwGroundingError(object, "cannot put " + object + " where it already stands");
  const ObjectDescriptor& mover = reader_.descriptor(object);
  const ObjectDescriptor& place = reader_.descriptor(owner);
  Goal goal;
  goal.kind = GoalKind::kAtPosition;
  goal.object = object;
  goal.target = owner;
  const Vector3 centre = place.bounds.center();
  goal.position = Vector3(mover.origin.x() + centre.x() - mover.bounds.center().x(),
                          mover.origin.y() + centre.y() - mover.bounds.center().y(),
                          mover.origin.z() + place.bounds.min().z() - mover.bounds.min().z());
  specification_.goals.push_back(goal);
}

}  // namespace lang2manip::language_detail
