#include "lang2manip/planning/motion_plan_json.hpp"

namespace lang2manip {

nlohmann::json motionPlanStatisticsToJson(const MotionPlanStatistics& statistics) {
  return {{"planning_seconds", statistics.planningSeconds},
          {"simplify_seconds", statistics.simplifySeconds},
          {"parameterization_seconds", statistics.parameterizationSeconds},
          {"verification_seconds", statistics.verificationSeconds},
          {"iterations", statistics.iterations},
          {"vertices", statistics.vertices},
          {"edges", statistics.edges},
          {"state_checks", statistics.stateChecks},
          {"motion_checks", statistics.motionChecks},
          {"length_before_simplification", statistics.lengthBeforeSimplification},
          {"length_after_simplification", statistics.lengthAfterSimplification},
          {"rejected_paths", statistics.rejectedPaths},
          {"repaired_segments", statistics.repairedSegments},
          {"repair_seconds", statistics.repairSeconds}};
}

nlohmann::json pathToJson(const std::vector<VectorX>& path) {
  nlohmann::json points = nlohmann::json::array();
  for (const VectorX& point : path) points.push_back(std::vector<double>(point.data(), point.data() + point.size()));
  return points;
}

}  // namespace lang2manip
