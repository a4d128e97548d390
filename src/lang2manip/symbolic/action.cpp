#include "lang2manip/symbolic/action.hpp"

#include <algorithm>

#include <array>
#include <cmath>
#include <sstream>
#include <utility>

namespace lang2manip {
namespace {

template <typename Enum, std::size_t N>
using NameTable = std::array<std::pair<Enum, const char*>, N>;

constexpr NameTable<ActionType, 4> kActionNames{{
    {ActionType::kPick, "pick"},
    {ActionType::kPlace, "place"},
    {ActionType::kMove, "move"},
    {ActionType::kPush, "push"},
}};

constexpr NameTable<SpatialRelation, 7> kRelationNames{{
    {SpatialRelation::kIn, "in"},
    {SpatialRelation::kOn, "on"},
    {SpatialRelation::kLeftOf, "left_of"},
    {SpatialRelation::kRightOf, "right_of"},
    {SpatialRelation::kInFrontOf, "in_front_of"},
    {SpatialRelation::kBehind, "behind"},
    {SpatialRelation::kNextTo, "next_to"},
}};

constexpr NameTable<GraspDirection, 4> kGraspNames{{
    {GraspDirection::kAuto, "auto"},
    {GraspDirection::kTop, "top"},
    {GraspDirection::kSide, "side"},
    {GraspDirection::kFront, "front"},
}};

constexpr NameTable<ArrangementShape, 7> kShapeNames{{
    {ArrangementShape::kLine, "line"},
    {ArrangementShape::kCircle, "circle"},
    {ArrangementShape::kTriangle, "triangle"},
    {ArrangementShape::kSquare, "square"},
    {ArrangementShape::kSpreadOut, "spread_out"},
    {ArrangementShape::kTogether, "together"},
    {ArrangementShape::kPyramid, "pyramid"},
}};

template <typename Enum, std::size_t N>
std::string nameOf(const NameTable<Enum, N>& table, Enum value) {
  for (const auto& [entry, name] : table) {
    if (entry == value) return name;
  }
  return "unknown";
}

template <typename Enum, std::size_t N>
std::optional<Enum> valueOf(const NameTable<Enum, N>& table, const std::string& name) {
  for (const auto& [entry, entryName] : table) {
    if (name == entryName) return entry;
  }
  return std::nullopt;
}

template <typename Enum, std::size_t N>
std::vector<std::string> namesOf(const NameTable<Enum, N>& table) {
  std::vector<std::string> names;
  for (const auto& entry : table) names.emplace_back(entry.second);
  return names;
}

}  // namespace

std::string actionTypeName(ActionType type) { return nameOf(kActionNames, type); }
std::string spatialRelationName(SpatialRelation relation) { return nameOf(kRelationNames, relation); }

std::string spatialRelationWords(SpatialRelation relation) {
  std::string words = spatialRelationName(relation);
  std::replace(words.begin(), words.end(), '_', ' ');
  return words;
}
std::string graspDirectionName(GraspDirection direction) { return nameOf(kGraspNames, direction); }

std::optional<ActionType> actionTypeFromName(const std::string& name) {
  return valueOf(kActionNames, name);
}
std::optional<SpatialRelation> spatialRelationFromName(const std::string& name) {
  return valueOf(kRelationNames, name);
}
std::optional<GraspDirection> graspDirectionFromName(const std::string& name) {
  return valueOf(kGraspNames, name);
}

std::vector<std::string> actionTypeNames() { return namesOf(kActionNames); }
std::vector<std::string> spatialRelationNames() { return namesOf(kRelationNames); }
std::vector<std::string> graspDirectionNames() { return namesOf(kGraspNames); }

std::string arrangementShapeName(ArrangementShape shape) { return nameOf(kShapeNames, shape); }
std::optional<ArrangementShape> arrangementShapeFromName(const std::string& name) { return valueOf(kShapeNames, name); }
std::vector<std::string> arrangementShapeNames() { return namesOf(kShapeNames); }

std::string describeGoal(const Goal& goal) {
  std::ostringstream text;
  switch (goal.kind) {
    case GoalKind::kRelation:
      text << goal.object << ' '
           << (goal.relation ? spatialRelationWords(*goal.relation) : std::string("?")) << ' '
           << goal.target;
      if (goal.distance) text << " at " << *goal.distance << " m";
      if (goal.region) text << " (" << surfaceRegionWords(*goal.region) << ")";
      break;
    case GoalKind::kHolding:
      text << "holding " << goal.object;
      break;
    case GoalKind::kDisplaced:
      text << goal.object << " displaced by (" << goal.displacement.x() << ", "
           << goal.displacement.y() << ", " << goal.displacement.z() << ")";
      break;
    case GoalKind::kAtConfiguration:
      text << "at " << goal.configuration;
      break;
    case GoalKind::kHandedOver:
      text << goal.object << " handed over";
      break;
    case GoalKind::kAtPosition: {
      const Vector3 p = goal.position.value_or(Vector3::Zero());
      text << goal.object << " at (" << std::round(p.x() * 1000.0) / 1000.0 << ", " << std::round(p.y() * 1000.0) / 1000.0 << ")";
      if (!goal.target.empty()) text << " where " << goal.target << " stood";
      break;
    }
    case GoalKind::kTurned:
      text << goal.object << " turned by " << std::round(goal.angle * 1800.0 / 3.14159265358979323846) / 10.0 << " deg";
      break;
    case GoalKind::kFacing:
      if (goal.target.empty()) {
        text << goal.object << " pointing along yaw " << std::round(goal.angle * 1800.0 / 3.14159265358979323846) / 10.0 << " deg";
      } else {
        text << goal.object << " pointing at " << goal.target;
      }
      break;
    case GoalKind::kArranged:
      for (std::size_t i = 0; i < goal.members.size(); ++i) text << (i == 0 ? "" : ", ") << goal.members[i];
      if (goal.shape == ArrangementShape::kSpreadOut) text << " spread out";
      else if (goal.shape == ArrangementShape::kTogether) text << " next to each other";
      else text << " in a " << (goal.shape ? arrangementShapeName(*goal.shape) : std::string("?"));
      if (goal.heading) text << " along yaw " << std::round(*goal.heading * 1800.0 / 3.14159265358979323846) / 10.0 << " deg";
      if (goal.evenlySpaced) text << ", evenly spaced";
      if (goal.distance) text << ", " << *goal.distance << " m apart";
      if (!goal.target.empty()) text << " on " << goal.target;
      if (goal.region) text << " (" << surfaceRegionName(*goal.region) << ")";
      break;
  }
  return text.str();
}

Vector3 handoverToolPosition() { return {0.40, 0.0, 0.25}; }

}  // namespace lang2manip
