#include "lang2manip/language/goal_conflicts.hpp"

#include "lang2manip/language/noun_phrase.hpp"

namespace lang2manip::language_detail {
namespace {

bool opposite(SpatialRelation a, SpatialRelation b) {
  using R = SpatialRelation;
  return (a == R::kLeftOf && b == R::kRightOf) || (a == R::kRightOf && b == R::kLeftOf) ||
         (a == R::kInFrontOf && b == R::kBehind) || (a == R::kBehind && b == R::kInFrontOf);
}

bool restsIn(SpatialRelation relation) { return relation == SpatialRelation::kIn || relation == SpatialRelation::kOn; }

/// True when `a` and `b` (relation goals of one object) cannot both hold.
bool conflict(const Goal& a, const Goal& b) {
  if (a.kind != GoalKind::kRelation || b.kind != GoalKind::kRelation || !a.relation || !b.relation) return false;
  if (restsIn(*a.relation) && restsIn(*b.relation)) {
    if (a.region && b.region && a.target == b.target && !regionsOverlap(*a.region, *b.region)) return true;
    return a.target != b.target || *a.relation != *b.relation;
  }
  // Inside a container it is where the container is: not beside something else.
  if (*a.relation == SpatialRelation::kIn || *b.relation == SpatialRelation::kIn) return a.target != b.target;
  return a.target == b.target && opposite(*a.relation, *b.relation);
}

std::string keptText(const Goal& kept) {
  return kept.kind == GoalKind::kRelation ? "keep " + describeGoal(kept) : "leave " + kept.object + " where it is";
}

}  // namespace

void refuseConflictingGoals(const std::vector<Goal>& stepGoals, const std::string& stepText) {
  for (std::size_t i = 0; i < stepGoals.size(); ++i) {
    for (std::size_t j = i + 1; j < stepGoals.size(); ++j) {
      if (stepGoals[i].object != stepGoals[j].object || !conflict(stepGoals[i], stepGoals[j])) continue;
      throwGroundingError(stepText, "it contradicts itself: " + describeGoal(stepGoals[i]) + " and " +
                                        describeGoal(stepGoals[j]) + " cannot both hold");
    }
  }
}

void refuseMovingKeptObjects(const std::vector<Goal>& goals, const std::vector<Goal>& kept, const std::string& text) {
  for (const Goal& keep : kept) {
    for (const Goal& goal : goals) {
      if (goal.object != keep.object || goal.kind == GoalKind::kAtConfiguration) continue;
      const bool same = keep.kind == GoalKind::kRelation && goal.kind == GoalKind::kRelation && goal.relation == keep.relation &&
                        goal.target == keep.target;
      if (same) continue;
      throwGroundingError(text, "it contradicts itself: it asks for " + describeGoal(goal) + " and to " + keptText(keep));
    }
  }
}

}  // namespace lang2manip::language_detail
