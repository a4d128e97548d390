#include "lang2manip/grounding/grasp_candidates.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/grounding/object_geometry.hpp"

namespace lang2manip {
namespace {

const Vector3 kUp = Vector3::UnitZ();

/// A unit horizontal vector from `v`, or zero when `v` is (nearly) vertical.
Vector3 horizontal(const Vector3& v) {
  const Vector3 h(v.x(), v.y(), 0.0);
  return h.norm() < 0.3 ? Vector3::Zero() : h.normalized();
}


/// The rotation R_WG putting the gripper's approach axis along `a` and closing axis along `c`.
Matrix3 gripperRotation(const GripperGeometry& gripper, const Vector3& a, const Vector3& c) {
  const Vector3 aG = gripper.approachAxis.normalized();
  const Vector3 cG = (gripper.closingAxis - gripper.closingAxis.dot(aG) * aG).normalized();
  Matrix3 world;
  world << a, c, a.cross(c);
  Matrix3 tool;
  tool << aG, cG, aG.cross(cG);
  return world * tool.transpose();
}

/// Largest |corner . axis| over finger bounds `fingers` (in G).
double fingerHalfExtent(const AlignedBox3& fingers, const Vector3& axisG) {
  double half = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    half = std::max(half, std::abs(fingers.corner(static_cast<AlignedBox3::CornerType>(corner)).dot(axisG)));
  }
  return half;
}

/// Lowest world z of the finger slabs `slabs` relative to the TCP for rotation R_WG.
double fingerLowest(const std::vector<AlignedBox3>& slabs, const Matrix3& R) {
  double lowest = 0.0;
  for (const AlignedBox3& slab : slabs) {
    for (int corner = 0; corner < 8; ++corner) {
      lowest = std::min(lowest, (R * slab.corner(static_cast<AlignedBox3::CornerType>(corner))).z());
    }
  }
  return lowest;
}

struct Approach {
  GraspDirection direction;
  Vector3 approach;
  std::vector<Vector3> closings;
};

std::vector<Approach> topApproaches(const GraspGeometryInput& in, const GraspSettings& settings) {
  const Matrix3 R = in.objectPose.linear();
  Vector3 reference = horizontal(R.col(0));
  if (reference.isZero()) reference = horizontal(R.col(1));
  Approach top{GraspDirection::kTop, -kUp, {}};
  for (int k = 0; k < settings.topYawSteps; ++k) {
    top.closings.push_back(Eigen::AngleAxisd(2.0 * M_PI * k / settings.topYawSteps, kUp) * reference);
  }
  return {top};
}

std::vector<Approach> horizontalApproaches(const GraspGeometryInput& in, GraspDirection direction,
                                           const std::vector<Vector3>& centres, const GraspSettings& settings) {
  const Matrix3 R = in.objectPose.linear();
  std::vector<Vector3> options;
  for (const Vector3& centre : centres) {
    options.push_back(centre);
    for (int axis = 0; axis < 2; ++axis) {
      for (double sign : {1.0, -1.0}) {
        const Vector3 normal = horizontal(sign * R.col(axis));
        if (!normal.isZero() && normal.dot(centre) >= std::cos(settings.sectorHalfAngle) - 1e-9) options.push_back(normal);
      }
    }
  }
  std::vector<Approach> approaches;
  for (const Vector3& a : options) {
    const bool seen = std::any_of(approaches.begin(), approaches.end(), [&](const Approach& x) { return x.approach.dot(a) > 1.0 - 1e-6; });
    if (seen) continue;
    const Vector3 across = kUp.cross(a).normalized();
    for (double pitch : settings.approachPitches) {
      const Vector3 tilted = std::cos(pitch) * a - std::sin(pitch) * kUp;
      const Vector3 upward = across.cross(tilted).normalized();
      approaches.push_back({direction, tilted, {across, -across, upward, -upward}});
    }
  }
  return approaches;
}

std::vector<Approach> approachesFor(const GraspGeometryInput& in, GraspDirection direction, const GraspSettings& settings) {
  const Vector3 front = horizontal(in.robotBase.linear().col(0));
  const Vector3 left = horizontal(in.robotBase.linear().col(1));
  std::vector<Approach> all;
  auto append = [&](std::vector<Approach> more) { all.insert(all.end(), more.begin(), more.end()); };
  if (direction == GraspDirection::kAuto || direction == GraspDirection::kTop) append(topApproaches(in, settings));
  if (direction == GraspDirection::kAuto || direction == GraspDirection::kFront) {
    append(horizontalApproaches(in, GraspDirection::kFront, {front}, settings));
  }
  if (direction == GraspDirection::kAuto || direction == GraspDirection::kSide) {
    append(horizontalApproaches(in, GraspDirection::kSide, {left, -left}, settings));
  }
  return all;
}

/// How far (m) lifting a grasp off the support may move it along the closing axis beyond the
/// opening's free play and still count as holding the object between the pads.
constexpr double kCentringTolerance = 0.003;

std::string describe(GraspDirection direction, const Vector3& a, const Vector3& c, double offset) {
  // Values that print as zero print without a sign ("-0.00" reads like a direction).
  const auto shown = [](double value, double resolution) { return std::abs(value) < resolution / 2.0 ? 0.0 : value; };
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "%s, approach (%.2f, %.2f, %.2f), closing (%.2f, %.2f, %.2f), offset %+.3f m",
                graspDirectionName(direction).c_str(), shown(a.x(), 0.01), shown(a.y(), 0.01), shown(a.z(), 0.01),
                shown(c.x(), 0.01), shown(c.y(), 0.01), shown(c.z(), 0.01), shown(offset, 0.001));
  return buffer;
}

