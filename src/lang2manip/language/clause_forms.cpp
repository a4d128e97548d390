// StepParser: steps said in other forms (subject first, wishes, causatives; handing to a person
// by a placing verb), displacements ("5 cm to the left", "3 cm toward the holder"), clauses with
// their own placement, rejected alternatives ("instead of ...") and where a target stands.

#include <algorithm>

#include "lang2manip/language/clause_parser.hpp"
#include "lang2manip/language/region_phrases.hpp"
#include "lang2manip/language/clause_step.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip::language_detail {

std::optional<Words> StepParser::inVerbFirstOrder(const Words& words) const {
  static const std::vector<Words> causatives{{"make"}, {"have"}, {"let"}};
  static const std::vector<Words> wishes{{"i", "want"}, {"i'd", "like"}, {"i", "would", "like"}, {"we", "want"}, {"i", "need"},
                                         {"we", "need"}, {"i'd", "love"}, {"i", "wish"}};
  static const std::vector<Words> placedVerbs{{"go"}, {"goes"}, {"belong"}, {"belongs"}, {"should", "be"}, {"should", "go"},
                                              {"must", "be"}, {"must", "go"}, {"needs", "to", "be"}, {"need", "to", "be"},
                                              {"has", "to", "be"}, {"have", "to", "be"}, {"should", "end", "up"}, {"end", "up"}};
  const auto join = [&words](const Words& verb, std::size_t from, std::size_t to, std::size_t rest) {
    Words rewritten = verb;
    rewritten.insert(rewritten.end(), words.begin() + static_cast<std::ptrdiff_t>(from), words.begin() + static_cast<std::ptrdiff_t>(to));
    rewritten.insert(rewritten.end(), words.begin() + static_cast<std::ptrdiff_t>(rest), words.end());
    return rewritten;
  };
  for (std::size_t by = 1; by + 1 < words.size(); ++by) {  // "clear the desk by putting everything in the holder"
    const std::string& gerund = words[by + 1];
    if (words[by] != "by" || gerund.size() < 5 || gerund.compare(gerund.size() - 3, 3, "ing") != 0) continue;
    const std::string base = gerund.substr(0, gerund.size() - 3);
    for (const std::string& stem : {base, base + "e", base.size() > 2 && base[base.size() - 1] == base[base.size() - 2] ? base.substr(0, base.size() - 1) : base}) {
      if (vocabulary::matchVerb(Words{stem}, 0)) return join(Words{stem}, by + 2, by + 2, by + 2);
    }
  }
  if (std::optional<Words> shape = inArrangementOrder(words)) return shape;
  std::size_t subject = longestPhraseAt(words, 0, causatives);  // "make the marker point at the holder"
  const std::size_t wish = subject == 0 ? longestPhraseAt(words, 0, wishes) : 0;  // "I want the marker in the holder"
  subject += wish;
  const std::vector<NounPhrase> list = reader_.readList(words, subject);
  if (list.empty() || (subject == 0 && vocabulary::matchVerb(words, 0))) return std::nullopt;
  std::size_t end = list.back().end;
  if (wish > 0 && matchesAt(words, end, {"to", "be"})) return join({"put"}, subject, end, end + 2);
  if (wish > 0) return end == words.size() ? join({"hand", "me"}, subject, end, end) : join({"put"}, subject, end, end);
  if (const std::size_t placed = longestPhraseAt(words, end, placedVerbs)) return join({"put"}, subject, end, end + placed);
  if (const auto verb = vocabulary::matchVerb(words, end)) {  // "the marker and the eraser trade places"
    const Words verbWords(words.begin() + static_cast<std::ptrdiff_t>(end), words.begin() + static_cast<std::ptrdiff_t>(end + verb->length));
    return join(verbWords, subject, end, end + verb->length);
  }
  return std::nullopt;
}

