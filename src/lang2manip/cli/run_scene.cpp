#include "lang2manip/cli/run_scene.hpp"

#include <algorithm>
#include <set>

#include "lang2manip/cli/run_report.hpp"
#include "lang2manip/model/gltf_writer.hpp"
#include "lang2manip/symbolic/plan_json.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

const Vector4 kToolPathColour(0.9, 0.1, 0.1, 1.0);

/// The exploration graphs of `action`'s transits, projected to the tool frame's position.
void addTrees(const ActionExecution& action, const ArmContext& arm, GlbBuilder& builder) {
  for (std::size_t k = 0; k < action.segments.size(); ++k) {
    const MotionSegment& segment = action.segments[k];
    std::vector<Vector3> points;
    for (const VectorX& q : segment.tree.vertices) points.push_back(arm.toolPose(segment.world, q).translation());
    addExplorationGraph(builder, "exploration_tree/" + std::to_string(action.index) + "/" + std::to_string(k), points, segment.tree.edges);
  }
}

/// The push segment of `action` under way at `time` (seconds from the action's start) and how far
/// it has gone (0 to 1); null when no push is.
std::pair<const MotionSegment*, double> pushAt(const ActionExecution& action, double time) {
  for (std::size_t k = 0; k < action.segments.size() && k < action.segmentEndTimes.size(); ++k) {
    const double begin = k == 0 ? 0.0 : action.segmentEndTimes[k - 1];
    const double end = action.segmentEndTimes[k];
    if (!action.segments[k].carried.empty() && time >= begin && time <= end + 1e-9) {
      return {&action.segments[k], end > begin ? (time - begin) / (end - begin) : 1.0};
    }
  }
  return {nullptr, 0.0};
}

/// The world during the motion at `time` (seconds from the start of the action).
const Scene& worldAt(const ActionExecution& action, double time, const Scene& fallback) {
  for (std::size_t k = 0; k < action.segments.size() && k < action.segmentEndTimes.size(); ++k) {
    if (time <= action.segmentEndTimes[k] + 1e-9) return action.segments[k].world;
  }
  return action.segments.empty() ? fallback : action.segments.back().world;
}

/// Objects any segment of the run carries: only those get animation tracks.
std::set<std::string> carriedObjects(const ExecutionRecord& execution) {
  std::set<std::string> carried;
  for (const ActionExecution& action : execution.actions) {
    for (const MotionSegment& segment : action.segments) {
      for (const SceneObject& object : segment.world.objects()) {
        if (segment.world.findAttachment(object.name) != nullptr) carried.insert(object.name);
      }
      if (!segment.carried.empty()) carried.insert(segment.carried);
    }
  }
  return carried;
}

/// Body poses of one moment: the robot's links, then the tracked objects.
struct Frame {
  double time = 0.0;
  std::vector<Pose> poses;
};

class Animator {
 public:
  Animator(const ArmContext& arm, std::vector<std::string> objects) : arm_(arm), objects_(std::move(objects)) {}

  Frame frame(double time, const Scene& world, const VectorX& q, const MotionSegment* push, double pushFraction) const {
    Frame frame{time, {}};
    const SceneRobot& robot = world.robot(arm_.robotName());
    for (const Pose& X_BL : robot.model->linkPoses(q)) frame.poses.push_back(robot.basePose * X_BL);
    Scene moved = world;
    moved.setConfiguration(arm_.robotName(), q);
    for (const std::string& name : objects_) {
      Pose pose = moved.objectWorldPose(name);
      if (push != nullptr && push->carried == name) pose.translation() = push->carriedStart.translation() + pushFraction * push->carriedDisplacement;
      frame.poses.push_back(pose);
    }
    return frame;
  }

 private:
  const ArmContext& arm_;
  std::vector<std::string> objects_;
};

/// The grasps and releases of `action` (started at `start` in the run) as {"time", "label"}.
void addGripperMoments(const ActionExecution& action, double start, json& moments) {
  for (std::size_t k = 0; k < action.segments.size() && k < action.segmentEndTimes.size(); ++k) {
    const GripperEvent event = action.segments[k].gripperEvent;
    if (event == GripperEvent::kNone) continue;
    moments.push_back({{"time", start + action.segmentEndTimes[k]},
                       {"label", (event == GripperEvent::kGrasp ? "grasp " : "release ") + action.action.object}});
  }
}

}  // namespace