/// Grasp points along the fingers' width axis: the centre, and both ends for long objects.
std::vector<double> graspOffsets(double halfLength, double padHalfWidth) {
  const double end = halfLength - padHalfWidth - 0.005;
  if (end < 0.01) return {0.0};
  return {0.0, end, -end};
}

void addGrasps(const GraspGeometryInput& in, const GripperGeometry& gripper, const GraspSettings& settings,
               const Approach& approach, const Vector3& c, GraspGeneration& out) {
  const SceneObject& object = *in.object;
  const Vector3& a = approach.approach;
  const double width = 2.0 * halfExtentAlong(object, in.objectPose, c);
  if (width > gripper.maxOpening) {
    out.rejections.push_back({describe(approach.direction, a, c, 0.0), GraspFailure::kTooWide,
                              object.name + " is " + metresText(width) + " wide across the fingers, the gripper opens " + metresText(gripper.maxOpening)});
    return;
  }
  if (width < gripper.minOpening) {
    out.rejections.push_back({describe(approach.direction, a, c, 0.0), GraspFailure::kNotGraspable,
                              object.name + " is " + metresText(width) + " wide across the fingers, the gripper closes only to " +
                                  metresText(gripper.minOpening)});
    return;
  }
  const Matrix3 R = gripperRotation(gripper, a, c);
  const Vector3 t = a.cross(c);
  const Vector3 centre = objectCentre(object, in.objectPose);
  // The fingers as they are from the opening the grasp approaches with down to the object's
  // width, and where the pads are then: linkage fingers move along the approach axis.
  const double approachOpening = std::min(gripper.maxOpening, width + 2.0 * settings.openingMargin);
  const AlignedBox3 fingers = gripper.fingerBoundsBetween(width, approachOpening);
  const std::vector<AlignedBox3> slabs = gripper.fingerSlabsBetween(width, approachOpening);
  const double pads = gripper.padCentreAt(width);
  const double padHalfWidth = fingerHalfExtent(fingers, R.transpose() * t);
  const double depthHalf = halfExtentAlong(object, in.objectPose, a);
  const double depth = std::min(depthHalf, pads - fingers.min().z() - settings.supportClearance);
  const double top = centre.z() + halfExtentAlong(object, in.objectPose, kUp);
  for (double offset : graspOffsets(halfExtentAlong(object, in.objectPose, t), padHalfWidth)) {
    Vector3 p = centre + t * offset + a * (depth - depthHalf - pads);
    const double lift = std::max(0.0, in.supportTop + settings.supportClearance - (p.z() + fingerLowest(slabs, R)));
    p.z() += lift;
    const std::string label = describe(approach.direction, a, c, offset);
    // Lifted along the closing axis by more than the approach opening leaves free, a pad would
    // come down into the object instead of beside it: the object is not between the pads.
    if (std::abs(lift * c.z()) > (approachOpening - width) / 2.0 + kCentringTolerance) {
      out.rejections.push_back({label, GraspFailure::kNotGraspable,
                                object.name + ": a finger would have to pass under it, through its support"});
      continue;
    }
    // Lifted across the closing axis within that play, the object is off the pads' middle: then
    // the TCP itself must be below the top; otherwise the fingertips must be.
    const bool centred = std::abs(lift * c.z()) <= kCentringTolerance;
    const double lowestHold = centred ? p.z() + fingerLowest(slabs, R) : p.z() + (R * Vector3(0.0, 0.0, pads)).z();
    if (lowestHold > top - settings.minimumEngagement) {
      out.rejections.push_back({label, GraspFailure::kNotGraspable,
                                object.name + ": the fingers cannot close below its top without touching its support"});
      continue;
    }
    GeometricGrasp grasp{approach.direction, label, Pose::Identity(), a, width, offset};
    grasp.pose.linear() = R;
    grasp.pose.translation() = p;
    out.grasps.push_back(grasp);
  }
}

}  // namespace

