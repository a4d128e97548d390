#pragma once
/// @file A task planner that answers with a plan given in advance (`run --plan FILE`): its first
/// answer is that plan; asked again (the plan failed), it has nothing else to offer.

#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip {

class GivenPlanTaskPlanner final : public TaskPlanner {
 public:
  /// `source` names where the plan came from in messages ("plan file plan.json").
  GivenPlanTaskPlanner(Plan plan, std::string source) : plan_(std::move(plan)), source_(std::move(source)) {}

  /// "given plan".
  [[nodiscard]] std::string name() const override { return "given plan"; }
  /// The plan; a PlanningError when asked again after it failed (earlier attempts present).
  Plan plan(const PlanningRequest& request, const StopCondition& stop, PlanningStatistics& statistics) override;

 private:
  Plan plan_;
  std::string source_;
};

}  // namespace lang2manip