std::optional<Words> StepParser::inArrangementOrder(const Words& words) const {
  static const std::vector<Words> verbs{{"make"}, {"form"}, {"build"}, {"create"}, {"arrange"}, {"lay", "out"}, {"set", "up"}, {"put"}};
  static const std::vector<Words> materials{{"with"}, {"of"}, {"from"}, {"out", "of"}, {"using"}};
  if (std::optional<Words> spread = spreadOrLinedUp(words)) return spread;
  const std::size_t verb = longestPhraseAt(words, 0, verbs);
  const std::size_t into = verb > 0 && matchesAt(words, verb, {"into"}) ? 1 : 0;  // "arrange into a circle the blocks"
  const std::optional<ShapePhrase> shape = verb > 0 ? matchShapePhrase(words, verb + into) : std::nullopt;
  if (!shape) return std::nullopt;
  const std::size_t shapeEnd = verb + into + shape->length;
  const std::size_t material = longestPhraseAt(words, shapeEnd, materials);
  const std::vector<NounPhrase> list = material > 0 ? reader_.readList(words, shapeEnd + material) : std::vector<NounPhrase>{};
  if (list.empty()) return std::nullopt;
  Words rewritten{"put"};
  rewritten.insert(rewritten.end(), words.begin() + static_cast<std::ptrdiff_t>(shapeEnd + material), words.begin() + static_cast<std::ptrdiff_t>(list.back().end));
  rewritten.emplace_back("in");
  rewritten.insert(rewritten.end(), words.begin() + static_cast<std::ptrdiff_t>(verb + into), words.begin() + static_cast<std::ptrdiff_t>(shapeEnd));
  rewritten.insert(rewritten.end(), words.begin() + static_cast<std::ptrdiff_t>(list.back().end), words.end());
  return rewritten;
}

std::optional<Words> StepParser::spreadOrLinedUp(const Words& words) const {
  static const std::vector<Words> spreadVerbs{{"spread"}, {"spread", "out"}, {"space"}, {"space", "out"}, {"scatter"}, {"distribute"}};
  static const std::vector<Words> lineVerbs{{"line"}, {"line", "up"}};
  static const std::vector<Words> groupVerbs{{"group"}, {"gather"}, {"cluster"}, {"bunch"}, {"collect"}, {"bring", "together"},
                                             {"push", "together"}, {"move", "together"}};
  static const std::vector<Words> sideBySide{{"side", "by", "side"}, {"next", "to", "each", "other"}, {"next", "to", "one", "another"}};
  const std::size_t spread = longestPhraseAt(words, 0, spreadVerbs);
  const std::size_t group = spread > 0 ? 0 : longestPhraseAt(words, 0, groupVerbs);
  const std::size_t verb = spread > 0 ? spread : group > 0 ? group : longestPhraseAt(words, 0, lineVerbs);
  const std::vector<NounPhrase> list = verb > 0 ? reader_.readList(words, verb) : std::vector<NounPhrase>{};
  if (list.empty()) return std::nullopt;
  std::size_t rest = list.back().end;
  if (matchesAt(words, rest, {"out"}) || matchesAt(words, rest, {"up"})) ++rest;  // "spread the blocks out", "line them up"
  Words rewritten{"put"};
  rewritten.insert(rewritten.end(), words.begin() + static_cast<std::ptrdiff_t>(verb), words.begin() + static_cast<std::ptrdiff_t>(list.back().end));
  const auto append = [&](std::initializer_list<const char*> added, std::size_t from) {
    for (const char* word : added) rewritten.emplace_back(word);
    rewritten.insert(rewritten.end(), words.begin() + static_cast<std::ptrdiff_t>(from), words.end());
    return rewritten;
  };
  if (spread > 0) return append({"spread", "out"}, rest);
  if (group > 0) {  // "gather the blocks (together, up)": next to each other; "gather X in the bowl" puts them there
    const bool together = matchesAt(words, list.back().end, {"together"});
    const std::size_t regionWords = regionPreposition(words, rest);
    const bool inRegion = regionWords > 0 && matchRegionPhrase(words, rest + regionWords);
    if (together || inRegion || rest == words.size() || matchesAt(words, rest, {"on"})) {
      return append({"together"}, together ? list.back().end + 1 : rest);
    }
    return std::nullopt;
  }
  if (const std::size_t side = longestPhraseAt(words, rest, sideBySide)) return append({"in", "a", "line"}, rest + side);
  // "line up the blocks (along the front edge, horizontally, in a column)"; "line up X with Y" points.
  if (rest == words.size() || matchesAt(words, rest, {"along"})) return append({"in", "a", "line"}, rest);
  if (matchesAt(words, rest, {"horizontally"})) return append({"in", "a", "horizontal", "line"}, rest + 1);
  if (matchesAt(words, rest, {"vertically"})) return append({"in", "a", "vertical", "line"}, rest + 1);
  if ((matchesAt(words, rest, {"in"}) || matchesAt(words, rest, {"into"})) && matchShapePhrase(words, rest + 1)) return append({}, rest);
  return std::nullopt;
}

