#include "lang2manip/language/vocabulary.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"

#include <algorithm>
#include <set>
#include <utility>

namespace lang2manip::vocabulary {
namespace {

template <typename Value>
struct PhraseTable {
  std::vector<std::pair<Words, Value>> entries;

  PhraseTable(std::initializer_list<std::pair<const char*, Value>> list) {
    for (const auto& [phrase, value] : list) entries.emplace_back(tokenize(phrase), value);
  }

  /// The longest entry at words[at] and its length.
  std::optional<std::pair<Value, std::size_t>> match(const Words& words, std::size_t at) const {
    std::optional<std::pair<Value, std::size_t>> best;
    for (const auto& [phrase, value] : entries) {
      if (matchesAt(words, at, phrase) && (!best || phrase.size() > best->second)) {
        best = std::make_pair(value, phrase.size());
      }
    }
    return best;
  }
};

Verb makeVerb(const char* lemma, std::initializer_list<bool Verb::*> flags) {
  Verb verb;
  verb.lemma = lemma;
  for (bool Verb::*flag : flags) verb.*flag = true;
  return verb;
}

const PhraseTable<Verb>& verbTable() {
  using V = Verb;
  static const PhraseTable<Verb> table{
      {"put", makeVerb("put", {&V::places})},
      {"put down", makeVerb("put", {&V::places, &V::putsDown})},
      {"put back", makeVerb("put", {&V::places})},
      {"place", makeVerb("place", {&V::places})},
      {"place down", makeVerb("place", {&V::places, &V::putsDown})},
      {"set", makeVerb("set", {&V::places})},
      {"set down", makeVerb("set", {&V::places, &V::putsDown})},
      {"lay", makeVerb("lay", {&V::places})},
      {"lay down", makeVerb("lay", {&V::places, &V::putsDown})},
      {"drop", makeVerb("drop", {&V::places, &V::putsDown})},
      {"drop off", makeVerb("drop", {&V::places, &V::putsDown})},
      {"insert", makeVerb("insert", {&V::places})},
      {"position", makeVerb("position", {&V::places})},
      {"bring", makeVerb("bring", {&V::places})},
      {"transfer", makeVerb("transfer", {&V::places})},
      {"relocate", makeVerb("relocate", {&V::places})},
      {"carry", makeVerb("carry", {&V::places, &V::picks})},
      {"store", makeVerb("store", {&V::places})},
      {"stick", makeVerb("stick", {&V::places})},
      {"deposit", makeVerb("deposit", {&V::places})},
      {"move", makeVerb("move", {&V::places, &V::pushes, &V::goesHome})},
      {"return", makeVerb("return", {&V::places, &V::goesHome})},
      {"take", makeVerb("take", {&V::places, &V::picks})},
      {"get", makeVerb("get", {&V::places, &V::picks})},
      {"pick", makeVerb("pick up", {&V::places, &V::picks})},
      {"pick up", makeVerb("pick up", {&V::places, &V::picks})},
      {"grab", makeVerb("grab", {&V::places, &V::picks})},
      {"grasp", makeVerb("grasp", {&V::places, &V::picks})},
      {"lift", makeVerb("lift", {&V::places, &V::picks})},
      {"lift up", makeVerb("lift", {&V::places, &V::picks})},
      {"hold", makeVerb("hold", {&V::picks})},
      {"keep", makeVerb("keep", {&V::keeps})},
      {"hand", makeVerb("hand", {&V::handsOver})},
      {"hand over", makeVerb("hand", {&V::handsOver})},
      {"give", makeVerb("give", {&V::handsOver})},
      {"pass", makeVerb("pass", {&V::handsOver})},
      {"leave", makeVerb("leave", {&V::keeps})},
      {"fetch", makeVerb("fetch", {&V::places, &V::picks})},
      {"seize", makeVerb("seize", {&V::picks})},
      {"push", makeVerb("push", {&V::pushes, &V::places})},
      {"slide", makeVerb("slide", {&V::pushes, &V::places})},
      {"shove", makeVerb("shove", {&V::pushes, &V::places})},
      {"shift", makeVerb("shift", {&V::pushes, &V::places})},
      {"nudge", makeVerb("nudge", {&V::pushes, &V::nudges})},
      {"stack", makeVerb("stack", {&V::places, &V::stacks})},
      {"make a tower of", makeVerb("stack", {&V::places, &V::stacks})},
      {"make a tower with", makeVerb("stack", {&V::places, &V::stacks})},
      {"make a tower from", makeVerb("stack", {&V::places, &V::stacks})},
      {"make a tower out of", makeVerb("stack", {&V::places, &V::stacks})},
      {"build a tower of", makeVerb("stack", {&V::places, &V::stacks})},
      {"build a tower with", makeVerb("stack", {&V::places, &V::stacks})},
      {"build a tower from", makeVerb("stack", {&V::places, &V::stacks})},
      {"build a tower out of", makeVerb("stack", {&V::places, &V::stacks})},
      {"form a tower of", makeVerb("stack", {&V::places, &V::stacks})},
      {"form a tower with", makeVerb("stack", {&V::places, &V::stacks})},
      {"make a stack of", makeVerb("stack", {&V::places, &V::stacks})},
      {"make a stack with", makeVerb("stack", {&V::places, &V::stacks})},
      {"build a stack of", makeVerb("stack", {&V::places, &V::stacks})},
      {"build a stack with", makeVerb("stack", {&V::places, &V::stacks})},
      {"make a pile of", makeVerb("stack", {&V::places, &V::stacks})},
      {"build a pile of", makeVerb("stack", {&V::places, &V::stacks})},
      {"stack up", makeVerb("stack", {&V::places, &V::stacks})},
      {"pile", makeVerb("stack", {&V::places, &V::stacks})},
      {"pile up", makeVerb("stack", {&V::places, &V::stacks})},
      {"sort", makeVerb("sort", {&V::places})},
      {"sort out", makeVerb("sort", {&V::places})},
      {"arrange", makeVerb("arrange", {&V::places})},
      {"lay out", makeVerb("lay out", {&V::places})},
      {"pack", makeVerb("pack", {&V::places})},
      {"swap", makeVerb("swap", {&V::swaps})},
      {"swap around", makeVerb("swap", {&V::swaps})},
      {"exchange", makeVerb("exchange", {&V::swaps})},
      {"switch", makeVerb("switch", {&V::swaps})},
      {"switch around", makeVerb("switch", {&V::swaps})},
      {"interchange", makeVerb("interchange", {&V::swaps})},
      {"trade", makeVerb("trade", {&V::swaps})},
      {"turn", makeVerb("turn", {&V::turns})},
      {"rotate", makeVerb("rotate", {&V::turns})},
      {"spin", makeVerb("spin", {&V::turns})},
      {"twist", makeVerb("twist", {&V::turns})},
      {"point", makeVerb("point", {&V::points})},
      {"orient", makeVerb("orient", {&V::points})},
      {"orientate", makeVerb("orient", {&V::points})},
      {"aim", makeVerb("aim", {&V::points})},
      {"direct", makeVerb("direct", {&V::points})},
      {"align", makeVerb("align", {&V::points})},
      {"line up", makeVerb("align", {&V::points})},
      {"replace", makeVerb("replace", {&V::replaces})},
      {"lower", makeVerb("lower", {&V::places})},
      {"load", makeVerb("load", {&V::places})},
      {"collect", makeVerb("collect", {&V::places})},
      {"gather", makeVerb("gather", {&V::places})},
      {"put away", makeVerb("put", {&V::places})},
      {"fill", makeVerb("fill", {&V::fills})},
      {"tidy", makeVerb("tidy", {&V::summarizes})},
      {"tidy up", makeVerb("tidy", {&V::summarizes})},
      {"clean up", makeVerb("clean", {&V::summarizes})},
      {"clear", makeVerb("clear", {&V::summarizes})},
      {"clear up", makeVerb("clear", {&V::summarizes})},
      {"organize", makeVerb("organize", {&V::summarizes})},
      {"organise", makeVerb("organize", {&V::summarizes})},
      {"go", makeVerb("go", {&V::goesHome})},
      {"head", makeVerb("head", {&V::goesHome})},
      {"come", makeVerb("come", {&V::goesHome})},
  };
  return table;
}

struct RelationValue {
  std::optional<SpatialRelation> relation;
  bool byTargetRole = false;
};

const PhraseTable<RelationValue>& relationTable() {
  using R = SpatialRelation;
  static const PhraseTable<RelationValue> table{
      {"in", {R::kIn}}, {"into", {R::kIn}}, {"in to", {R::kIn}}, {"inside", {R::kIn}},
      {"inside of", {R::kIn}}, {"within", {R::kIn}},
      {"on", {R::kOn}}, {"onto", {R::kOn}}, {"on to", {R::kOn}}, {"on top of", {R::kOn}},
      {"upon", {R::kOn}}, {"atop", {R::kOn}}, {"on the top of", {R::kOn}},
      {"next to", {R::kNextTo}}, {"beside", {R::kNextTo}}, {"besides", {R::kNextTo}},
      {"by", {R::kNextTo}}, {"near", {R::kNextTo}}, {"close to", {R::kNextTo}},
      {"alongside", {R::kNextTo}}, {"closer to", {R::kNextTo}}, {"nearer to", {R::kNextTo}}, {"by the side of", {R::kNextTo}},
      {"away from", {R::kNextTo}},
      {"left of", {R::kLeftOf}}, {"to the left of", {R::kLeftOf}},
      {"on the left of", {R::kLeftOf}}, {"on the left side of", {R::kLeftOf}},
      {"to the left side of", {R::kLeftOf}}, {"at the left of", {R::kLeftOf}},
      {"right of", {R::kRightOf}}, {"to the right of", {R::kRightOf}},
      {"on the right of", {R::kRightOf}}, {"on the right side of", {R::kRightOf}},
      {"to the right side of", {R::kRightOf}}, {"at the right of", {R::kRightOf}},
      {"in front of", {R::kInFrontOf}}, {"to the front of", {R::kInFrontOf}},
      {"at the front of", {R::kInFrontOf}},
      {"behind", {R::kBehind}}, {"in back of", {R::kBehind}}, {"at the back of", {R::kBehind}},
      {"to the back of", {R::kBehind}},
      {"to the top of", {R::kInFrontOf}}, {"toward the top of", {R::kInFrontOf}}, {"towards the top of", {R::kInFrontOf}},
      {"to the bottom of", {R::kBehind}}, {"toward the bottom of", {R::kBehind}}, {"towards the bottom of", {R::kBehind}},
      {"to the top side of", {R::kInFrontOf}}, {"to the bottom side of", {R::kBehind}},
      {"to", {std::nullopt, true}}, {"over to", {std::nullopt, true}},
  };
  return table;
}

const PhraseTable<Vector3>& directionTable() {
  static const Vector3 left(0, 1, 0), right(0, -1, 0), forward(1, 0, 0), back(-1, 0, 0);
  static const PhraseTable<Vector3> table{
      {"left", left}, {"to the left", left}, {"leftward", left}, {"leftwards", left},
      {"towards the left", left}, {"toward the left", left},
      {"right", right}, {"to the right", right}, {"rightward", right}, {"rightwards", right},
      {"towards the right", right}, {"toward the right", right},
      {"forward", forward}, {"forwards", forward}, {"ahead", forward}, {"away", forward},
      {"to the front", forward}, {"further away", forward}, {"farther away", forward},
      {"away from the robot", forward}, {"away from you", forward}, {"away from me", forward},
      {"back", back}, {"backward", back}, {"backwards", back}, {"to the back", back},
      {"towards the robot", back}, {"toward the robot", back}, {"towards you", back},
      {"toward you", back}, {"towards me", back}, {"toward me", back}, {"closer", back},
  };
  return table;
}

const PhraseTable<double>& unitTable() {
  static const PhraseTable<double> table{
      {"cm", 0.01},  {"cms", 0.01},  {"centimeter", 0.01}, {"centimeters", 0.01},
      {"centimetre", 0.01}, {"centimetres", 0.01},
      {"mm", 0.001}, {"millimeter", 0.001}, {"millimeters", 0.001}, {"millimetre", 0.001},
      {"millimetres", 0.001},
      {"m", 1.0},    {"meter", 1.0}, {"meters", 1.0}, {"metre", 1.0}, {"metres", 1.0},
      {"inch", 0.0254}, {"inches", 0.0254},
  };
  return table;
}

const PhraseTable<bool>& smallAmountTable() {
  static const PhraseTable<bool> table{
      {"a bit", true}, {"a little", true}, {"a little bit", true}, {"slightly", true},
      {"a tiny bit", true}, {"just a bit", true},
  };
  return table;
}

const PhraseTable<bool>& fillerTable() {
  static const PhraseTable<bool> table{
      {"please", true}, {"kindly", true}, {"could you", true}, {"could you please", true},
      {"can you", true}, {"can you please", true}, {"would you", true},
      {"would you please", true}, {"would you kindly", true}, {"will you", true},
      {"i'd like you to", true}, {"i would like you to", true}, {"i want you to", true},
      {"i need you to", true}, {"i'd like to", true}, {"go ahead and", true},
      {"make sure to", true}, {"try to", true}, {"let's", true}, {"lets", true},
      {"now", true}, {"just", true}, {"carefully", true}, {"gently", true}, {"slowly", true},
      {"quickly", true}, {"also", true}, {"too", true}, {"as well", true}, {"for me", true},
      {"thanks", true}, {"thank you", true}, {"ok", true}, {"okay", true}, {"hey", true},
      {"hi", true}, {"hello", true}, {"hey robot", true}, {"ok robot", true},
      {"you should", true}, {"pls", true}, {"plz", true}, {"plse", true}, {"could u", true}, {"can u", true},
      {"would u", true}, {"could u pls", true}, {"can u pls", true}, {"could you pls", true}, {"thx", true}, {"ty", true},
      {"kindly please", true}, {"if you can", true}, {"if possible", true}, {"when you can", true},
  };
  return table;
}

const PhraseTable<bool>& sequenceTable() {
  static const PhraseTable<bool> table{
      {"then", true}, {"and then", true}, {"after that", true}, {"and after that", true},
      {"afterwards", true}, {"and afterwards", true}, {"after this", true},
      {"finally", true}, {"and finally", true}, {"lastly", true}, {"and lastly", true},
      {"once done", true}, {"when done", true}, {"once that's done", true},
  };
  return table;
}

const PhraseTable<bool>& stepOrdinalTable() {
  static const PhraseTable<bool> table{
      {"first", true}, {"firstly", true}, {"first of all", true}, {"to begin", true},
      {"next", true}, {"second", true}, {"secondly", true}, {"third", true}, {"thirdly", true},
      {"to start", true},
  };
  return table;
}

const PhraseTable<bool>& homeTable() {
  static const PhraseTable<bool> table{
      {"home", true}, {"back home", true}, {"to home", true}, {"back to home", true},
      {"to the home position", true}, {"back to the home position", true},
      {"to its home position", true}, {"back to its home position", true},
      {"to your home position", true}, {"back to your home position", true},
      {"to the home pose", true}, {"back to the home pose", true},
      {"to the home configuration", true}, {"back to the home configuration", true},
      {"to home position", true}, {"to home configuration", true}, {"to the home", true},
      {"home position", true}, {"home pose", true}, {"home configuration", true},
  };
  return table;
}

const PhraseTable<bool>& robotTable() {
  static const PhraseTable<bool> table{
      {"the arm", true}, {"the robot", true}, {"yourself", true}, {"your arm", true},
      {"the gripper", true}, {"the robot arm", true}, {"your gripper", true}, {"it", true},
  };
  return table;
}

template <typename Value>
std::optional<std::size_t> lengthOf(const PhraseTable<Value>& table, const Words& words,
                                    std::size_t at) {
  if (auto match = table.match(words, at)) return match->second;
  return std::nullopt;
}

}  // namespace

std::optional<VerbMatch> matchVerb(const Words& words, std::size_t at) {
  if (auto match = verbTable().match(words, at)) return VerbMatch{match->first, match->second};
  return std::nullopt;
}

std::vector<std::string> verbLemmas() {
  std::vector<std::string> lemmas;
  for (const auto& entry : verbTable().entries) {
    if (std::find(lemmas.begin(), lemmas.end(), entry.second.lemma) == lemmas.end()) {
      lemmas.push_back(entry.second.lemma);
    }
  }
  return lemmas;
}

std::optional<RelationMatch> matchRelation(const Words& words, std::size_t at) {
  if (auto match = relationTable().match(words, at)) {
    return RelationMatch{match->first.relation, match->first.byTargetRole, match->second};
  }
  return std::nullopt;
}

std::optional<DirectionMatch> matchDirection(const Words& words, std::size_t at) {
  if (auto match = directionTable().match(words, at)) {
    return DirectionMatch{match->first, match->second};
  }
  return std::nullopt;
}

std::optional<MagnitudeMatch> matchMagnitude(const Words& words, std::size_t at) {
  static const std::vector<Words> little{{"a", "little"}, {"a", "little", "bit"}, {"a", "bit"}, {"slightly"}, {"a", "tad"},
                                         {"just"}, {"a", "touch"}, {"somewhat"}, {"barely"}, {"a", "few", "centimetres"},
                                         {"a", "few", "centimeters"}, {"a", "few", "cm"}};
  static const std::vector<Words> lot{{"a", "lot"}, {"far"}, {"well"}, {"way"}, {"a", "long", "way"}, {"much", "further"},
                                      {"a", "good", "distance"}, {"far", "off"}, {"quite", "far"}, {"very", "far"}};
  const SpatialOptions spatial;
  if (const std::size_t length = longestPhraseAt(words, at, little)) return MagnitudeMatch{spatial.littleGap, length};
  if (const std::size_t length = longestPhraseAt(words, at, lot)) return MagnitudeMatch{spatial.lotGap, length};
  return std::nullopt;
}

std::size_t matchApproximation(const Words& words, std::size_t at) {
  static const std::vector<std::string> words_{"about", "around", "roughly", "approximately", "approx", "some", "~", "circa", "nearly", "almost"};
  if (at + 1 >= words.size() || !numberValue(words[at + 1])) return 0;
  return std::find(words_.begin(), words_.end(), words[at]) != words_.end() ? 1 : 0;
}

std::optional<LengthMatch> matchLength(const Words& words, std::size_t at) {
  const std::size_t approximately = matchApproximation(words, at);
  at += approximately;
  if (at >= words.size()) return std::nullopt;
  const std::optional<double> number = numberValue(words[at]);
  if (!number) return std::nullopt;
  const auto unit = unitTable().match(words, at + 1);
  if (!unit) return std::nullopt;
  return LengthMatch{*number * unit->first, approximately + 1 + unit->second};
}

std::optional<std::size_t> matchSmallAmount(const Words& words, std::size_t at) {
  return lengthOf(smallAmountTable(), words, at);
}

std::optional<std::size_t> matchFiller(const Words& words, std::size_t at) {
  // "as well as" joins a list; only "as well" on its own is filler.
  if (matchesAt(words, at, {"as", "well", "as"})) return std::nullopt;
  return lengthOf(fillerTable(), words, at);
}

std::optional<std::size_t> matchSequenceWord(const Words& words, std::size_t at) {
  return lengthOf(sequenceTable(), words, at);
}

std::optional<std::size_t> matchStepOrdinal(const Words& words, std::size_t at) {
  if (matchesAt(words, at, {"next", "to"})) return std::nullopt;
  return lengthOf(stepOrdinalTable(), words, at);
}

bool isRefusedWord(const std::string& word) {
  static const std::vector<std::string> refused{
      "don't", "dont", "not", "never", "without", "except", "unless", "if", "but", "no",
      "nothing", "avoid", "excluding", "instead", "or", "either", "whether"};
  return std::find(refused.begin(), refused.end(), word) != refused.end();
}

bool isQuestionWord(const std::string& word) {
  static const std::vector<std::string> questions{
      "what", "where", "which", "why", "how", "who", "whose", "is", "are", "does", "did"};
  return std::find(questions.begin(), questions.end(), word) != questions.end();
}

std::optional<std::size_t> matchHome(const Words& words, std::size_t at) {
  std::size_t position = at;
  if (auto robot = lengthOf(robotTable(), words, position)) position += *robot;
  if (auto home = lengthOf(homeTable(), words, position)) return position + *home - at;
  return std::nullopt;
}

std::set<std::string> knownWords() {
  std::set<std::string> words;
  const auto add = [&words](const auto& table) {
    for (const auto& entry : table.entries) words.insert(entry.first.begin(), entry.first.end());
  };
  add(verbTable());
  add(relationTable());
  add(directionTable());
  add(unitTable());
  add(smallAmountTable());
  add(fillerTable());
  add(sequenceTable());
  add(stepOrdinalTable());
  add(homeTable());
  add(robotTable());
  return words;
}

std::vector<std::string> verbWords() {
  std::set<std::string> words;
  for (const auto& entry : verbTable().entries) words.insert(entry.first.begin(), entry.first.end());
  return {words.begin(), words.end()};
}

}  // namespace lang2manip::vocabulary