void addExplorationGraph(GlbBuilder& builder, const std::string& name, const std::vector<Vector3>& points,
                         const std::vector<std::pair<int, int>>& edges) {
  if (edges.empty()) return;
  std::vector<std::pair<Vector3, Vector3>> lines;
  for (const auto& [from, to] : edges) lines.emplace_back(points[static_cast<std::size_t>(from)], points[static_cast<std::size_t>(to)]);
  builder.addLines("exploration_tree", name, lines, Vector4(0.1, 0.7, 0.2, 1.0));
}

std::string runSceneGlb(const Scene& initial, const ArmContext& arm, const ExecutionRecord* execution) {
  GlbBuilder builder(GltfGeometry::kBoth, 24);
  const std::vector<int> nodes = addSceneBodies(initial, builder);
  if (execution == nullptr) return builder.finish();
  const SceneRobot& robot = initial.robot(arm.robotName());
  std::size_t firstLink = 0;
  for (const SceneRobot& other : initial.robots()) {
    if (other.name == robot.name) break;
    firstLink += other.model->links().size();
  }
  std::size_t links = 0;
  for (const SceneRobot& other : initial.robots()) links += other.model->links().size();
  const std::set<std::string> carried = carriedObjects(*execution);
  std::vector<std::string> objects;
  std::vector<int> tracked(nodes.begin() + static_cast<std::ptrdiff_t>(firstLink),
                           nodes.begin() + static_cast<std::ptrdiff_t>(firstLink + robot.model->links().size()));
  for (std::size_t o = 0; o < initial.objects().size(); ++o) {
    if (carried.count(initial.objects()[o].name) == 0) continue;
    objects.push_back(initial.objects()[o].name);
    tracked.push_back(nodes[links + o]);
  }
  const Animator animator(arm, objects);
  std::vector<Frame> frames;
  for (const auto& [action, trajectory] : timedActions(*execution)) {
    std::vector<Vector3> toolPath;
    const double start = trajectory.points.empty() ? 0.0 : trajectory.points.front().time;
    for (const TrajectoryPoint& point : trajectory.points) {
      const double local = point.time - start;
      const Scene& world = worldAt(*action, local, initial);
      const auto [push, fraction] = pushAt(*action, local);
      if (frames.empty() || point.time > frames.back().time) frames.push_back(animator.frame(point.time, world, point.positions, push, fraction));
      toolPath.push_back(arm.toolPose(world, point.positions).translation());
    }
    builder.addPolyline("tool_paths", "tool_path/" + std::to_string(action->index), toolPath, kToolPathColour);
    addTrees(*action, arm, builder);
  }
  if (frames.size() >= 2) {
    std::vector<double> times;
    for (const Frame& frame : frames) times.push_back(frame.time);
    std::vector<std::pair<int, std::vector<Pose>>> tracks;
    for (std::size_t b = 0; b < tracked.size(); ++b) {
      std::vector<Pose> poses;
      for (const Frame& frame : frames) poses.push_back(frame.poses[b]);
      tracks.emplace_back(tracked[b], std::move(poses));
    }
    builder.addAnimation("trajectory", times, tracks);
  }
  return builder.finish();
}

json viewerRunDocument(const std::string& task, const json& report, const ExecutionRecord* execution, const std::string& robot,
                       const std::string& observation, const std::string& prompt) {
  json actions = json::array();
  json moments = json::array({{{"time", 0.0}, {"label", "start"}}});
  double duration = 0.0;
  if (execution != nullptr) {
    double time = 0.0;
    for (const ActionExecution& action : execution->actions) {
      if (action.status == ActionStatus::kSucceeded) addGripperMoments(action, time, moments);
      const double end = time + (action.status == ActionStatus::kSucceeded ? action.trajectory.duration() : 0.0);
      json entry{{"index", action.index}, {"kind", actionTypeName(action.action.type)}, {"object", action.action.object},
                 {"status", actionStatusName(action.status)}, {"start_time", time}, {"end_time", end},
                 {"text", describeAction(action.action) + (action.status == ActionStatus::kFailed ? ": " + action.reason : "")}};
      actions.push_back(std::move(entry));
      time = end;
    }
    duration = time;
  }
  if (duration > 0.0) moments.push_back({{"time", duration}, {"label", "end"}});
  return {{"format_version", 1}, {"task", task}, {"success", report.value("success", false)}, {"duration", duration}, {"robot", robot},
          {"actions", actions}, {"moments", moments}, {"observation", observation}, {"prompt", prompt}, {"report", report}};
}

}  // namespace lang2manip
