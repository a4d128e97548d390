// Arrangements of a step: "put the blocks in a horizontal line", "in a row along the top edge",
// "in an evenly spaced column", "in a line 10 cm apart", "in a circle (around the bowl)", "in a
// triangle", "in the shape of a square", "in a circular formation in the middle of the table",
// "spread out": an arranged goal (what is checked) and an at_position goal per member (where the
// offline planner puts it, arrangement_layout.cpp).

#include <algorithm>
#include <cmath>
#include <numeric>

#include "lang2manip/language/arrangement_layout.hpp"
#include "lang2manip/language/clause_parser.hpp"
#include "lang2manip/language/clause_step.hpp"
#include "lang2manip/language/region_phrases.hpp"
#include "lang2manip/symbolic/arrangement_check.hpp"

namespace lang2manip::language_detail {
namespace {

const std::vector<Words> kEvenly{{"evenly", "spaced"}, {"equally", "spaced"}, {"spaced", "evenly"}, {"spaced", "equally"},
                                 {"evenly", "distributed"}, {"at", "equal", "distances"}, {"with", "equal", "gaps"},
                                 {"with", "equal", "spacing"}, {"evenly"}, {"equidistant"}};
const std::vector<Words> kSpreadOut{{"spread", "out"}, {"spaced", "out"}, {"far", "apart"}, {"well", "apart"},
                                    {"apart", "from", "each", "other"}, {"away", "from", "each", "other"},
                                    {"far", "apart", "from", "each", "other"}, {"well", "apart", "from", "each", "other"},
                                    {"far", "from", "each", "other"}, {"far", "away", "from", "each", "other"},
                                    {"apart", "from", "one", "another"}, {"apart"}, {"scattered"}};
/// "next to each other", "close to one another", "side by side", "together", "in a group", ...
std::vector<Words> togetherPhrases() {
  std::vector<Words> phrases{{"side", "by", "side"}, {"close", "together"}, {"together"}, {"grouped", "together"}, {"clustered", "together"},
                             {"in", "a", "group"}, {"in", "one", "group"}, {"in", "a", "cluster"}, {"in", "a", "bunch"}};
  for (const Words& near : {Words{"next", "to"}, Words{"beside"}, Words{"close", "to"}, Words{"near"}, Words{"close", "by"}, Words{"by"}}) {
    for (const Words& reciprocal : {Words{"each", "other"}, Words{"one", "another"}}) {
      Words phrase = near;
      phrase.insert(phrase.end(), reciprocal.begin(), reciprocal.end());
      phrases.push_back(phrase);
    }
  }
  return phrases;
}
const std::vector<Words> kTogether = togetherPhrases();
const std::vector<Words> kShapeNouns{{"shape"}, {"formation"}, {"pattern"}, {"arrangement"}, {"layout"}};
const std::vector<Words> kSkippedAdjectives{{"single"}, {"straight"}, {"neat"}, {"nice"}, {"perfect"}, {"tidy"},
                                            {"big"}, {"large"}, {"small"}, {"little"}, {"regular"}, {"equilateral"}};

/// The shape noun at words[i] ("line", "circle", "triangular formation"): its length, 0 when none.
std::size_t shapeNoun(const Words& words, std::size_t i, ShapePhrase& phrase) {
  if (i >= words.size()) return 0;
  const std::string& word = words[i];
  std::size_t length = 1;
  if (word == "row" || word == "line") phrase.shape = ArrangementShape::kLine;
  else if (word == "column") phrase.shape = ArrangementShape::kLine, phrase.direction = phrase.direction.value_or(Vector3::UnitX());
  else if (word == "circle" || word == "ring") phrase.shape = ArrangementShape::kCircle;
  else if (word == "triangle") phrase.shape = ArrangementShape::kTriangle;
  else if (word == "square") phrase.shape = ArrangementShape::kSquare;
  else if (word == "pyramid") phrase.shape = ArrangementShape::kPyramid;
  else if ((word == "circular" || word == "round" || word == "triangular") && longestPhraseAt(words, i + 1, kShapeNouns) > 0) {
    phrase.shape = word == "triangular" ? ArrangementShape::kTriangle : ArrangementShape::kCircle;
    length = 2;
  } else {
    return 0;
  }
  if (length == 1) length += longestPhraseAt(words, i + 1, kShapeNouns);  // "a square shape"
  if (phrase.shape == ArrangementShape::kLine && word == "row") phrase.direction = phrase.direction.value_or(Vector3::UnitY());
  return length;
}

Goal arrangedGoal(const std::vector<std::string>& members, const ShapePhrase& phrase, const std::string& support, const Vector3& direction) {
  Goal arranged;
  arranged.kind = GoalKind::kArranged;
  arranged.members = members;
  arranged.shape = phrase.shape;
  arranged.target = support;
  arranged.evenlySpaced = phrase.evenly || phrase.spacing.has_value();
  arranged.distance = phrase.spacing;
  if (phrase.direction || phrase.diagonal) arranged.heading = std::atan2(direction.y(), direction.x());
  return arranged;
}

/// True when the members stand on the support in the arrangement already (outside any region
/// asked for it is not), clearly: within half the check's distance tolerance, so that what is
/// left standing is not at the edge of what the words allow.
bool alreadyArranged(const Goal& arranged, const ArrangementLayoutRequest& request) {
  if (request.centreArea || request.around || request.between) return false;
  if (!std::all_of(request.onSupport.begin(), request.onSupport.end(), [](bool on) { return on; })) return false;
  SpatialOptions clearly;
  clearly.distanceTolerance /= 2.0;
  return checkArrangedBoxes(arranged, request.members, clearly).holds;
}

std::vector<Vector3> standingCentres(const ArrangementLayoutRequest& request) {
  std::vector<Vector3> centres;
  for (const AlignedBox3& box : request.members) centres.emplace_back(box.center().x(), box.center().y(), 0.0);
  return centres;
}

}  // namespace

std::optional<ShapePhrase> matchShapePhrase(const Words& words, std::size_t at) {
  ShapePhrase phrase;
  std::size_t i = at;
  const auto determiner = [&] {
    if (i < words.size() && (words[i] == "a" || words[i] == "an" || words[i] == "one" || words[i] == "the")) ++i;
  };
  determiner();
  if (matchesAt(words, i, {"shape", "of"}) || matchesAt(words, i, {"form", "of"})) i += 2, determiner();
  for (bool more = true; more && i < words.size();) {
    const std::string& word = words[i];
    if (const std::size_t evenly = longestPhraseAt(words, i, kEvenly)) phrase.evenly = true, i += evenly;
    else if (const std::size_t skipped = longestPhraseAt(words, i, kSkippedAdjectives)) i += skipped;
    else if (word == "horizontal" || word == "sideways") phrase.direction = Vector3::UnitY(), ++i;
    else if (word == "vertical") phrase.direction = Vector3::UnitX(), ++i;
    else if (word == "diagonal") phrase.diagonal = true, ++i;
    else more = false;
  }
  const std::size_t noun = shapeNoun(words, i, phrase);
  if (noun == 0) return std::nullopt;
  i += noun;
  if (phrase.shape != ArrangementShape::kLine && (phrase.direction || phrase.diagonal)) return std::nullopt;
  if (const std::size_t evenly = longestPhraseAt(words, i, kEvenly)) phrase.evenly = true, i += evenly;
  if (const auto length = vocabulary::matchLength(words, i); length && matchesAt(words, i + length->length, {"apart"})) {
    phrase.spacing = length->metres;  // "in a line 10 cm apart"
    i += length->length + 1;
  }
  phrase.length = i - at;
  return phrase;
}

bool StepParser::parseArrangement(Step& step) {
  const Words& words = step.words;
  std::size_t at = step.at;
  if (step.objects.size() < 2) {
    const std::size_t preposition = longestPhraseAt(words, at, {{"in"}, {"into"}, {"as"}});
    if (preposition > 0 && matchShapePhrase(words, at + preposition)) failStep(step, "an arrangement needs at least two objects");
    return false;
  }
  ShapePhrase phrase;
  if (const std::size_t spread = longestPhraseAt(words, at, kSpreadOut)) {
    phrase.shape = ArrangementShape::kSpreadOut;
    at += spread;
  } else if (const std::size_t together = longestPhraseAt(words, at, kTogether)) {
    // "together in the bowl" puts them into the bowl; "together" alone or on a support groups them
    const std::size_t into = longestPhraseAt(words, at + together, {{"in"}, {"into"}, {"inside"}});
    const std::size_t regionWords = regionPreposition(words, at + together);
    if (into > 0 && !(regionWords > 0 && matchRegionPhrase(words, at + together + regionWords))) {
      step.at = at + together;  // read on from "in the bowl"
      return false;
    }
    phrase.shape = ArrangementShape::kTogether;
    at += together;
  } else {
    const std::size_t preposition =
        longestPhraseAt(words, at, {{"in"}, {"into"}, {"to"}, {"as"}, {"on"}, {"forming"}, {"to", "form"}, {"so", "they", "form"}});
    const std::optional<ShapePhrase> shape = preposition > 0 ? matchShapePhrase(words, at + preposition) : std::nullopt;
    if (!shape) return false;
    phrase = *shape;
    at += preposition + shape->length;
  }
  step.at = at;
  parseArrangementPlace(step, phrase);
  arrange(step, phrase);
  return true;
}

void StepParser::parseArrangementPlace(Step& step, ShapePhrase& phrase) {
  const Words& words = step.words;
  for (bool more = true; more && !step.atEnd();) {
    std::size_t& at = step.at;
    const bool along = matchesAt(words, at, {"along"});
    const std::size_t preposition = along ? 1 : regionPreposition(words, at);
    const std::optional<RegionPhrase> region = matchRegionPhrase(words, at + preposition);
    if (region && preposition > 0) {  // "along the top edge", "in the middle"
      if (along && region->region.kind != SurfaceRegion::Kind::kEdge) failStep(step, "a line goes along an edge: the top, bottom, left or right one");
      if (region->nearestCorner || region->farthestCorner || (region->region.depth == 0 && region->region.side == 0 && region->region.kind == SurfaceRegion::Kind::kCorner)) {
        failStep(step, "say which corner the arrangement goes in (\"the far left corner\")");
      }
      phrase.region = region->region;
      if (along) phrase.direction = region->region.depth != 0 ? Vector3::UnitY() : Vector3::UnitX();
      at += preposition + region->length;
      continue;
    }
    if (matchesAt(words, at, {"around"}) || matchesAt(words, at, {"round"}) || matchesAt(words, at, {"surrounding"})) {
      const std::optional<NounPhrase> centre = reader_.read(words, at + 1);
      if (!centre) failStep(step, "expected an object after \"" + words[at] + "\"");
      if (phrase.shape == ArrangementShape::kLine || phrase.shape == ArrangementShape::kSpreadOut || phrase.shape == ArrangementShape::kTogether ||
          phrase.shape == ArrangementShape::kPyramid) {
        failStep(step, "only a circle, triangle or square goes around something");
      }
      phrase.around = groundTarget(step, *centre, false);
      at = centre->end;
      continue;
    }
    if (matchesAt(words, at, {"between"})) {  // "between the red bowl and the blue bowl"
      const std::optional<NounPhrase> first = reader_.read(words, at + 1);
      const std::optional<NounPhrase> second = first && matchesAt(words, first->end, {"and"}) ? reader_.read(words, first->end + 1) : std::nullopt;
      if (!second) failStep(step, "expected \"between X and Y\"");
      if (phrase.shape != ArrangementShape::kLine) failStep(step, "only a line goes between two objects");
      phrase.between = {groundTarget(step, *first, false), groundTarget(step, *second, false)};
      if (phrase.between[0] == phrase.between[1]) failStep(step, "a line between " + phrase.between[0] + " and itself");
      at = second->end;
      continue;
    }
    const std::size_t on = longestPhraseAt(words, at, {{"on"}, {"of"}, {"across"}, {"over"}, {"on", "top", "of"}});
    const std::optional<NounPhrase> support = on > 0 ? reader_.read(words, at + on) : std::nullopt;
    if (support) {  // "on the table", "across the desk"
      phrase.support = groundTarget(step, *support, false);
      at = support->end;
      continue;
    }
    // ", evenly spaced" or "10 cm apart" after the places
    const std::size_t comma = matchesAt(words, at, {","}) ? 1 : 0;
    if (const std::size_t evenly = phrase.shape == ArrangementShape::kLine ? longestPhraseAt(words, at + comma, kEvenly) : 0) {
      phrase.evenly = true;
      at += comma + evenly;
      continue;
    }
    more = false;
  }
}

void StepParser::arrange(Step& step, const ShapePhrase& phrase) {
  const std::string support = phrase.support.empty() ? defaultRegionSupport(step) : phrase.support;
  const ObjectDescriptor& top = reader_.descriptor(support);
  if (top.role != ObjectRole::kSupport) failStep(step, support + " is not a support to arrange things on");
  const std::size_t members = step.objects.size();
  if (const std::string problem = memberCountProblem(phrase.shape, members); !problem.empty()) {
    const bool tooManyForCorners = polygonCorners(phrase.shape) != 0 && members > polygonCorners(phrase.shape);
    failStep(step, problem + (tooManyForCorners ? "; say which of them, or a circle or line" : ""));
  }
  ArrangementLayoutRequest request;
  request.shape = phrase.shape;
  request.area = top.reachableTop.value_or(top.bounds);
  if (phrase.region) request.centreArea = regionBox(request.area, *phrase.region);
  if (phrase.region && phrase.region->kind == SurfaceRegion::Kind::kEdge && phrase.shape == ArrangementShape::kLine) {
    const int along = phrase.region->depth != 0 ? 1 : 0;  // a line along an edge may run its whole length
    request.centreArea->min()[along] = request.area.min()[along];
    request.centreArea->max()[along] = request.area.max()[along];
  }
  request.direction = phrase.direction.value_or(Vector3::UnitY());
  if (phrase.diagonal) request.direction = Vector3(request.area.sizes().x(), request.area.sizes().y(), 0.0).normalized();
  request.spacing = phrase.spacing;
  for (const std::string& member : step.objects) {
    request.members.push_back(reader_.descriptor(member).bounds);
    request.onSupport.push_back(standsOn(member, support));
  }
  if (!phrase.around.empty()) request.around = reader_.descriptor(phrase.around).bounds;
  if (!phrase.between.empty()) {
    if (phrase.spacing || phrase.direction || phrase.diagonal) failStep(step, "a line between two objects takes their direction and spacing");
    request.between = std::make_pair(reader_.descriptor(phrase.between[0]).bounds, reader_.descriptor(phrase.between[1]).bounds);
    Vector3 along = request.between->second.center() - request.between->first.center();
    along.z() = 0.0;
    request.direction = along.normalized();
  }
  for (const ObjectDescriptor& other : reader_.objects()) {
    const bool below = other.bounds.max().z() < top.bounds.max().z() - 0.01;  // what the support stands on
    if (other.name == support || below || containsWord(step.objects, other.name)) continue;
    request.others.push_back(other.bounds);
    request.othersMovable.push_back(other.movable);
  }
  Goal arranged = arrangedGoal(step.objects, phrase, support, request.direction);
  if (!phrase.between.empty()) {  // evenly spaced along the segment's direction
    arranged.heading = std::atan2(request.direction.y(), request.direction.x());
    arranged.evenlySpaced = true;
  }
  std::string why;
  const std::optional<std::vector<Vector3>> spots = alreadyArranged(arranged, request) ? standingCentres(request) : layOutArrangement(request, why);
  if (!spots) failStep(step, why + " on " + support);

  bool inRegion = phrase.region.has_value();
  std::vector<Goal> memberGoals;
  for (std::size_t i = 0; i < step.objects.size(); ++i) {
    const ObjectDescriptor& object = reader_.descriptor(step.objects[i]);
    const Vector3& spot = (*spots)[i];
    const AlignedBox3 regionArea = phrase.region ? regionBox(request.area, *phrase.region) : request.area;
    inRegion = inRegion && regionArea.contains(Vector3(spot.x(), spot.y(), regionArea.center().z()));
    Goal goal;
    goal.kind = GoalKind::kAtPosition;
    goal.object = step.objects[i];
    // A pyramid's member rises onto the row below; the others keep the height they stand at.
    const double height = phrase.shape == ArrangementShape::kPyramid ? top.bounds.max().z() + spot.z() + object.origin.z() - object.bounds.min().z()
                                                                     : object.origin.z();
    goal.position = Vector3(spot.x() + object.origin.x() - object.position.x(), spot.y() + object.origin.y() - object.position.y(), height);
    memberGoals.push_back(goal);
  }
  if (phrase.shape == ArrangementShape::kPyramid) {  // row by row from the base up
    std::vector<std::size_t> order(memberGoals.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return (*spots)[a].z() < (*spots)[b].z(); });
    std::vector<Goal> rows;
    for (const std::size_t i : order) rows.push_back(memberGoals[i]);
    memberGoals = std::move(rows);
  }
  specification_.goals.insert(specification_.goals.end(), memberGoals.begin(), memberGoals.end());
  if (inRegion) arranged.region = phrase.region;
  specification_.goals.push_back(arranged);
  step.target = support;
}

}  // namespace lang2manip::language_detail
