// Arrangements of a step: "put the blocks in a horizontal line", "in a row", "in a vertical
// column", "in a diagonal line", "in a line along the top edge": a place per object on one line
// of the support's reachable top, evenly spaced, clear of the other objects, in the order the
// objects already have along it.

#include <algorithm>
#include <cmath>

#include "lang2manip/language/clause_parser.hpp"
#include "lang2manip/language/clause_step.hpp"
#include "lang2manip/language/region_phrases.hpp"

namespace lang2manip::language_detail {
namespace {

constexpr double kSpacingGap = 0.04;
constexpr double kClearance = 0.03;

/// The line's direction (base frame, unit, x-y) a phrase names at words[at]: its length, 0 when none.
std::size_t lineWords(const Words& words, std::size_t at, Vector3& direction, bool& diagonal) {
  std::size_t i = at;
  if (i < words.size() && (words[i] == "a" || words[i] == "one" || words[i] == "the")) ++i;
  if (i < words.size() && (words[i] == "single" || words[i] == "straight" || words[i] == "neat" || words[i] == "nice")) ++i;
  std::optional<Vector3> named;
  diagonal = false;
  if (i < words.size()) {
    const std::string& word = words[i];
    if (word == "horizontal" || word == "sideways") named = Vector3::UnitY(), ++i;
    else if (word == "vertical") named = Vector3::UnitX(), ++i;
    else if (word == "diagonal") named = Vector3::UnitX(), diagonal = true, ++i;
  }
  if (i >= words.size()) return 0;
  const std::string& noun = words[i];
  if (noun == "row") direction = named.value_or(Vector3::UnitY());
  else if (noun == "column") direction = named.value_or(Vector3::UnitX());
  else if (noun == "line") direction = named.value_or(Vector3::UnitY());
  else return 0;
  return i + 1 - at;
}

}  // namespace

bool StepParser::parseArrangement(Step& step) {
  if (step.objects.size() < 2) return false;
  const Words& words = step.words;
  const std::size_t preposition = longestPhraseAt(words, step.at, {{"in"}, {"into"}, {"to"}, {"as"}, {"on"}});
  Vector3 direction = Vector3::UnitY();
  bool diagonal = false;
  const std::size_t line = preposition > 0 ? lineWords(words, step.at + preposition, direction, diagonal) : 0;
  if (line == 0) return false;
  std::size_t at = step.at + preposition + line;
  std::optional<SurfaceRegion> along;
  if (matchesAt(words, at, {"along"})) {  // "in a line along the top edge"
    const std::optional<RegionPhrase> edge = matchRegionPhrase(words, at + 1);
    if (!edge || edge->region.kind != SurfaceRegion::Kind::kEdge) failStep(step, "a line goes along an edge: the top, bottom, left or right one");
    along = edge->region;
    direction = edge->region.depth != 0 ? Vector3::UnitY() : Vector3::UnitX();
    at += 1 + edge->length;
  }
  const std::string support = defaultRegionSupport(step);
  if (at < words.size() && words[at] == "of") {
    const std::optional<NounPhrase> of = reader_.read(words, at + 1);
    if (of) at = of->end;
  }
  step.at = at;
  arrangeInLine(step, support, direction, diagonal, along);
  return true;
}

void StepParser::arrangeInLine(Step& step, const std::string& support, Vector3 direction, bool diagonal,
                               const std::optional<SurfaceRegion>& along) {
  const ObjectDescriptor& top = reader_.descriptor(support);
  const AlignedBox3 area = top.reachableTop.value_or(top.bounds);
  if (diagonal) direction = Vector3(area.sizes().x(), area.sizes().y(), 0.0).normalized();
  const Vector3 normal(-direction.y(), direction.x(), 0.0);
  double widest = 0.0;
  for (const std::string& object : step.objects) widest = std::max(widest, reader_.descriptor(object).bounds.sizes().head<2>().maxCoeff());
  const double spacing = widest + kSpacingGap;
  const double length = spacing * static_cast<double>(step.objects.size() - 1);
  // The order along the line is the order they stand in now.
  std::vector<std::string> order = step.objects;
  std::stable_sort(order.begin(), order.end(), [&](const std::string& a, const std::string& b) {
    return reader_.descriptor(a).position.dot(direction) < reader_.descriptor(b).position.dot(direction);
  });
  const auto inside = [&](const Vector3& p) {
    const double margin = widest / 2.0 + 0.02;
    return p.x() >= area.min().x() + margin && p.x() <= area.max().x() - margin && p.y() >= area.min().y() + margin &&
           p.y() <= area.max().y() - margin;
  };
  const auto clear = [&](const Vector3& p, bool ofOwn) {
    for (const ObjectDescriptor& other : reader_.objects()) {
      if (other.name == support || (!ofOwn && containsWord(step.objects, other.name))) continue;
      const AlignedBox3& box = other.bounds;
      const double half = widest / 2.0 + kClearance;
      if (p.x() > box.min().x() - half && p.x() < box.max().x() + half && p.y() > box.min().y() - half && p.y() < box.max().y() + half) return false;
    }
    return true;
  };
  Vector3 middle = along ? regionBox(area, *along).center() : area.center();
  middle.z() = 0.0;
  for (bool ofOwn : {true, false}) {
    for (double shift : {0.0, 0.25, -0.25, 0.5, -0.5, 0.75, -0.75}) {
      const double reach = std::abs(normal.x()) * area.sizes().x() / 2.0 + std::abs(normal.y()) * area.sizes().y() / 2.0;
      const Vector3 centre = middle + normal * (along ? 0.0 : shift * reach);
      std::vector<Vector3> spots;
      for (std::size_t i = 0; i < order.size(); ++i) spots.push_back(centre + direction * (-length / 2.0 + spacing * static_cast<double>(i)));
      if (!std::all_of(spots.begin(), spots.end(), [&](const Vector3& p) { return inside(p) && clear(p, ofOwn); })) continue;
      for (std::size_t i = 0; i < order.size(); ++i) {
        const ObjectDescriptor& object = reader_.descriptor(order[i]);
        Goal goal;
        goal.kind = GoalKind::kAtPosition;
        goal.object = order[i];
        goal.position = Vector3(spots[i].x() + object.origin.x() - object.position.x(), spots[i].y() + object.origin.y() - object.position.y(),
                                object.origin.z());
        specification_.goals.push_back(goal);
      }
      step.target = support;
      return;
    }
  }
  failStep(step, std::to_string(step.objects.size()) + " objects in a line need " + std::to_string(static_cast<int>(std::round(length * 100.0))) +
                     " cm clear on " + support + ", and its reachable top has no such line free");
}

}  // namespace lang2manip::language_detail
