#pragma once
/// @file A run as the viewer shows it: the scene as GLB with the executed motion as an animation
/// (every link, and every object while it is carried), the tool frame's path of each action as a
/// red polyline, and the run document (task, actions with their times and status, observation,
/// prompt, report).

#include <nlohmann/json.hpp>
#include <string>

#include "lang2manip/execution/arm_motion.hpp"
#include "lang2manip/execution/execution_types.hpp"
#include "lang2manip/model/glb_builder.hpp"

namespace lang2manip {

/// An exploration graph as green lines "exploration_tree/..." (`points`: its vertices in the
/// world, `edges`: pairs of their indices); nothing when it has no edge.
void addExplorationGraph(GlbBuilder& builder, const std::string& name, const std::vector<Vector3>& points,
                         const std::vector<std::pair<int, int>>& edges);

/// The GLB of a run: `initial` with both geometries of every body, the animation "trajectory"
/// of `execution` (absent when nothing moved) and the tool paths "tool_path/<action index>".
std::string runSceneGlb(const Scene& initial, const ArmContext& arm, const ExecutionRecord* execution);

/// What the viewer lists beside the scene: {"format_version": 1, "task", "success", "duration",
/// "robot", "actions": [{"index", "kind", "object", "status", "start_time", "end_time", "text"}],
/// "moments": [{"time", "label"}] (start, each grasp and release, end), "observation", "prompt",
/// "report"}.
nlohmann::json viewerRunDocument(const std::string& task, const nlohmann::json& report, const ExecutionRecord* execution,
                                 const std::string& robot, const std::string& observation, const std::string& prompt);

}  // namespace lang2manip