bool StepParser::handsToPerson(const Step& step) const {
  static const std::vector<Words> endings{{"to", "me"}, {"over", "to", "me"}, {"to", "us"}, {"over", "to", "us"}, {"to", "the", "user"},
                                          {"to", "the", "person"}, {"to", "the", "human"}, {"to", "the", "operator"}, {"over", "here"}};
  const Words& words = step.words;
  if (step.next("me") || step.next("us")) return true;  // "bring me the marker"
  for (const Words& ending : endings) {
    if (words.size() >= ending.size() && matchesAt(words, words.size() - ending.size(), ending)) return true;
  }
  return false;
}

bool StepParser::parseDisplacement(Step& step) {
  const Words& words = step.words;
  std::size_t at = step.at;
  if (words.size() > at && words[at] == "by") ++at;
  std::optional<double> distance;
  if (auto length = vocabulary::matchLength(words, at)) {
    distance = length->metres;
    at += length->length;
  } else if (auto small = vocabulary::matchSmallAmount(words, at)) {
    distance = vocabulary::kSmallAmount;
    at += *small;
  }
  std::optional<vocabulary::DirectionMatch> direction;
  std::string reference;  // "3 cm toward the holder": along the line to another object
  bool away = false;
  if (distance) {
    static const std::vector<Words> toward{{"toward"}, {"towards"}, {"closer", "to"}, {"nearer", "to"}, {"in", "the", "direction", "of"}};
    static const std::vector<Words> from{{"away", "from"}, {"further", "from"}, {"farther", "from"}};
    std::size_t length = 0;
    for (const Words& phrase : toward) length = matchesAt(words, at, phrase) ? std::max(length, phrase.size()) : length;
    for (const Words& phrase : from) {
      if (matchesAt(words, at, phrase) && phrase.size() > length) length = phrase.size(), away = true;
    }
    const std::optional<NounPhrase> target = length > 0 ? reader_.read(words, at + length) : std::nullopt;
    if (target && target->pronoun == Pronoun::kNone && !matchesAt(words, at + length, {"the", "robot"}) &&
        !matchesAt(words, at + length, {"you"})) {
      reference = groundTarget(step, *target, false);
      direction = vocabulary::DirectionMatch{Vector3::Zero(), target->end - at};
    }
  }
  if (!direction) direction = vocabulary::matchDirection(words, at);
  if (!direction) return false;
  at += direction->length;
  if (!distance) {
    std::size_t after = at;
    if (words.size() > after && words[after] == "by") ++after;
    if (auto length = vocabulary::matchLength(words, after)) {
      distance = length->metres;
      at = after + length->length;
    } else if (auto small = vocabulary::matchSmallAmount(words, after)) {
      distance = vocabulary::kSmallAmount;
      at = after + *small;
    } else if (step.verb.nudges) {
      distance = vocabulary::kSmallAmount;
    }
  }
  if (words.size() > at + 1 && words[at] == ",") {  // "a bit to the left, about 4 cm": the amount said again
    if (auto restated = vocabulary::matchLength(words, at + 1)) {
      distance = restated->metres;
      at += 1 + restated->length;
    }
  }
  if (!distance) {
    throwGroundingError(joinWords(words, 0, at),
                        "say how far (e.g. \"5 cm " + joinWords(words, at - direction->length, at) +
                            "\")");
  }
  if (!step.verb.pushes && !step.verb.places) {
    failStep(step, "\"" + step.verb.lemma + "\" cannot move an object by a distance");
  }
  step.at = at;
  for (const std::string& object : step.objects) {
    Goal goal;
    goal.kind = GoalKind::kDisplaced;
    goal.object = object;
    goal.displacement = direction->direction * *distance;
    if (!reference.empty()) {
      Vector3 line = reader_.descriptor(reference).position - reader_.descriptor(object).position;
      line.z() = 0.0;
      if (line.norm() < 1e-6) failStep(step, object + " and " + reference + " stand at the same place: no direction between them");
      goal.displacement = line.normalized() * *distance * (away ? -1.0 : 1.0);
    }
    specification_.goals.push_back(goal);
  }
  return true;
}