GraspGeneration generateGrasps(const GraspGeometryInput& input, const GripperGeometry& gripper,
                               GraspDirection direction, const GraspSettings& settings) {
  GraspGeneration out;
  for (const Approach& approach : approachesFor(input, direction, settings)) {
    for (const Vector3& c : approach.closings) addGrasps(input, gripper, settings, approach, c, out);
  }
  return out;
}

GraspGeneration generateWidenedGrasps(const GraspGeometryInput& input, const GripperGeometry& gripper,
                                      GraspDirection direction, const GraspSettings& settings) {
  GraspGeneration out;
  if (direction != GraspDirection::kAuto && direction != GraspDirection::kTop) return out;
  const Vector3 reference = topApproaches(input, settings).front().closings.front();
  // Leaning towards or away from the robot first: the only leans an arm whose joints turn in
  // one vertical plane (fewer than six) can take, and natural for any arm.
  Vector3 radial = input.objectPose.translation() - input.robotBase.translation();
  radial.z() = 0.0;
  if (radial.norm() > 1e-6) {
    const Vector3 across = kUp.cross(radial.normalized());
    for (const double tilt : settings.widenedTopTilts) {
      for (const double sign : {1.0, -1.0}) {
        const Eigen::AngleAxisd lean(sign * tilt, across);
        for (const Vector3& c : {across, Vector3(radial.normalized())}) addGrasps(input, gripper, settings, {GraspDirection::kTop, lean * -kUp, {}}, lean * c, out);
      }
    }
  }
  const int steps = 2 * settings.topYawSteps;
  for (int k = 0; k < steps; ++k) {
    const Vector3 c = Eigen::AngleAxisd(2.0 * M_PI * k / steps, kUp) * reference;
    if (k % 2 == 1) addGrasps(input, gripper, settings, {GraspDirection::kTop, -kUp, {}}, c, out);
    const Vector3 between = -kUp.cross(c);  // the axis from one finger's width to the other's
    for (const Vector3& axis : {c, between}) {
      for (const double tilt : settings.widenedTopTilts) {
        for (const double sign : {1.0, -1.0}) {
          const Eigen::AngleAxisd lean(sign * tilt, axis);
          addGrasps(input, gripper, settings, {GraspDirection::kTop, lean * -kUp, {}}, lean * c, out);
        }
      }
    }
  }
  return out;
}

}  // namespace lang2manip
