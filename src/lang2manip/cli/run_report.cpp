#include "lang2manip/cli/run_report.hpp"

#include <sstream>

#include "lang2manip/grounding/object_geometry.hpp"
#include "lang2manip/llm/llm_json.hpp"
#include "lang2manip/symbolic/plan_json.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

json vectorJson(const Vector3& v) { return {v.x(), v.y(), v.z()}; }

json runPoseJson(const Pose& pose) {
  const Quaternion q(pose.linear());
  return {{"position", vectorJson(pose.translation())}, {"orientation_wxyz", {q.w(), q.x(), q.y(), q.z()}}};
}

JointTrajectory shiftedBy(JointTrajectory trajectory, double seconds) {
  for (TrajectoryPoint& point : trajectory.points) point.time += seconds;
  return trajectory;
}

/// Path lengths (joint space): the transit planners' paths before and after simplification,
/// and the path the trajectory follows.
struct PathLengths {
  double planned = 0.0;
  double simplified = 0.0;
  double executed = 0.0;

  PathLengths& operator+=(const PathLengths& other) {
    planned += other.planned;
    simplified += other.simplified;
    executed += other.executed;
    return *this;
  }
  [[nodiscard]] json toJson() const { return {{"transits_planned", planned}, {"transits_simplified", simplified}, {"executed", executed}}; }
};

PathLengths pathLengths(const ActionExecution& action) {
  PathLengths lengths;
  for (const MotionSegment& segment : action.segments) {
    lengths.planned += segment.plannedLength;
    lengths.simplified += segment.simplifiedLength;
  }
  lengths.executed = action.quality.pathLength;
  return lengths;
}

json qualityJson(const TrajectoryQuality& quality) {
  return {{"stops_inside_runs", quality.stopsInsideRuns}, {"blended_corners", quality.blendedCorners},
          {"reduced_blends", quality.reducedBlends}, {"rest_to_rest_fallbacks", quality.restToRestFallbacks},
          {"jerk_limited_runs", quality.jerkLimitedRuns}, {"jerk_reduced_runs", quality.jerkReducedRuns},
          {"seconds", quality.seconds}};
}

json actionJson(const ActionExecution& action) {
  json segments = json::array();
  for (const MotionSegment& segment : action.segments) {
    json entry = {{"label", segment.label}, {"waypoints", segment.waypoints.size()}};
    if (!segment.planner.empty()) {
      entry["planner"] = segment.planner;
      entry["path_length"] = {{"planned", segment.plannedLength}, {"simplified", segment.simplifiedLength}};
    }
    segments.push_back(entry);
  }
  json entry = {{"step", action.index + 1},
                {"action", toJson(action.action)},
                {"description", describeAction(action.action)},
                {"status", actionStatusName(action.status)},
                {"motions", segments},
                {"duration", action.trajectory.duration()},
                {"runs", action.runs.size()},
                {"trajectory", qualityJson(action.quality)},
                {"path_length", pathLengths(action).toJson()},
                {"seconds", {{"grasp", action.times.grasp}, {"placement", action.times.placement},
                             {"ik", action.times.ik}, {"motion", action.times.motion}}}};
  if (!action.choice.empty()) entry["choice"] = action.choice;
  if (action.status == ActionStatus::kFailed) {
    entry["stage"] = action.stage;
    entry["reason"] = action.reason;
  }
  return entry;
}

json goalsJson(const RunOutcome& outcome) {
  json goals = json::array();
  for (const GoalOutcome& goal : outcome.verification.goals) {
    goals.push_back({{"goal", describeGoal(goal.goal)}, {"holds", goal.holds}, {"explanation", goal.explanation}});
  }
  return goals;
}

json finalPosesJson(const Scene& scene) {
  json poses = json::object();
  for (const SceneObject& object : scene.objects()) {
    json entry = runPoseJson(currentObjectPose(scene, object.name));
    if (const Attachment* held = scene.findAttachment(object.name)) entry["held_by"] = held->robot + "/" + held->link;
    poses[object.name] = entry;
  }
  return poses;
}

json roundsJson(const RepairResult& repair) {
  json rounds = json::array();
  for (const RepairRound& round : repair.rounds) {
    json entry = {{"round", round.round}, {"outcome", roundOutcomeName(round.outcome)}};
    if (round.outcome != RoundOutcome::kAccepted) entry["failure"] = round.attempt.failure;
    if (round.attempt.plan) entry["plan"] = toJson(*round.attempt.plan);
    if (const auto& failure = round.attempt.grounding) {
      entry["grounding_failure"] = {{"action_index", failure->actionIndex}, {"stage", failure->stage},
                                    {"object", failure->object}, {"reason", failure->reason},
                                    {"blocking_objects", failure->blockingObjects},
                                    {"object_ungraspable", failure->objectUngraspable}};
    }
    rounds.push_back(entry);
  }
  return rounds;
}

struct Totals {
  StageTimes times;
  ExecutionCounters counters;
};

Totals totals(const RunOutcome& outcome) {
  Totals sum;
  if (outcome.executions == nullptr) return sum;
  for (const ExecutionRecord& record : *outcome.executions) {
    sum.times += record.times;
    sum.counters += record.counters;
  }
  return sum;
}

std::string fixed(double value, int decimals) {
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(decimals);
  text << value;
  return text.str();
}

}  // namespace

