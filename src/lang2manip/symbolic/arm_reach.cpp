#include "lang2manip/symbolic/arm_reach.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <string>

#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/kinematics/ik_solver.hpp"
#include "lang2manip/model/geometry.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kRayFirst = -120.0 * kDegree;
constexpr int kRays = 17;
constexpr double kRayStep = 15.0 * kDegree;
constexpr double kRadiusStep = 0.02;
constexpr double kNearestRadius = 0.04;
/// Tool-frame heights above the top the arm must reach at every point of its reach.
constexpr double kHeights[] = {0.02, 0.12};
/// Attempts for the first point of a ray (from the middle configuration) and for each next one
/// (seeded with its neighbour's solution).
constexpr int kFirstAttempts = 24;
constexpr int kNextAttempts = 3;
constexpr std::uint64_t kIkSeed = 11;
/// Restarts (other random seeds) of a search whose solution hits the robot itself.
constexpr std::uint64_t kSelfCollisionRetries = 3;

/// True when a configuration keeps the robot clear of itself.
using FreeOfItself = std::function<bool(const VectorX&)>;

/// What the measurement needs of one arm: chain frames, the hand's axis and the shoulder.
struct ArmFrames {
  const Manipulator* manipulator = nullptr;
  /// X_base(chain base) and the hand's direction in the tool frame (from the wrist to the tool).
  Pose baseToChain = Pose::Identity();
  Vector3 handAxis = Vector3::UnitZ();
  Vector3 shoulder = Vector3::Zero();
  double span = 0.0;
};

std::optional<int> shoulderJoint(const RobotModel& model, const Manipulator& manipulator, const std::vector<Pose>& links) {
  std::optional<int> first;
  for (const std::string& name : manipulator.armJoints) {
    const auto joint = model.findJoint(name);
    if (!joint) continue;
    if (!first) first = joint;
    const Joint& data = model.joints()[static_cast<std::size_t>(*joint)];
    const Matrix3 frame = links[static_cast<std::size_t>(model.parentLinkOf(*joint))].linear() * data.origin.linear();
    if (std::abs((frame * data.axis).z()) < 0.7) return joint;
  }
  return first;
}

std::optional<ArmFrames> armFrames(const SceneRobot& robot, const Pose& base, const Manipulator& manipulator) {
  const RobotModel& model = *robot.model;
  const std::vector<Pose> links = model.linkPoses(model.middleConfiguration());
  if (manipulator.armJoints.empty()) return std::nullopt;
  const auto first = shoulderJoint(model, manipulator, links);
  const auto last = model.findJoint(manipulator.armJoints.back());
  const auto tool = model.findLink(manipulator.toolFrame);
  const auto chainBase = model.findLink(manipulator.baseLink);
  if (!first || !last || !tool || !chainBase) return std::nullopt;
  const Pose rootInBase = base.inverse() * robot.basePose;
  const auto at = [&](int link) { return Vector3(rootInBase * links[static_cast<std::size_t>(link)].translation()); };
  ArmFrames frames;
  frames.manipulator = &manipulator;
  frames.baseToChain = rootInBase * links[static_cast<std::size_t>(*chainBase)];
  const Pose& X_RT = links[static_cast<std::size_t>(*tool)];
  const Vector3 wristToTool = X_RT.translation() - links[static_cast<std::size_t>(model.childLinkOf(*last))].translation();
  if (wristToTool.norm() > 0.01) frames.handAxis = (X_RT.linear().transpose() * wristToTool).normalized();
  frames.shoulder = at(model.childLinkOf(*first));
  if (const auto pan = model.findJoint(manipulator.armJoints.front()); pan && *pan != *first) {
    frames.shoulder.head<2>() = at(model.childLinkOf(*pan)).head<2>();
  }
  double span = 0.0;  // an upper bound of the horizontal reach: the chain's links end to end
  for (const std::string& name : manipulator.armJoints) {
    if (const auto joint = model.findJoint(name)) span += model.joints()[static_cast<std::size_t>(*joint)].origin.translation().norm();
  }
  frames.span = span + wristToTool.norm();
  return frames;
}

