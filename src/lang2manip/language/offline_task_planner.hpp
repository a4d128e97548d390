#pragma once
/// @file The offline task planner (the default, deterministic, no network): understands the
/// instruction over the scene's objects, observes the symbolic state from geometry and
/// sequences the goals into a plan. It answers the grounding failures of earlier attempts from
/// their data, never their words: another grasp direction, carrying instead of a push that failed,
/// the next free spot for an object set aside, a turn in more steps, the other order of filling a
/// container whose earlier object blocked a later one (unless the instruction orders its steps);
/// and says "nothing new to try" with the reason otherwise.

#include <string>

#include "lang2manip/language/sequencer.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip {

/// What the sequencer needs of `scene`: a container's room is the floor area of its cavity; an
/// object's footprint is the product of its two smallest extents (it may go in standing up);
/// every object's layout and every support's flat top in the base frame of `robot` (the first
/// robot when empty).
SequencingOptions sequencingOptionsFor(const Scene& scene, const std::string& robot = {});

/// The grasp directions the offline planner tries in turn after grasp failures of an object.
std::vector<GraspDirection> graspRetryOrder();

class OfflineTaskPlanner final : public TaskPlanner {
 public:
  /// "offline".
  [[nodiscard]] std::string name() const override { return "offline"; }

  /// A plan for `request`. Throws PlanningError when the request has no scene, the stop
  /// condition has fired, the instruction cannot be grounded, no order of actions works, or
  /// the earlier attempts failed in ways it has no new answer to (the message says which).
  /// Thread-safe: the planner holds no state.
  Plan plan(const PlanningRequest& request, const StopCondition& stop,
            PlanningStatistics& statistics) override;
};

}  // namespace lang2manip
