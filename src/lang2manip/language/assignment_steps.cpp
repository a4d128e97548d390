// Per-object assignments of a step: "put the blocks in the bowls with matching colours", "each
// block in the bowl of the same colour", "... with mismatched colours", "sort the blocks into the
// bowls by colour", "put the blocks in different corners". A goal per object, chosen by a matching
// over the objects; refused with the reason when none exists.

#include <algorithm>
#include <limits>
#include <numeric>

#include "lang2manip/core/assignment.hpp"

#include "lang2manip/language/clause_parser.hpp"
#include "lang2manip/language/clause_step.hpp"
#include "lang2manip/language/region_phrases.hpp"

namespace lang2manip::language_detail {
namespace {

const std::vector<Words>& colourWords() {
  static const std::vector<Words> words{{"color"}, {"colour"}, {"colors"}, {"colours"}};
  return words;
}

/// "with matching colours", "of the same colour", "by colour": the length of a rule at
/// words[at] and whether it asks for different colours; 0 when none.
std::size_t colourRule(const Words& words, std::size_t at, bool& different) {
  static const std::vector<Words> same{
      {"with", "matching"},      {"with", "the", "matching"}, {"with", "the", "same"}, {"of", "the", "same"}, {"of", "matching"},
      {"of", "their"},           {"of", "its"},              {"in", "their"},         {"that", "match", "their"}, {"that", "matches", "its"},
      {"that", "match", "its"},  {"matching", "in"},         {"matching"},            {"by"},                   {"according", "to"},
      {"based", "on"},           {"of", "the", "matching"},  {"with", "their"},       {"with", "its"},          {"that", "has", "the", "same"},
      {"that", "have", "the", "same"}, {"matching", "their"}, {"matching", "its"}};
  static const std::vector<Words> other{
      {"with", "mismatched"},       {"with", "mismatching"},     {"of", "mismatched"}, {"of", "a", "different"}, {"of", "different"},
      {"with", "different"},        {"with", "a", "different"},  {"of", "another"},     {"of", "the", "wrong"},   {"that", "don't", "match", "their"},
      {"that", "doesn't", "match", "its"}, {"that", "do", "not", "match", "their"}, {"not", "matching", "their"}, {"with", "other"}};
  for (const auto& [table, isDifferent] : {std::pair{&same, false}, std::pair{&other, true}}) {
    const std::size_t lead = longestPhraseAt(words, at, *table);
    if (lead == 0) continue;
    const std::size_t colour = longestPhraseAt(words, at + lead, colourWords());
    if (colour == 0) continue;
    different = isDifferent;
    return lead + colour;
  }
  return 0;
}

/// "different corners", "separate corners", "their own corners", "all four corners", "each
/// corner": the length at words[at] (after the preposition); 0 when none.
std::size_t distinctCorners(const Words& words, std::size_t at) {
  static const std::vector<Words> leads{{"different"}, {"separate"}, {"distinct"}, {"their", "own"}, {"all", "four"}, {"the", "four"},
                                        {"all", "the"}, {"each"}, {"all"}, {"four"}, {"every"}, {"the", "different"}, {"all", "different"}};
  const std::size_t lead = longestPhraseAt(words, at, leads);
  if (lead == 0) return 0;
  if (at + lead < words.size() && (words[at + lead] == "corners" || words[at + lead] == "corner")) return lead + 1;
  return 0;
}

bool shareColour(const ObjectDescriptor& a, const ObjectDescriptor& b) {
  return std::any_of(a.colours.begin(), a.colours.end(), [&](const std::string& colour) { return containsWord(b.colours, colour); });
}

double distance(const ObjectDescriptor& a, const ObjectDescriptor& b) { return (a.position - b.position).head<2>().norm(); }

/// The length of "each", "every", "each of the", "every one of the" at words[at]; 0 when none.
std::size_t eachWord(const Words& words, std::size_t at) {
  static const std::vector<Words> each{{"each"}, {"every"}, {"each", "of", "the"}, {"every", "one", "of", "the"}, {"each", "one", "of", "the"}};
  return longestPhraseAt(words, at, each);
}

/// The length of the preposition of a distributive place ("in", "into", "on", "per"); 0 when none.
std::size_t eachPlacePreposition(const Words& words, std::size_t at) {
  if (at < words.size() && words[at] == "per") return 1;
  return regionPreposition(words, at);
}

}  // namespace

bool eachPlaceFollows(const Words& words, std::size_t at) {
  const std::size_t preposition = eachPlacePreposition(words, at);
  if (preposition == 0) return false;
  return words[at] == "per" ? at + 1 < words.size() : eachWord(words, at + preposition) > 0;
}

void StepParser::assignOnePerPlace(Step& step, std::size_t at) {
  const Words& words = step.words;
  const bool per = words[at] == "per";
  const std::string preposition = words[at];
  at += eachPlacePreposition(words, at);
  at += eachWord(words, at);
  if (at < words.size() && (words[at] == "corner" || words[at] == "corners")) {
    step.at = at + 1;
    std::string support = defaultRegionSupport(step);
    if (step.at < words.size() && words[step.at] == "of") {
      const std::optional<NounPhrase> of = reader_.read(words, step.at + 1);
      if (!of) failStep(step, "expected a table or desk after \"of\"");
      support = groundTarget(step, *of, false);
      step.at = of->end;
    }
    assignCorners(step, support);
    return;
  }
  std::optional<NounPhrase> places = reader_.read(words, at);
  if (!places || !places->noun) failStep(step, "expected the places that each get one after \"" + joinWords(words, 0, at) + "\"");
  places->quantity = Quantity::kAll;
  std::vector<std::string> targets = reader_.ground(*places, discourse_, true, step.objects);
  std::erase_if(targets, [&](const std::string& name) { return containsWord(step.objects, name); });
  if (targets.empty()) failStep(step, "no place to put them in or on: " + places->text);
  const bool into = per || preposition == "in" || preposition == "into";
  for (const std::string& target : targets) {
    const ObjectDescriptor& place = reader_.descriptor(target);
    if (into && place.role != ObjectRole::kContainer && !per) failStep(step, target + " is not a container: nothing goes in it");
  }
  if (step.objects.size() < targets.size()) {
    failStep(step, "one in each needs " + std::to_string(targets.size()) + ": there are only " + std::to_string(step.objects.size()) +
                       " objects for the " + std::to_string(targets.size()) + " places (" + joinNames(targets) + ")");
  }
  // Each place the object that makes the moves least in total.
  std::vector<std::vector<double>> costs(targets.size(), std::vector<double>(step.objects.size()));
  for (std::size_t t = 0; t < targets.size(); ++t) {
    for (std::size_t o = 0; o < step.objects.size(); ++o) costs[t][o] = distance(reader_.descriptor(step.objects[o]), reader_.descriptor(targets[t]));
  }
  const std::vector<std::size_t> chosen = cheapestAssignment(costs);
  std::vector<std::string> moved;
  for (std::size_t o = 0; o < step.objects.size(); ++o) {
    const auto it = std::find(chosen.begin(), chosen.end(), o);
    if (it == chosen.end()) continue;
    const std::string& target = targets[static_cast<std::size_t>(it - chosen.begin())];
    const SpatialRelation relation = reader_.descriptor(target).role == ObjectRole::kContainer ? SpatialRelation::kIn : SpatialRelation::kOn;
    addGoal(step.objects[o], RelationSpec{relation, target, std::nullopt, std::nullopt});
    moved.push_back(step.objects[o]);
  }
  step.objects = moved;
  step.at = places->end;
  step.target = targets.front();
}

bool StepParser::parseAssignment(Step& step) {
  if (step.objects.empty()) return false;
  const Words& words = step.words;
  std::size_t at = step.at;
  if (step.distributive && eachPlaceFollows(words, at)) {
    assignOnePerPlace(step, at);
    return true;
  }
  bool different = false;
  bool ruleFirst = false;
  if (const std::size_t rule = colourRule(words, at, different); rule > 0 && words[at] == "by") {
    at += rule;  // "sort the blocks by colour into the bowls"
    ruleFirst = true;
  }
  const std::size_t preposition = regionPreposition(words, at);
  if (preposition == 0) return false;
  at += preposition;
  if (!ruleFirst) {
    if (const std::size_t corners = distinctCorners(words, at)) {
      step.at = at + corners;
      std::string support;
      if (step.at < words.size() && words[step.at] == "of") {
        const std::optional<NounPhrase> of = reader_.read(words, step.at + 1);
        if (!of) failStep(step, "expected a table or desk after \"of\"");
        support = groundTarget(step, *of, false);
        step.at = of->end;
      } else {
        support = defaultRegionSupport(step);
      }
      assignCorners(step, support);
      return true;
    }
  }
  // The targets: "the bowls", "the matching bowls", "each bowl", "the bowl" (all that the noun names).
  Words reading(words.begin(), words.end());
  std::size_t skipped = 0;
  const std::size_t determiner = (at < words.size() && (words[at] == "the" || words[at] == "a" || words[at] == "each" || words[at] == "their" ||
                                                        words[at] == "its")) ? 1 : 0;
  if (at + determiner < words.size() && (words[at + determiner] == "matching" || words[at + determiner] == "corresponding" ||
                                          words[at + determiner] == "mismatched" || words[at + determiner] == "mismatching")) {
    different = words[at + determiner] == "mismatched" || words[at + determiner] == "mismatching";
    reading.erase(reading.begin() + static_cast<std::ptrdiff_t>(at + determiner));
    skipped = 1;
  } else if (!ruleFirst) {
    const std::optional<NounPhrase> probe = reader_.read(words, at);
    if (!probe || colourRule(words, probe->end, different) == 0) return false;
  }
  std::optional<NounPhrase> targets = reader_.read(reading, at);
  if (!targets || !targets->noun) return false;
  std::size_t end = targets->end + skipped;
  if (!ruleFirst && skipped == 0) end += colourRule(words, end, different);
  if (!ruleFirst && skipped == 0 && end == targets->end) return false;
  if (end < words.size() && words[end] == "by") end += colourRule(words, end, different);  // "into the bowls by colour"
  targets->quantity = Quantity::kAll;
  std::vector<std::string> names = reader_.ground(*targets, discourse_, true, step.objects);
  std::erase_if(names, [&](const std::string& name) { return containsWord(step.objects, name); });
  if (names.empty()) failStep(step, "no object to put them in or on: " + targets->text);
  step.at = end;
  assignByColour(step, names, different);
  return true;
}

void StepParser::assignByColour(Step& step, const std::vector<std::string>& targets, bool different) {
  std::vector<std::string> used;
  for (const std::string& object : step.objects) {
    const ObjectDescriptor& item = reader_.descriptor(object);
    std::string best;
    double bestScore = std::numeric_limits<double>::infinity();
    for (const std::string& target : targets) {
      const ObjectDescriptor& place = reader_.descriptor(target);
      if (shareColour(item, place) == different) continue;
      // A target not yet used comes first (one object each, while there are enough), then the nearest.
      const double score = distance(item, place) + (different && containsWord(used, target) ? 100.0 : 0.0);
      if (score < bestScore) bestScore = score, best = target;
    }
    if (best.empty()) {
      const std::string colours = item.colours.empty() ? std::string("no colour") : joinNames(item.colours);
      failStep(step, "no " + std::string(different ? "other-coloured" : "matching") + " place for " + object + " (" + colours +
                         ") among " + joinNames(targets));
    }
    used.push_back(best);
    const ObjectDescriptor& place = reader_.descriptor(best);
    const SpatialRelation relation =
        place.role == ObjectRole::kContainer ? SpatialRelation::kIn : SpatialRelation::kOn;
    addGoal(object, RelationSpec{relation, best, std::nullopt, std::nullopt});
  }
  step.target = targets.front();
}

void StepParser::assignCorners(Step& step, const std::string& support) {
  constexpr std::size_t kCorners = 4;
  if (!step.distributive && step.objects.size() > kCorners) {
    failStep(step, std::to_string(step.objects.size()) + " objects cannot each have a corner of their own: " + support + " has 4");
  }
  if (step.distributive && step.objects.size() < kCorners) {
    failStep(step, "one in each corner needs 4: there are only " + std::to_string(step.objects.size()) + " objects for the 4 corners of " +
                       support);
  }
  const ObjectDescriptor& top = reader_.descriptor(support);
  const AlignedBox3 area = top.reachableTop.value_or(top.bounds);
  std::vector<SurfaceRegion> corners;
  for (int depth : {1, -1}) {
    for (int side : {1, -1}) corners.push_back({SurfaceRegion::Kind::kCorner, depth, side});
  }
  // A corner without room for an object (taken by something that stays) costs more than any move.
  constexpr double kNoRoom = 100.0;
  std::vector<std::vector<double>> costs(step.objects.size(), std::vector<double>(kCorners));
  for (std::size_t i = 0; i < step.objects.size(); ++i) {
    for (std::size_t c = 0; c < kCorners; ++c) {
      const SurfaceRegion& corner = corners[c];
      const Vector3 point(corner.depth > 0 ? area.max().x() : area.min().x(), corner.side > 0 ? area.max().y() : area.min().y(), 0.0);
      const double move = (reader_.descriptor(step.objects[i]).position - point).head<2>().norm();
      costs[i][c] = regionHasRoom(step.objects[i], support, corner, step.objects) ? move : move + kNoRoom;
    }
  }
  // The assignment that moves the objects least: each object a corner, or (distributive, more
  // objects than corners) each corner an object.
  std::vector<std::size_t> cornerOf(step.objects.size(), kCorners);
  if (step.objects.size() <= kCorners) {
    cornerOf = cheapestAssignment(costs);
  } else {
    std::vector<std::vector<double>> byCorner(kCorners, std::vector<double>(step.objects.size()));
    for (std::size_t i = 0; i < step.objects.size(); ++i) {
      for (std::size_t c = 0; c < kCorners; ++c) byCorner[c][i] = costs[i][c];
    }
    const std::vector<std::size_t> objectOf = cheapestAssignment(byCorner);
    for (std::size_t c = 0; c < kCorners; ++c) cornerOf[objectOf[c]] = c;
  }
  std::vector<std::string> moved;
  for (std::size_t i = 0; i < step.objects.size(); ++i) {
    if (cornerOf[i] == kCorners) continue;
    addGoal(step.objects[i], RelationSpec{SpatialRelation::kOn, support, std::nullopt, corners[cornerOf[i]]});
    moved.push_back(step.objects[i]);
  }
  step.objects = moved;
  step.target = support;
}

void StepParser::addGoal(const std::string& object, const RelationSpec& relation) {
  Goal goal;
  goal.kind = GoalKind::kRelation;
  goal.object = object;
  goal.relation = relation.relation;
  goal.target = relation.target;
  goal.distance = relation.distance;
  goal.region = relation.region;
  specification_.goals.push_back(goal);
}

}  // namespace lang2manip::language_detail
