#pragma once
/// @file The default grasp planner ("heuristic"): geometric candidates (grasp_candidates.hpp)
/// checked for reachability and ranked.

#include <memory>

#include "lang2manip/grounding/grasp_planner.hpp"

namespace lang2manip {

/// Generates top / front / side candidates from the object's shape, drops those wider than the
/// gripper, then checks the most promising ones (direction preference top > front > side for
/// "auto", grasps at the object's centre before grasps towards its ends) in that order:
/// IK at the grasp pose with the gripper open (the object may touch the fingers only), IK at the
/// pre-grasp pose seeded from it (no contact allowed), IK at the post-grasp lift, and the
/// clearance of the robot to the world without the object. Score (higher is better):
///   min(clearance, 0.05) / 0.05 + 0.3 * direction preference (top 1, front 2/3, side 1/3)
///   + 0.2 * (1 - |offset| / length) + 0.2 * (IK solutions found / asked).
class HeuristicGraspPlanner final : public GraspPlanner {
 public:
  [[nodiscard]] std::string name() const override { return "heuristic"; }
  [[nodiscard]] GraspPlan plan(const ReachabilityChecker& reach, const GraspRequest& request) const override;
};

std::unique_ptr<GraspPlanner> makeHeuristicGraspPlanner();

}  // namespace lang2manip