/// Solves IK for the tool frame at `point` (base frame) with the hand pointing straight down, as
/// it places what a top grasp holds (a grasp that leans at the pick keeps its lean, so a lean is
/// no reach the place can count on); updates `seed` to the solution when there is one.
bool reachDown(const IkSolver& solver, const SceneRobot& robot, const ArmFrames& arm, const FreeOfItself& free, const Vector3& point,
               VectorX& seed, int attempts) {
  IkRequest request;
  request.model = robot.model.get();
  request.manipulator = arm.manipulator->name;
  const Pose chainToBase = arm.baseToChain.inverse();
  request.seed = seed;
  request.timeoutSeconds = 10.0;  // never the limit: maxAttempts is, so that the answer is the machine's
  request.maxAttempts = attempts;
  request.positionTolerance = 1e-3;
  request.orientationTolerance = 1e-2;
  request.randomSeed = kIkSeed;
  request.target = IkTarget::positionAndAxis(chainToBase * point, chainToBase.linear() * -Vector3::UnitZ(), arm.handAxis);
  // A solution the arm cannot take without hitting itself (a wrist folded into its forearm near
  // the base) is no reach: other restarts are tried for one it can.
  for (std::uint64_t restart = 0; restart < kSelfCollisionRetries; ++restart) {
    request.randomSeed = kIkSeed + restart;
    const IkResult result = solver.solve(request);
    if (result.status != IkStatus::kSuccess) return false;
    if (free(result.solutions.front())) {
      seed = result.solutions.front();
      return true;
    }
  }
  return false;
}

/// [inner, outer] reached along one ray at one height (inner > outer when nothing is).
std::pair<double, double> measureRay(const IkSolver& solver, const SceneRobot& robot, const ArmFrames& arm, const FreeOfItself& free,
                                     double azimuth, double z) {
  const Vector3 direction(std::cos(azimuth), std::sin(azimuth), 0.0);
  const Vector3 origin(arm.shoulder.x(), arm.shoulder.y(), z);
  const auto point = [&](double r) -> Vector3 { return origin + r * direction; };
  const int steps = static_cast<int>(std::ceil((arm.span - kNearestRadius) / kRadiusStep));
  VectorX seed = robot.model->middleConfiguration();
  std::optional<int> start;
  for (const double share : {0.5, 0.35, 0.65, 0.2, 0.8}) {  // a first reached point, near the middle first
    const int step = static_cast<int>(std::lround(share * steps));
    if (reachDown(solver, robot, arm, free, point(kNearestRadius + step * kRadiusStep), seed, kFirstAttempts)) {
      start = step;
      break;
    }
  }
  if (!start) return {1.0, 0.0};
  const VectorX found = seed;
  // A step is seeded with its neighbour's solution; when that fails, searched again from the
  // middle with restarts, so that the boundary is where the arm stops, not where one descent did.
  const auto reachedAt = [&](int step) {
    const Vector3 target = point(kNearestRadius + step * kRadiusStep);
    if (reachDown(solver, robot, arm, free, target, seed, kNextAttempts)) return true;
    seed = robot.model->middleConfiguration();
    return reachDown(solver, robot, arm, free, target, seed, kFirstAttempts);
  };
  int outer = *start, inner = *start;
  while (outer + 1 <= steps && reachedAt(outer + 1)) ++outer;
  seed = found;
  while (inner - 1 >= 0 && reachedAt(inner - 1)) --inner;
  return {kNearestRadius + inner * kRadiusStep, kNearestRadius + outer * kRadiusStep};
}

/// The footprints of the links fixed to the root whose collision geometry rises through the top.
std::vector<AlignedBox3> bodyOnTop(const SceneRobot& robot, const Pose& base, double topZ) {
  const RobotModel& model = *robot.model;
  const std::vector<Pose> links = model.linkPoses(model.middleConfiguration());
  const Pose rootInBase = base.inverse() * robot.basePose;
  std::vector<AlignedBox3> footprints;
  for (int link = 0; link < static_cast<int>(model.links().size()); ++link) {
    bool fixed = true;
    for (int joint = model.parentJoint(link); joint >= 0 && fixed; joint = model.parentJoint(model.parentLinkOf(joint))) {
      fixed = model.joints()[static_cast<std::size_t>(joint)].type == JointType::kFixed;
    }
    if (!fixed) continue;
    for (const Shape& shape : model.links()[static_cast<std::size_t>(link)].collisions) {
      const AlignedBox3 local = shapeBounds(shape);
      if (local.isEmpty()) continue;
      AlignedBox3 box;
      for (int corner = 0; corner < 8; ++corner) box.extend(rootInBase * links[static_cast<std::size_t>(link)] * local.corner(static_cast<AlignedBox3::CornerType>(corner)));
      if (box.max().z() <= topZ + 0.005 || box.min().z() >= topZ + 0.3) continue;  // below the top, or high above it
      footprints.emplace_back(box.min() - Vector3(kBodyClearance, kBodyClearance, 0.0), box.max() + Vector3(kBodyClearance, kBodyClearance, 0.0));
    }
  }
  return footprints;
}