void StepParser::parseGappedPlacements(Step& step) {
  // "put the marker where the eraser is and the eraser where the marker was"
  while (step.next("and") || step.next(",")) {
    const std::size_t restart = step.at;
    std::size_t at = step.at + 1;
    if (matchesAt(step.words, at, {"and"})) ++at;
    const std::vector<NounPhrase> list = reader_.readList(step.words, at);
    if (list.empty()) return;
    const std::vector<std::string> previous = step.objects;
    step.at = list.back().end;
    clauseBefore_ = previous;
    clauseStart_ = specification_.goals.size();
    step.objects = groundList(step, list);
    if (!parsePlacement(step)) {
      step.at = restart;
      step.objects = previous;
      return;
    }
  }
}

void StepParser::skipRejectedAlternative(Step& step) {
  if (!matchesAt(step.words, step.at, {"instead", "of"}) && !matchesAt(step.words, step.at, {"rather", "than"})) return;
  std::size_t at = step.at + 2;
  if (const auto relation = vocabulary::matchRelation(step.words, at)) at += relation->length;  // "instead of on top of it"
  const std::optional<NounPhrase> phrase = reader_.read(step.words, at);
  if (!phrase) failStep(step, "expected what not to do after \"" + joinWords(step.words, step.at, step.at + 2) + "\"");
  step.at = phrase->end;
}

bool StepParser::standsOn(const std::string& object, const std::string& support) const {
  constexpr double kContactGap = 0.015;
  const AlignedBox3& a = reader_.descriptor(object).bounds;
  const AlignedBox3& b = reader_.descriptor(support).bounds;
  const bool over = a.min().x() < b.max().x() && b.min().x() < a.max().x() && a.min().y() < b.max().y() && b.min().y() < a.max().y();
  return object != support && over && std::abs(a.min().z() - b.max().z()) <= kContactGap;
}

double StepParser::gapAsDistance(const Step& step, const RelationSpec& spec, double gap) const {
  if (spec.relation == SpatialRelation::kNextTo || step.objects.empty()) return gap;
  const int axis = spec.relation == SpatialRelation::kLeftOf || spec.relation == SpatialRelation::kRightOf ? 1 : 0;
  const double half = reader_.descriptor(step.objects.front()).bounds.sizes()[axis] / 2.0 +
                      reader_.descriptor(spec.target).bounds.sizes()[axis] / 2.0;
  return half + gap;
}

bool StepParser::isOpenDish(const std::string& object) const {
  const ObjectDescriptor& descriptor = reader_.descriptor(object);
  return descriptor.role == ObjectRole::kContainer && descriptor.cavitySize &&
         std::min(descriptor.cavitySize->x(), descriptor.cavitySize->y()) >= descriptor.cavitySize->z();
}

bool StepParser::parseEachOther(Step& step, std::size_t after) {
  if (!matchesAt(step.words, after, {"each", "other"}) && !matchesAt(step.words, after, {"one", "another"})) return false;
  step.at = after + 2;  // "on top of each other": a stack
  addStackGoals(step, std::nullopt);
  return true;
}

}  // namespace lang2manip::language_detail
