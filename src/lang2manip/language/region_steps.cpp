// Region phrases of a step: "put the red block in the top left corner of the table".

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "lang2manip/language/clause_parser.hpp"
#include "lang2manip/language/clause_step.hpp"
#include "lang2manip/language/layout_geometry.hpp"
#include "lang2manip/language/region_phrases.hpp"

namespace lang2manip::language_detail {
namespace {

/// The relation beside an object that a side of it names ("on the left side of the box").
std::optional<SpatialRelation> sideRelation(const SurfaceRegion& region) {
  if (region.kind != SurfaceRegion::Kind::kEdge && region.kind != SurfaceRegion::Kind::kHalf) return std::nullopt;
  if (region.side > 0) return SpatialRelation::kLeftOf;
  if (region.side < 0) return SpatialRelation::kRightOf;
  return region.depth > 0 ? SpatialRelation::kInFrontOf : SpatialRelation::kBehind;
}

/// The length of "the robot", "you", "the base" ... at words[at]; 0 when absent.
std::size_t robotWords(const Words& words, std::size_t at) {
  return longestPhraseAt(words, at, {{"the", "robot"}, {"robot"}, {"you"}, {"yourself"}, {"the", "robot's", "base"}, {"your", "base"},
                                     {"the", "base"}, {"me"}});
}

Vector3 cornerPoint(const AlignedBox3& box, int depth, int side) {
  return {depth > 0 ? box.max().x() : box.min().x(), side > 0 ? box.max().y() : box.min().y(), box.max().z()};
}

}  // namespace

std::string StepParser::defaultRegionSupport(const Step& step) const {
  std::vector<std::string> supports;
  for (const ObjectDescriptor& object : reader_.objects()) {
    if (object.role != ObjectRole::kSupport) continue;
    if (!step.objects.empty() && standsOn(step.objects.front(), object.name)) return object.name;
    supports.push_back(object.name);
  }
  if (supports.size() == 1) return supports.front();
  failStep(step, supports.empty() ? "no support (table, desk) to have corners, edges or a middle"
                                  : "which support's region is meant: " + joinAlternatives(supports) + "? say \"of the " +
                                        supports.front() + "\"");
}

bool StepParser::regionHasRoom(const std::string& object, const std::string& support, const SurfaceRegion& region,
                               const std::vector<std::string>& leaving) const {
  constexpr double kClearance = 0.01;
  const ObjectDescriptor& top = reader_.descriptor(support);
  const AlignedBox3 area = top.reachableTop.value_or(top.bounds);
  const Vector3 size = reader_.descriptor(object).bounds.sizes();
  const auto centres = regionCentres(area, region, size);
  if (!centres) return false;
  const Vector3 half(size.x() / 2.0 + kClearance, size.y() / 2.0 + kClearance, 0.0);
  const AlignedBox3 room(centres->min() - half, centres->max() + half);
  std::vector<AlignedBox3> occupied;
  for (const ObjectDescriptor& other : reader_.objects()) {
    if (other.name == object || other.name == support || containsWord(leaving, other.name)) continue;
    if (other.bounds.min().z() < area.max().z() + 0.05 && other.bounds.max().z() > area.max().z()) occupied.push_back(other.bounds);
  }
  return !freeSpots(size, room, occupied, centres->center(), kClearance, 1).empty();
}

SurfaceRegion StepParser::chooseCorner(const Step& step, SurfaceRegion corner, const std::string& support,
                                       const std::string& reference, bool fromRobot, bool farthest) const {
  const ObjectDescriptor& descriptor = reader_.descriptor(support);
  const AlignedBox3 top = descriptor.reachableTop.value_or(descriptor.bounds);
  Vector3 from = reference.empty() ? Vector3::Zero() : reader_.descriptor(reference).position;
  if (reference.empty() && !fromRobot && !step.objects.empty()) from = reader_.descriptor(step.objects.front()).position;
  double best = farthest ? -1.0 : std::numeric_limits<double>::infinity();
  SurfaceRegion chosen = corner;
  std::map<std::pair<int, int>, bool> room;  // per (depth, side), measured once
  for (int depth : {1, -1}) {
    for (int side : {1, -1}) {
      room[{depth, side}] = step.objects.empty() ||
                            regionHasRoom(step.objects.front(), support, {SurfaceRegion::Kind::kCorner, depth, side}, step.objects);
    }
  }
  const bool anyRoom = std::any_of(room.begin(), room.end(), [](const auto& entry) { return entry.second; });
  const auto hasRoom = [&](int depth, int side) { return room.at({depth, side}); };
  for (int depth : {1, -1}) {
    for (int side : {1, -1}) {
      if ((corner.depth != 0 && corner.depth != depth) || (corner.side != 0 && corner.side != side)) continue;
      if (anyRoom && !hasRoom(depth, side)) continue;
      const double distance = (cornerPoint(top, depth, side) - from).head<2>().norm();
      if (farthest ? distance > best : distance < best) {
        best = distance;
        chosen = {SurfaceRegion::Kind::kCorner, depth, side};
      }
    }
  }
  return chosen;
}

bool StepParser::parseRegion(Step& step) {
  const Words& words = step.words;
  const std::size_t preposition = regionPreposition(words, step.at);
  if (preposition == 0) return false;
  const std::optional<RegionPhrase> phrase = matchRegionPhrase(words, step.at + preposition);
  if (!phrase) return false;
  std::size_t at = step.at + preposition + phrase->length;
  std::string reference;
  bool fromRobot = false;
  if (const std::size_t robot = robotWords(words, phrase->referenceAt); robot > 0 && (phrase->nearestCorner || phrase->farthestCorner)) {
    fromRobot = true;  // "the corner closest to the robot": its base
    at = phrase->referenceAt + robot;
  } else if (phrase->nearestCorner || phrase->farthestCorner) {
    const std::optional<NounPhrase> referencePhrase = reader_.read(words, phrase->referenceAt);
    if (!referencePhrase) {
      throwGroundingError(joinWords(words, step.at, words.size()), "expected an object after \"" +
                                                                       joinWords(words, step.at, phrase->referenceAt) + "\"");
    }
    const std::vector<std::string> named = reader_.ground(*referencePhrase, discourse_, true, step.objects);
    if (named.size() != 1) throwGroundingError(referencePhrase->text, "a corner is chosen by one object");
    reference = named.front();
    at = referencePhrase->end;
  }
  std::string support;
  if (at < words.size() && words[at] == "of") {
    const std::optional<NounPhrase> supportPhrase = reader_.read(words, at + 1);
    if (!supportPhrase) return false;  // "the left side of" something that names nothing: not a region
    support = groundTarget(step, *supportPhrase, false);
    at = supportPhrase->end;
  } else {
    support = defaultRegionSupport(step);
  }
  step.at = at;
  RelationSpec spec{SpatialRelation::kOn, support, std::nullopt, phrase->region};
  if (reader_.descriptor(support).role != ObjectRole::kSupport) {
    const std::optional<SpatialRelation> beside = sideRelation(phrase->region);
    if (!beside) {
      failStep(step, support + " is not a table or desk: its " + surfaceRegionName(phrase->region) +
                         " is no place to put things (regions are of a support's top)");
    }
    spec = RelationSpec{*beside, support, std::nullopt, std::nullopt};
  } else if (phrase->region.kind == SurfaceRegion::Kind::kCorner &&
             (phrase->region.depth == 0 || phrase->region.side == 0 || !reference.empty() || fromRobot)) {
    spec.region = chooseCorner(step, phrase->region, support, reference, fromRobot, phrase->farthestCorner);
  }
  if (spec.region && refineGoalsOnSupport(step, spec)) return true;
  addRelationGoals(step, spec);
  return true;
}

bool StepParser::refineGoalsOnSupport(Step& step, const RelationSpec& spec) {
  bool refined = false;
  for (std::size_t i = step.firstGoal; i < specification_.goals.size(); ++i) {
    Goal& goal = specification_.goals[i];
    const bool onSupport = goal.kind == GoalKind::kRelation && goal.relation == SpatialRelation::kOn && goal.target == spec.target;
    if (onSupport && !goal.region && containsWord(step.objects, goal.object)) {
      goal.region = spec.region;  // "on the desk in its far left corner"
      refined = true;
    }
  }
  return refined;
}

}  // namespace lang2manip::language_detail