ArmReach measureArm(const IkSolver& solver, const SceneRobot& robot, const Pose& base, const ArmFrames& arm, double topZ) {
  // The robot alone: its own links are what a reached configuration must keep clear of.
  Scene alone;
  alone.addRobot(robot);
  const FclCollisionChecker self(std::move(alone));
  const std::unique_ptr<CollisionContext> context = self.makeContext();
  const FreeOfItself free = [&](const VectorX& q) { return self.isStateValid(0, q, *context); };
  ArmReach reach;
  reach.body = bodyOnTop(robot, base, topZ);
  reach.manipulator = arm.manipulator->name;
  reach.shoulder = arm.shoulder;
  for (int ray = 0; ray < kRays; ++ray) {
    const double azimuth = kRayFirst + ray * kRayStep;
    double inner = 0.0, outer = std::numeric_limits<double>::infinity();
    for (const double height : kHeights) {
      const auto [near, far] = measureRay(solver, robot, arm, free, azimuth, topZ + height);
      inner = std::max(inner, near);
      outer = std::min(outer, far);
    }
    reach.azimuths.push_back(azimuth);
    reach.inner.push_back(inner + kReachBoundaryMargin);
    reach.outer.push_back(outer - kReachBoundaryMargin);
  }
  return reach;
}

/// Everything the measurement depends on, as text: the joints and limits, the arm, where the
/// robot's root is in the base frame and the top's height (to a millimetre).
std::string cacheKey(const SceneRobot& robot, const Pose& base, double topZ, const std::string& manipulator) {
  std::string key = robot.model->name() + "|" + manipulator;
  char number[32];
  const auto add = [&](double value) {
    std::snprintf(number, sizeof number, "|%.4f", value);
    key += number;
  };
  for (const Joint& joint : robot.model->joints()) {
    for (int i = 0; i < 3; ++i) add(joint.origin.translation()[i]), add(joint.axis[i]);
    add(joint.limits.lower), add(joint.limits.upper);
  }
  const Pose rootInBase = base.inverse() * robot.basePose;
  for (int i = 0; i < 3; ++i) add(rootInBase.translation()[i]);
  for (int i = 0; i < 9; ++i) add(rootInBase.linear().data()[i]);
  add(std::round(topZ * 1000.0) / 1000.0);
  return key;
}

}  // namespace

bool ArmReach::reaches(const Vector3& point) const {
  for (const AlignedBox3& footprint : body) {
    if (point.x() >= footprint.min().x() && point.x() <= footprint.max().x() && point.y() >= footprint.min().y() &&
        point.y() <= footprint.max().y()) {
      return false;
    }
  }
  const Eigen::Vector2d d = point.head<2>() - shoulder.head<2>();
  const double azimuth = std::atan2(d.y(), d.x()), distance = d.norm();
  for (std::size_t i = 0; i + 1 < azimuths.size(); ++i) {
    if (azimuth < azimuths[i] || azimuth > azimuths[i + 1]) continue;
    if (inner[i] > outer[i] || inner[i + 1] > outer[i + 1]) return false;
    const double t = (azimuth - azimuths[i]) / (azimuths[i + 1] - azimuths[i]);
    return distance >= inner[i] + t * (inner[i + 1] - inner[i]) && distance <= outer[i] + t * (outer[i + 1] - outer[i]);
  }
  return false;
}

std::vector<ArmReach> measuredArmReaches(const SceneRobot& robot, const Pose& base, double topZ, const std::string& manipulator) {
  const RobotModel& model = *robot.model;
  const auto& arms = model.semantics().manipulators;
  if (!manipulator.empty() && std::none_of(arms.begin(), arms.end(), [&](const Manipulator& arm) { return arm.name == manipulator; })) {
    std::string names;
    for (const Manipulator& arm : arms) names += (names.empty() ? "" : ", ") + arm.name;
    throw InputError("robot " + robot.name + " has no arm \"" + manipulator + "\"; its arms: " + names);
  }
  static std::mutex mutex;
  static std::map<std::string, ArmReach> cache;
  static const std::unique_ptr<IkSolver> solver = makeIkSolver("dls");
  const std::lock_guard<std::mutex> lock(mutex);
  std::vector<ArmReach> reaches;
  for (const Manipulator& arm : arms) {
    if (!manipulator.empty() && arm.name != manipulator) continue;
    const std::string key = cacheKey(robot, base, topZ, arm.name);
    if (const auto found = cache.find(key); found != cache.end()) {
      reaches.push_back(found->second);
      continue;
    }
    const auto frames = armFrames(robot, base, arm);
    if (!frames) continue;
    reaches.push_back(cache.emplace(key, measureArm(*solver, robot, base, *frames, topZ)).first->second);
  }
  return reaches;
}

}  // namespace lang2manip
