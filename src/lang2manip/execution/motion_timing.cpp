#include "lang2manip/execution/motion_timing.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <utility>

#include "lang2manip/planning/blended_path.hpp"
#include "lang2manip/planning/jerk_limiting.hpp"
#include "lang2manip/planning/time_optimal_trajectory.hpp"

namespace lang2manip {
namespace {

/// An arc that fails its checks is shrunk by this factor until it passes, and left sharp below
/// kSmallestBlend (rad): however wide the requested blends, a corner stops only where not even
/// an arc of kSmallestBlend fits.
constexpr double kBlendShrink = 0.25;
constexpr double kSmallestBlend = 1e-4;
/// Relative slack of the limit check on the samples: the phase-plane integration keeps each
/// step's path acceleration within the bounds at its ends, and the bounds move a little between.
constexpr double kLimitSlack = 2e-3;
/// Jerk limiting: the filter's input is sampled this finely (s); its output may leave the
/// blended path by at most kJerkFilterDeviation (rad, Euclidean), a twentieth of the default
/// verification resolution, else the run's acceleration is halved (at most kJerkAttempts times).
constexpr double kJerkInputInterval = 1e-3;
constexpr double kJerkFilterDeviation = 1e-4;
constexpr int kJerkAttempts = 8;

bool movesTheArm(const ArmContext& arm, const MotionSegment& segment) {
  for (const VectorX& q : segment.waypoints) {
    for (const int v : arm.armVariables()) {
      if (std::abs(q[v] - segment.waypoints.front()[v]) > 1e-9) return true;
    }
  }
  return false;
}

bool sameAttachments(const Scene& a, const Scene& b) {
  const auto names = [](const Scene& scene) {
    std::set<std::string> attached;
    for (const Attachment& attachment : scene.attachments()) attached.insert(attachment.object + "@" + attachment.link);
    return attached;
  };
  return names(a) == names(b);
}

/// Runs of segments joined without a stop: a gripper motion or a push stands alone, and a run
/// ends where the attachments change.
std::vector<TimedRun> splitIntoRuns(const ArmContext& arm, const std::vector<MotionSegment>& segments) {
  std::vector<TimedRun> runs;
  const auto standsAlone = [&](const MotionSegment& s) { return !s.carried.empty() || !movesTheArm(arm, s); };
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const bool joins = i > 0 && !standsAlone(segments[i]) && !standsAlone(segments[i - 1]) &&
                       sameAttachments(segments[i - 1].world, segments[i].world);
    if (joins) {
      runs.back().endSegment = i + 1;
    } else {
      runs.push_back({i, i + 1, {}});
    }
  }
  return runs;
}

double polylineLength(const std::vector<VectorX>& points) {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

double pointToSegmentDistance(const Vector3& p, const Vector3& a, const Vector3& b) {
  const Vector3 ab = b - a;
  const double squared = ab.squaredNorm();
  const double t = squared > 0.0 ? std::clamp((p - a).dot(ab) / squared, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

/// Checks points of a run's blended path against the segments they belong to; checkers and the
/// Cartesian moves' tool lines are made once per segment.
class RunPointChecker {
 public:
  RunPointChecker(const ArmContext& arm, const std::vector<MotionSegment>& segments) : arm_(arm), segments_(segments) {}

  /// Empty when `q` is allowed in every segment of `owners`; otherwise the forbidden contacts.
  std::string contacts(const VectorX& q, const std::vector<std::size_t>& owners) {
    for (const std::size_t owner : owners) {
      std::string found = checker(owner).forbiddenContacts(q);
      if (!found.empty()) return segments_[owner].label + ": " + found;
    }
    return {};
  }

  /// Whether the tool at `q` is within cartesianDeviation of the line of a Cartesian move among
  /// `owners` (true when none is Cartesian). Where a transit joins a Cartesian move at `corner`,
  /// the tool may also be anywhere within one cartesianStep of the corner's tool position (a
  /// blend zone, like an industrial controller's).
  bool straightEnough(const VectorX& q, const std::vector<std::size_t>& owners, const VectorX& corner) {
    double nearest = std::numeric_limits<double>::infinity();
    bool joinsATransit = false;
    for (const std::size_t owner : owners) {
      joinsATransit |= !segments_[owner].planner.empty();
    }
    for (const std::size_t owner : owners) {
      const MotionSegment& segment = segments_[owner];
      if (!segment.planner.empty()) continue;
      auto line = lines_.find(owner);
      if (line == lines_.end()) {
        line = lines_.emplace(owner, std::pair{arm_.toolPose(segment.world, segment.waypoints.front()).translation(),
                                               arm_.toolPose(segment.world, segment.waypoints.back()).translation()})
                   .first;
      }
      const Vector3 tool = arm_.toolPose(segment.world, q).translation();
      nearest = std::min(nearest, pointToSegmentDistance(tool, line->second.first, line->second.second));
    }
    if (nearest <= arm_.settings().cartesianDeviation || std::isinf(nearest)) return true;
    const MotionSegment& any = segments_[owners.front()];
    return joinsATransit && (arm_.toolPose(any.world, q).translation() - arm_.toolPose(any.world, corner).translation()).norm() <=
                                arm_.settings().cartesianStep;
  }

  [[nodiscard]] long checks() const {
    long total = 0;
    for (const auto& [owner, checker] : checkers_) total += checker->checks();
    return total;
  }

 private:
  SegmentStateChecker& checker(std::size_t owner) {
    auto found = checkers_.find(owner);
    if (found == checkers_.end()) {
      found = checkers_.emplace(owner, std::make_unique<SegmentStateChecker>(arm_, segments_[owner])).first;
    }
    return *found->second;
  }

  const ArmContext& arm_;
  const std::vector<MotionSegment>& segments_;
  std::map<std::size_t, std::unique_ptr<SegmentStateChecker>> checkers_;
  std::map<std::size_t, std::pair<Vector3, Vector3>> lines_;
};

/// The segments a piece of a blended run path belongs to: a line, the segment reaching its end
/// waypoint; an arc, both segments meeting at its corner.
std::vector<std::size_t> ownersOf(const PathSegment& piece, const RunPath& path) {
  if (piece.kind == PathSegment::Kind::kLine) return {path.segmentOf[piece.waypoint + 1]};
  const std::size_t before = path.segmentOf[piece.waypoint];
  const std::size_t after = path.segmentOf[piece.waypoint + 1];
  return before == after ? std::vector<std::size_t>{before} : std::vector<std::size_t>{before, after};
}

/// Local arc lengths from 0 to the piece's end such that no joint moves more than `resolution`
/// between two of them (the max-norm step of checkSegment): steps of resolution divided by a
/// bound on the tangent's largest component (for an arc, |x_i cos - y_i sin| <= |(x_i, y_i)|).
std::vector<double> samplesAlong(const PathSegment& piece, double resolution) {
  const VectorX bound = piece.kind == PathSegment::Kind::kLine
                            ? VectorX(piece.axisX.cwiseAbs())
                            : VectorX((piece.axisX.array().square() + piece.axisY.array().square()).sqrt());
  const double step = resolution / std::max(bound.maxCoeff(), 1e-12);
  std::vector<double> at;
  for (double u = 0.0; u < piece.length; u += step) at.push_back(u);
  at.push_back(piece.length);
  return at;
}

/// Arc lengths on a line piece at the states checkSegment() checked its segment at (the grid
/// anchored at the segment's first waypoint), and both ends: a line is a part of a verified
/// segment and is checked as it was, so that a path grazing an obstacle between two checked
/// states is not accepted by one check and refused by another.
std::vector<double> lineSamples(const PathSegment& line, const RunPath& path, double resolution) {
  const VectorX& from = path.waypoints[line.waypoint];
  const VectorX& to = path.waypoints[line.waypoint + 1];
  const double length = (to - from).norm();
  std::vector<double> at{0.0};
  if (length > 0.0) {
    const int steps = std::max(1, static_cast<int>(std::ceil((to - from).cwiseAbs().maxCoeff() / resolution)));
    const double start = (line.position(0.0) - from).norm() / length;
    for (int i = static_cast<int>(std::ceil(start * steps)); i <= steps; ++i) {
      const double u = (static_cast<double>(i) / steps - start) * length;
      if (u > 0.0 && u < line.length) at.push_back(u);
    }
  }
  at.push_back(line.length);
  return at;
}

/// Whether every sample of `arc` is allowed by its segments and, on Cartesian moves, straight.
bool arcIsAcceptable(const PathSegment& arc, const RunPath& path, double resolution, RunPointChecker& checker) {
  const std::vector<std::size_t> owners = ownersOf(arc, path);
  for (const double u : samplesAlong(arc, resolution)) {
    const VectorX q = arc.position(u);
    if (!checker.straightEnough(q, owners, path.waypoints[arc.waypoint]) || !checker.contacts(q, owners).empty()) return false;
  }
  return true;
}

/// The blend bound of each corner of `path`: settings.blendDeviation, shrunk where the arc fails.
std::vector<double> chooseBlends(const ArmContext& arm, const RunPath& path, RunPointChecker& checker,
                                 TrajectoryQuality& quality) {
  const ExecutionSettings& settings = arm.settings();
  std::vector<double> deviations(path.waypoints.size(), settings.blendDeviation);
  if (path.waypoints.size() < 3 || settings.blendDeviation == 0.0) return deviations;
  std::set<std::size_t> reduced;
  std::set<std::size_t> shrunk;  // the corners made smaller by the last attempt
  for (bool first = true;; first = false) {
    // An arc depends only on its corner's deviation: after the first pass, only the arcs made
    // smaller are checked again.
    const BlendedPath blended(path.waypoints, deviations);
    std::vector<std::size_t> failing;
    for (const PathSegment& piece : blended.segments()) {
      const bool changed = first || shrunk.count(piece.waypoint) != 0;
      if (piece.kind == PathSegment::Kind::kArc && changed &&
          !arcIsAcceptable(piece, path, settings.verificationResolution, checker)) {
        failing.push_back(piece.waypoint);
      }
    }
    if (failing.empty()) break;
    shrunk.clear();
    for (const std::size_t corner : failing) {
      reduced.insert(corner);
      shrunk.insert(corner);
      const double smaller = deviations[corner] * kBlendShrink;
      deviations[corner] = smaller < kSmallestBlend ? 0.0 : smaller;
    }
  }
  quality.reducedBlends += static_cast<int>(reduced.size());
  return deviations;
}

/// The time of the trajectory point nearest `position`, searching from point `from` on.
std::size_t nearestPoint(const JointTrajectory& trajectory, const VectorX& position, std::size_t from) {
  std::size_t best = from;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (std::size_t p = from; p < trajectory.points.size(); ++p) {
    const double distance = (trajectory.points[p].positions - position).norm();
    if (distance < bestDistance) {
      bestDistance = distance;
      best = p;
    }
  }
  return best;
}

/// Appends `part` (which starts at rest where `whole` ends) to `whole`, `offset` seconds later.
void append(JointTrajectory& whole, const JointTrajectory& part, double offset) {
  for (std::size_t p = whole.points.empty() ? 0 : 1; p < part.points.size(); ++p) {
    TrajectoryPoint point = part.points[p];
    point.time += offset;
    whole.points.push_back(std::move(point));
  }
}

/// When each segment of the run ends in `part` (the run's own trajectory).
void addSegmentEnds(const PlanningSpace& space, const RunPath& path, const JointTrajectory& part, double offset,
                    std::vector<double>& ends) {
  std::size_t from = 0;
  for (std::size_t k = 0; k < path.lastWaypointOf.size(); ++k) {
    if (k + 1 == path.lastWaypointOf.size()) {
      ends.push_back(offset + part.duration());
      break;
    }
    from = nearestPoint(part, space.trajectoryPositions(path.waypoints[path.lastWaypointOf[k]]), from);
    ends.push_back(offset + part.points[from].time);
  }
}

bool hasJerkLimits(const PlanningSpace& space) { return space.jointJerkLimits().maxCoeff() > 0.0; }

/// The time-optimal trajectory along `blended`, jerk-limited when the space has jerk limits and
/// the settings ask for it: the acceleration is halved until the filter stays within
/// kJerkFilterDeviation of the path.
JointTrajectory timeAlong(const ArmContext& arm, const BlendedPath& blended, TrajectoryQuality& quality) {
  const ExecutionSettings& settings = arm.settings();
  const PlanningSpace& space = arm.robotSpace();
  TimeOptimalOptions options;
  options.velocityScaling = settings.velocityScaling;
  options.accelerationScaling = settings.accelerationScaling;
  if (!settings.limitJerk || !hasJerkLimits(space)) return timeOptimalParameterize(space, blended, options);
  const double outputInterval = options.sampleInterval;
  options.sampleInterval = kJerkInputInterval;
  for (int attempt = 0;; ++attempt) {
    const JointTrajectory fine = timeOptimalParameterize(space, blended, options);
    if (fine.points.size() < 2) return fine;
    JerkLimitedTrajectory limited = limitJerk(fine, space.jointAccelerationLimits() * options.accelerationScaling,
                                              space.jointJerkLimits(), outputInterval);
    if (limited.deviation <= kJerkFilterDeviation || attempt + 1 == kJerkAttempts) {
      ++quality.jerkLimitedRuns;
      quality.jerkReducedRuns += attempt > 0 ? 1 : 0;
      return std::move(limited.trajectory);
    }
    options.accelerationScaling *= 0.5;
  }
}

/// The time-optimal trajectory of one run, or its rest-to-rest one when the first breaks a limit.
JointTrajectory timeRun(const ArmContext& arm, const RunPath& path, TimedRun& run, TrajectoryQuality& quality) {
  const ExecutionSettings& settings = arm.settings();
  const PlanningSpace& space = arm.robotSpace();
  const BlendedPath blended(path.waypoints, run.cornerDeviations);
  JointTrajectory part = timeAlong(arm, blended, quality);
  if (checkTrajectoryLimits(space, part, kLimitSlack, settings.velocityScaling, settings.accelerationScaling).empty() &&
      (!settings.limitJerk || checkJerkLimits(part, space.jointJerkLimits(), kLimitSlack).empty())) {
    quality.stopsInsideRuns += static_cast<int>(blended.stopPoints().size());
    quality.pathLength += blended.length();
    for (const PathSegment& piece : blended.segments()) quality.blendedCorners += piece.kind == PathSegment::Kind::kArc ? 1 : 0;
    return part;
  }
  ++quality.restToRestFallbacks;
  run.cornerDeviations.assign(path.waypoints.size(), 0.0);
  quality.stopsInsideRuns += static_cast<int>(path.waypoints.size()) - 2;
  quality.pathLength += polylineLength(path.waypoints);
  TimeParameterizationOptions rest;
  rest.velocityScaling = settings.velocityScaling;
  rest.accelerationScaling = settings.accelerationScaling;
  return timeParameterize(space, path.waypoints, rest);
}

/// The older timing: rest to rest at every waypoint of the whole action.
ActionTiming timeRestToRest(const ArmContext& arm, const std::vector<MotionSegment>& segments) {
  ActionTiming timing;
  TimeParameterizationOptions options;
  options.velocityScaling = arm.settings().velocityScaling;
  options.accelerationScaling = arm.settings().accelerationScaling;
  const RunPath path = runPath(segments, {0, segments.size(), {}});
  timing.trajectory = timeParameterize(arm.robotSpace(), path.waypoints, options);
  std::size_t point = 0;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const VectorX end = arm.robotSpace().trajectoryPositions(path.waypoints[path.lastWaypointOf[k]]);
    while (point + 1 < timing.trajectory.points.size() &&
           (timing.trajectory.points[point].positions - end).norm() > RunPath::kRepeatedWaypoint) {
      ++point;
    }
    timing.segmentEndTimes.push_back(timing.trajectory.points[point].time);
  }
  timing.quality.stopsInsideRuns = std::max(0, static_cast<int>(path.waypoints.size()) - 2);
  timing.quality.pathLength = polylineLength(path.waypoints);
  return timing;
}

}  // namespace

RunPath runPath(const std::vector<MotionSegment>& segments, const TimedRun& run) {
  RunPath path;
  for (std::size_t k = run.firstSegment; k < run.endSegment; ++k) {
    for (const VectorX& q : segments[k].waypoints) {
      if (path.waypoints.empty() || (q - path.waypoints.back()).norm() > RunPath::kRepeatedWaypoint) {
        path.waypoints.push_back(q);
        path.segmentOf.push_back(k);
      }
    }
    path.lastWaypointOf.push_back(path.waypoints.empty() ? 0 : path.waypoints.size() - 1);
  }
  return path;
}

ActionTiming timeActionMotions(const ArmContext& arm, const std::vector<MotionSegment>& segments) {
  const auto began = std::chrono::steady_clock::now();
  ActionTiming timing;
  if (segments.empty()) return timing;
  if (arm.settings().timing == TrajectoryTiming::kRestToRest) {
    timing = timeRestToRest(arm, segments);
  } else {
    timing.trajectory.jointNames = arm.robotSpace().trajectoryJointNames();
    RunPointChecker checker(arm, segments);
    double offset = 0.0;
    for (TimedRun& run : splitIntoRuns(arm, segments)) {
      const RunPath path = runPath(segments, run);
      if (path.waypoints.empty()) {  // segments without waypoints end where the previous one did
        timing.segmentEndTimes.insert(timing.segmentEndTimes.end(), run.endSegment - run.firstSegment, offset);
        timing.runs.push_back(std::move(run));
        continue;
      }
      run.cornerDeviations = chooseBlends(arm, path, checker, timing.quality);
      const JointTrajectory part = timeRun(arm, path, run, timing.quality);
      addSegmentEnds(arm.robotSpace(), path, part, offset, timing.segmentEndTimes);
      append(timing.trajectory, part, offset);
      offset += part.duration();
      timing.runs.push_back(std::move(run));
    }
    timing.collisionChecks = checker.checks();
  }
  timing.quality.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  return timing;
}

SegmentCheck checkTimedAction(const ArmContext& arm, const ActionExecution& action, double resolution) {
  SegmentCheck result;
  if (action.runs.empty()) {
    for (const MotionSegment& segment : action.segments) {
      const SegmentCheck check = checkSegment(arm, segment, resolution);
      result.checks += check.checks;
      if (!check.collision.empty()) return {check.collision, result.checks};
    }
    return result;
  }
  RunPointChecker checker(arm, action.segments);
  for (const TimedRun& run : action.runs) {
    for (std::size_t k = run.firstSegment; k < run.endSegment; ++k) {
      if (std::string carried = carriedSweepCollision(action.segments[k]); !carried.empty()) return {carried, checker.checks()};
    }
    const RunPath path = runPath(action.segments, run);
    if (path.waypoints.empty()) continue;
    if (run.cornerDeviations.size() != path.waypoints.size() || run.endSegment > action.segments.size()) {
      result.collision = "the timing of segments " + std::to_string(run.firstSegment) + " to " + std::to_string(run.endSegment) +
                         " does not match their waypoints (" + std::to_string(run.cornerDeviations.size()) + " blends for " +
                         std::to_string(path.waypoints.size()) + " waypoints): the motion was changed after it was timed";
      result.checks = checker.checks();
      return result;
    }
    const BlendedPath blended(path.waypoints, run.cornerDeviations);
    for (const PathSegment& piece : blended.segments()) {
      const std::vector<std::size_t> owners = ownersOf(piece, path);
      const std::vector<double> samples =
          piece.kind == PathSegment::Kind::kLine ? lineSamples(piece, path, resolution) : samplesAlong(piece, resolution);
      for (const double u : samples) {
        std::string contacts = checker.contacts(piece.position(u), owners);
        if (contacts.empty()) continue;
        result.collision = contacts + (piece.kind == PathSegment::Kind::kArc ? " (on the blend at waypoint " : " (after waypoint ") +
                           std::to_string(piece.waypoint) + " of the run)";
        result.checks = checker.checks();
        return result;
      }
    }
  }
  result.checks = checker.checks();
  return result;
}

}  // namespace lang2manip
