#include "lang2manip/symbolic/plan_prompt.hpp"

#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"

namespace lang2manip {
namespace {

constexpr const char* kRole = R"(You are the task planner of a robot manipulator. You turn a task given in plain language into a plan of symbolic actions that the robot's motion layer grounds into collision-free motions. You see the environment as a textual observation: the robot (joints, end effector, gripper), the objects (name, kind, pose, size, whether they are movable, containers or supports) and the relations between them. Positions are in metres; directions are in the robot base frame: x points in front of the robot, y to its left, z up.
)";

constexpr const char* kGrammar = R"(
ACTION GRAMMAR. Each action is a(o, p, r, kappa): an action type, the object o it acts on, parameters p, refinements r and an optional motion planner kappa.
- pick: grasp object o and lift it. params: null.
- place: put the held object o somewhere. params: a relation ("in", "on", "left_of", "right_of", "in_front_of", "behind", "next_to") with a target object (and, for the side relations and next_to, an optional distance in metres; for "on", an optional region of the target's top face: one of the corners "far_left_corner", "far_right_corner", "near_left_corner", "near_right_corner", the edges (sides) "far_edge", "near_edge", "left_edge", "right_edge", "centre", the halves "far_half", "near_half", "left_half", "right_half", or the quadrants "far_left_quadrant", ...; "top" and "front" mean far, "bottom" and "back" near), or an explicit position {x, y, z} (with an optional orientation quaternion {w, x, y, z}).
- move: move the gripper to a named configuration such as "home" (params.configuration; object null) or to a position; with object = the held object it carries it there.
- push: push object o with the gripper. params: a unit direction {x, y, z} and a distance in metres.
- refinements: null, or {"grasp": "top" | "side" | "front" | "auto", "approach": unit vector or null}.
- planner: null for the default motion planner, or one of the planner names given below.
)";

constexpr const char* kRules = R"(
RULES.
1. Use only object names that appear in the observation, exactly as written.
2. The robot has one gripper per arm and holds at most one object: pick an object before placing it, and place it before picking another one.
3. Pick only movable objects that are clear (nothing on or in them). Place "in" only into containers; place "on" only onto supports or onto clear objects.
4. Push needs a free gripper.
5. Give every field of every action; use null for values that do not apply.
6. Answer with ONE JSON object that follows the schema below and nothing else: no prose, no code fences. Put any explanation in "reasoning".
7. In "goals", state the final state the task asks for, one condition per entry: {"kind": "relation", "object", "relation", "target", "region"} (an object in, on or beside another at the end; region: for on, the region of the target's top it stands in, or null), {"kind": "holding", "object"} (the robot still holds it), {"kind": "displaced", "object", "displacement": {x, y, z}} (moved by that many metres), {"kind": "at_configuration", "configuration"} (e.g. "home"), {"kind": "handed_over", "object"} (held out to the person: move it with params.position {"x": 0.40, "y": 0.0, "z": 0.25}, the handover position of the tool), {"kind": "at_position", "object", "position": {x, y, z}, "target"} (its frame's origin at that base-frame position; target: whose place it was, or null), {"kind": "turned", "object", "angle"} (turned about the vertical by that many radians from where it started, standing where it stood: place it at its own position with the turned orientation), {"kind": "facing", "object", "target"} (its long side points at target) or {"kind": "facing", "object", "angle"} (its long side along that base-frame heading in radians, 0 = front), {"kind": "arranged", "members": [objects], "shape", "target", "region", "heading", "evenly_spaced", "distance"} (the members stand together in a shape seen from above, each on target (a support, or null) and in its region (or null): "line" (centres within the distance tolerance of one line; heading: its base-frame direction in radians when the task names one, 0 = away from the robot, pi/2 = sideways; evenly_spaced: neighbours equally far apart; distance: the spacing of neighbouring centres), "circle" (on one circle, spread around it), "triangle" (3 members at the corners of an equilateral triangle, or 6, 9, ...: the corners and as many more evenly along each side), "square" (4 members at the corners of a square, or 8, 12, ... likewise), "spread_out" (no two next_to each other), "together" (next to each other: one group, each member next_to another), "pyramid" (3, 6 or 10 members in rows of k, k - 1, ..., 1: the base row in a line on target, side by side about 2 cm apart (room for the fingers), each higher member over the middle of two neighbours below, resting on both); place each member at a position of the shape with params.position (for a pyramid's higher rows, its z raised by the height of the row below, base row first)). Only the end state: not a step a later action undoes (a pick followed by a place of the same object is not "holding"). Every goal is checked against the world after the plan runs.
8. To put an object where another one stands, or to swap two objects, first set the one in the way aside on a free spot of the support (a place at an explicit position clear of everything), then move the other, then bring the first where it belongs.
9. If an earlier answer was rejected, read the failure, fix the plan and answer again with a complete plan.
)";

constexpr const char* kExample = R"(
EXAMPLE. Task: "put the cube in the box" (objects: table, cube, box). Answer:
{"reasoning": "pick the cube, then place it in the box", "actions": [
 {"action": "pick", "object": "cube", "params": null, "refinements": {"grasp": "top", "approach": null}, "planner": null},
 {"action": "place", "object": "cube", "params": {"relation": "in", "target": "box", "distance": null, "position": null, "orientation": null, "configuration": null, "direction": null, "region": null}, "refinements": null, "planner": null}],
 "goals": [{"kind": "relation", "object": "cube", "relation": "in", "target": "box", "distance": null, "displacement": null, "configuration": null, "position": null, "angle": null, "region": null, "members": null, "shape": null, "heading": null, "evenly_spaced": null}]}
)";

std::string planListLine(const std::vector<std::string>& planners) {
  if (planners.empty()) return "Motion planners: use null (the default planner).\n";
  std::string text;
  for (const std::string& name : planners) text += (text.empty() ? "" : ", ") + name;
  return "Motion planners you may name (or null for the default): " + text + ".\n";
}

std::string roleName(LlmMessage::Role role) { return role == LlmMessage::Role::kUser ? "user" : "assistant"; }

}  // namespace

