#include "lang2manip/symbolic/given_plan_planner.hpp"

namespace lang2manip {

Plan GivenPlanTaskPlanner::plan(const PlanningRequest& request, const StopCondition&, PlanningStatistics&) {
  if (!request.earlierAttempts.empty()) {
    throw PlanningError("the " + source_ + " failed and a given plan is not repaired: " + request.earlierAttempts.back().failure);
  }
  return plan_;
}

}  // namespace lang2manip