std::vector<std::pair<const ActionExecution*, JointTrajectory>> timedActions(const ExecutionRecord& execution) {
  std::vector<std::pair<const ActionExecution*, JointTrajectory>> timed;
  double start = 0.0;
  for (const ActionExecution& action : execution.actions) {
    if (action.status != ActionStatus::kSucceeded) continue;
    timed.emplace_back(&action, shiftedBy(action.trajectory, start));
    start += action.trajectory.duration();
  }
  return timed;
}

json runReportJson(const RunOutcome& outcome) {
  const Totals sum = totals(outcome);
  const PlanningStatistics& llm = outcome.repair.statistics;
  json report = {{"success", outcome.success()},
                 {"problem", outcome.problem},
                 {"task", outcome.task},
                 {"task_planner", outcome.taskPlanner},
                 {"robot", outcome.robot},
                 {"manipulator", outcome.manipulator},
                 {"seed", outcome.seed},
                 {"goal_source", outcome.goalSource},
                 {"goals", goalsJson(outcome)},
                 {"rounds", roundsJson(outcome.repair)}};
  if (!outcome.repair.succeeded()) report["failure"] = outcome.repair.failure;
  json actions = json::array();
  if (outcome.execution != nullptr) {
    for (const ActionExecution& action : outcome.execution->actions) actions.push_back(actionJson(action));
    report["final_poses"] = finalPosesJson(outcome.execution->finalScene);
    double duration = 0.0;
    TrajectoryQuality quality;
    PathLengths lengths;
    for (const ActionExecution& action : outcome.execution->actions) {
      duration += action.trajectory.duration();
      quality += action.quality;
      lengths += pathLengths(action);
    }
    report["trajectory_duration"] = duration;
    report["trajectory"] = qualityJson(quality);
    report["trajectory"]["duration"] = duration;
    report["trajectory"]["timing"] = outcome.timing;
    report["trajectory"]["velocity_scaling"] = outcome.scaling.velocity;
    report["trajectory"]["acceleration_scaling"] = outcome.scaling.acceleration;
    report["trajectory"]["scaling_from"] = {{"velocity", outcome.scaling.velocitySource},
                                            {"acceleration", outcome.scaling.accelerationSource}};
    report["trajectory"]["position_margin"] = {{"angular", outcome.scaling.positionMargin.angular},
                                               {"linear", outcome.scaling.positionMargin.linear}};
    report["path_length"] = lengths.toJson();
  }
  report["actions"] = actions;
  report["verification"] = {{"collision_free", outcome.verification.collision.empty()},
                            {"collision", outcome.verification.collision},
                            {"disturbed_objects", outcome.verification.disturbedObjects},
                            {"motions_checked", outcome.verification.segmentsChecked},
                            {"states_checked", outcome.verification.collisionChecks}};
  report["seconds"] = {{"observation", outcome.observationSeconds},
                       {"planning", llm.planningSeconds},
                       {"grasp", sum.times.grasp},
                       {"placement", sum.times.placement},
                       {"ik", sum.times.ik},
                       {"motion", sum.times.motion},
                       {"verification", outcome.verification.seconds},
                       {"total", outcome.totalSeconds}};
  report["counts"] = {{"planner_rounds", outcome.repair.rounds.size()},
                      {"executions", outcome.executions ? outcome.executions->size() : 0},
                      {"motion_planner_calls", sum.counters.plannerCalls},
                      {"motion_planner_solved", sum.counters.plannerSolved},
                      {"grasp_plans", sum.counters.graspPlans},
                      {"placement_plans", sum.counters.placementPlans},
                      {"llm_calls", llm.llmCalls},
                      {"llm_input_tokens", tokenCountJson(llm.inputTokens)},
                      {"llm_output_tokens", tokenCountJson(llm.outputTokens)},
                      {"ik_calls", sum.counters.ikCalls},
                      {"collision_checks", sum.counters.collisionChecks + outcome.verification.collisionChecks}};
  return report;
}

std::string runSummary(const RunOutcome& outcome) {
  std::ostringstream out;
  out << (outcome.success() ? "SUCCESS" : "FAILED") << ": \"" << outcome.task << "\" on " << outcome.problem << " ("
      << outcome.robot << (outcome.manipulator.empty() ? "" : "/" + outcome.manipulator) << ", " << outcome.taskPlanner << ")\n";
  if (!outcome.repair.succeeded()) out << "  " << outcome.repair.failure << '\n';
  if (outcome.execution != nullptr) {
    for (const ActionExecution& action : outcome.execution->actions) {
      out << "  " << action.index + 1 << ". " << describeAction(action.action) << ": " << actionStatusName(action.status);
      if (action.status == ActionStatus::kSucceeded) out << " (" << fixed(action.trajectory.duration(), 2) << " s of motion)";
      if (action.status == ActionStatus::kFailed) out << " [" << action.stage << "] " << action.reason;
      out << '\n';
    }
  }
  for (const GoalOutcome& goal : outcome.verification.goals) {
    out << "  goal " << describeGoal(goal.goal) << ": " << (goal.holds ? "holds" : "does not hold") << " (" << goal.explanation << ")\n";
  }
  if (!outcome.verification.collision.empty()) out << "  collision: " << outcome.verification.collision << '\n';
  for (const std::string& moved : outcome.verification.disturbedObjects) out << "  disturbed: " << moved << '\n';
  const Totals sum = totals(outcome);
  out << "  rounds " << outcome.repair.rounds.size() << ", motion planner calls " << sum.counters.plannerCalls << ", IK calls "
      << sum.counters.ikCalls << ", total " << fixed(outcome.totalSeconds * 1000.0, 1) << " ms\n";
  return out.str();
}

}  // namespace lang2manip