std::string planSystemPrompt(const std::vector<std::string>& planners) {
  return std::string(kRole) + "SPATIAL CONVENTIONS: " + spatialConventions() + ".\n" + kGrammar + kRules + "\nSCHEMA of the answer (JSON Schema):\n" +
         planJsonSchema().dump() + "\n" + kExample + "\n" + planListLine(planners) +
         "(prompt version " + kPlanPromptVersion + ")\n";
}

std::string planTaskMessage(const std::string& task, const std::string& observation) {
  return "TASK: " + task + "\n\nOBSERVATION of the current environment:\n" + observation +
         "\nAnswer with the JSON plan for the task.";
}

std::string planRepairMessage(const PlanAttempt& attempt, int attemptNumber) {
  return "Your answer " + std::to_string(attemptNumber) + " was not accepted:\n" + attempt.failure +
         "\n\nFix these problems and answer again with a complete JSON plan for the same task, "
         "starting from the same initial state.";
}

std::vector<LlmMessage> planMessages(const std::string& task, const std::string& observation,
                                     const std::vector<PlanAttempt>& earlierAttempts, std::size_t maxAttempts) {
  std::vector<LlmMessage> messages{{LlmMessage::Role::kUser, planTaskMessage(task, observation)}};
  const std::size_t first = earlierAttempts.size() > maxAttempts ? earlierAttempts.size() - maxAttempts : 0;
  if (first > 0) {
    messages.front().content += "\n\n(" + std::to_string(first) + " earlier answers were also rejected; the last " +
                                std::to_string(earlierAttempts.size() - first) + " follow.)";
  }
  for (std::size_t i = first; i < earlierAttempts.size(); ++i) {
    const PlanAttempt& attempt = earlierAttempts[i];
    messages.push_back({LlmMessage::Role::kAssistant, attempt.answer.empty() ? "(empty answer)" : attempt.answer});
    messages.push_back({LlmMessage::Role::kUser, planRepairMessage(attempt, static_cast<int>(i + 1))});
  }
  return messages;
}

std::string renderPrompt(const std::string& system, const std::vector<LlmMessage>& messages) {
  std::string text = "=== system ===\n" + system;
  for (const LlmMessage& message : messages) {
    text += "\n=== " + roleName(message.role) + " ===\n" + message.content + "\n";
  }
  return text;
}

}  // namespace lang2manip
