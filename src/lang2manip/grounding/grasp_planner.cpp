#include "lang2manip/grounding/grasp_planner.hpp"

#include <array>
#include <cmath>

#include "lang2manip/core/error.hpp"
#include "lang2manip/grounding/heuristic_grasp_planner.hpp"
#include "lang2manip/grounding/object_geometry.hpp"

namespace lang2manip {
namespace {

const std::array<GraspPlannerEntry, 1> kRegistry{{
    {"heuristic", "top, front and side grasps from the object's shape, ranked by reachability and clearance",
     &makeHeuristicGraspPlanner},
}};

}  // namespace

std::string graspFailureName(GraspFailure failure) {
  switch (failure) {
    case GraspFailure::kNone: return "none";
    case GraspFailure::kNotGraspable: return "not graspable";
    case GraspFailure::kTooWide: return "too wide";
    case GraspFailure::kNoCandidate: return "no candidate";
    case GraspFailure::kUnreachable: return "unreachable";
    case GraspFailure::kInCollision: return "in collision";
  }
  return "unknown";
}

std::span<const GraspPlannerEntry> graspPlannerRegistry() { return kRegistry; }

std::vector<std::string> graspPlannerNames() {
  std::vector<std::string> names;
  for (const GraspPlannerEntry& entry : kRegistry) names.emplace_back(entry.name);
  return names;
}

std::string defaultGraspPlannerName() { return std::string(kRegistry.front().name); }

std::unique_ptr<GraspPlanner> makeGraspPlanner(const std::string& name) {
  std::string names;
  for (const GraspPlannerEntry& entry : kRegistry) {
    if (entry.name == name) return entry.make();
    names += (names.empty() ? "" : ", ") + std::string(entry.name);
  }
  throw InputError("grasp planner: unknown name \"" + name + "\" (grasp planners: " + names + ")");
}

void checkGraspSettings(const GraspSettings& s) {
  requireSettingLength(s.approachDistance, "grasp", "approachDistance");
  requireSettingLength(s.liftDistance, "grasp", "liftDistance");
  requireSettingLength(s.openingMargin, "grasp", "openingMargin");
  requireSettingLength(s.supportClearance, "grasp", "supportClearance");
  requireSettingLength(s.minimumEngagement, "grasp", "minimumEngagement");
  requireSettingLength(s.sectorHalfAngle, "grasp", "sectorHalfAngle");
  for (double pitch : s.approachPitches) {
    if (!std::isfinite(pitch) || pitch < 0.0 || pitch >= M_PI / 2.0) throw InputError("grasp settings: approachPitches must be in [0, pi/2)");
  }
  if (s.approachPitches.empty()) throw InputError("grasp settings: approachPitches must not be empty");
  for (double tilt : s.widenedTopTilts) {
    if (!std::isfinite(tilt) || tilt <= 0.0 || tilt >= M_PI / 2.0) throw InputError("grasp settings: widenedTopTilts must be in (0, pi/2)");
  }
  requireSettingCount(s.topYawSteps, "grasp", "topYawSteps");
  requireSettingCount(s.maxCandidates, "grasp", "maxCandidates");
  requireSettingCount(s.maxReachChecks, "grasp", "maxReachChecks");
}

}  // namespace lang2manip
