#include "lang2manip/grounding/gripper_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "lang2manip/core/error.hpp"
#include "lang2manip/grounding/gripper_fingers.hpp"
#include "lang2manip/grounding/object_geometry.hpp"

namespace lang2manip {
namespace {

using gripper_detail::FingerSet;
using gripper_detail::PadLayout;

/// Samples of the pad gap over the travel.
constexpr int kCurveSamples = 33;
/// A gripper whose pad gap changes less than this over its travel does not open (m).
constexpr double kMinimumTravel = 1e-3;
/// The tool frame is between the pads when within this of them along the approach axis (m).
constexpr double kTcpTolerance = 0.01;
/// Each finger link is described by this many boxes, one per slab across the approach axis.
constexpr int kFingerSlabs = 6;

std::string millimetres(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f mm", value * 1000.0);
  return buffer;
}

std::string where(const RobotModel& model, const Manipulator& manipulator) {
  return "gripper of " + model.name() + "/" + manipulator.name;
}

std::vector<double> openingCurve(const FingerSet& fingers, const PadLayout& layout) {
  std::vector<double> curve;
  for (int i = 0; i < kCurveSamples; ++i) {
    curve.push_back(gripper_detail::padGap(fingers, layout, fingers.linkPoses(i / (kCurveSamples - 1.0))));
  }
  return curve;
}

/// Bounds along `axis` of the pads' points in the contact band, when open.
std::pair<double, double> padRange(const FingerSet& fingers, const PadLayout& layout, const Vector3& axis) {
  const std::vector<Pose>& open = fingers.openPoses();
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (std::size_t f = 0; f < layout.pads.size(); ++f) {
    for (const Vector3& p : gripper_detail::padContactPoints(fingers, layout, f, open)) {
      low = std::min(low, p.dot(axis));
      high = std::max(high, p.dot(axis));
    }
  }
  return {low, high};
}

/// X_TH: the tool frame when its origin lies between the open pads, else the pads' centre; the
/// rotation keeps T's when T's +z is the approach axis, else turns +z onto it and +y onto closing.
Pose graspFrameOf(const FingerSet& fingers, const PadLayout& layout) {
  const Vector3 a = layout.approach;
  const Vector3 c = layout.closing;
  const Vector3 t = a.cross(c);
  const std::vector<Pose>& open = fingers.openPoses();
  const auto [aLow, aHigh] = gripper_detail::contactBand(fingers, layout, open);
  const auto [tLow, tHigh] = padRange(fingers, layout, t);
  const double gap = gripper_detail::padGap(fingers, layout, open);
  const double middle = gripper_detail::gapMiddle(fingers, layout, open);
  const bool between = aLow - kTcpTolerance <= 0.0 && 0.0 <= aHigh + kTcpTolerance && tLow - kTcpTolerance <= 0.0 &&
                       0.0 <= tHigh + kTcpTolerance && std::abs(middle) <= 0.5 * std::max(gap, 0.0) + kTcpTolerance;
  Pose X_TH = Pose::Identity();
  if (!a.isApprox(Vector3::UnitZ(), 1e-9)) X_TH.linear() << c.cross(a), c, a;
  if (!between) X_TH.translation() = a * 0.5 * (aLow + aHigh) + c * middle + t * 0.5 * (tLow + tHigh);
  return X_TH;
}

/// The finger links' points in H cut into kFingerSlabs slabs along H's z, a box for each.
std::vector<AlignedBox3> fingerSlabs(const FingerSet& fingers, const std::vector<Pose>& poses, const Pose& X_HT) {
  std::vector<AlignedBox3> slabs;
  for (std::size_t i = 0; i < fingers.links().size(); ++i) {
    std::vector<Vector3> points = fingers.pointsInTool(i, poses);
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (Vector3& p : points) {
      p = X_HT * p;
      low = std::min(low, p.z());
      high = std::max(high, p.z());
    }
    const std::size_t first = slabs.size();
    slabs.resize(first + kFingerSlabs);
    const double thickness = std::max(high - low, 1e-9) / kFingerSlabs;
    for (const Vector3& p : points) {
      const int slab = std::clamp(static_cast<int>((p.z() - low) / thickness), 0, kFingerSlabs - 1);
      slabs[first + static_cast<std::size_t>(slab)].extend(p);
    }
  }
  return slabs;
}

void describeFingers(const RobotModel& model, const FingerSet& fingers, const PadLayout& layout, GripperGeometry& g) {
  g.graspFrame = graspFrameOf(fingers, layout);
  const Pose X_HT = g.graspFrame.inverse();
  g.approachAxis = Vector3::UnitZ();
  g.closingAxis = (X_HT.linear() * layout.closing).normalized();
  g.fingerCount = layout.radial ? static_cast<int>(layout.pads.size()) : 2;
  const std::vector<Pose>& open = fingers.openPoses();
  const auto [aLow, aHigh] = gripper_detail::contactBand(fingers, layout, open);
  g.padDepth = aHigh - aLow;
  double rootLow = aLow;
  double tip = aHigh;
  for (std::size_t i = 0; i < fingers.links().size(); ++i) {
    for (const Vector3& p : fingers.pointsInTool(i, open)) rootLow = std::min(rootLow, p.dot(layout.approach));
  }
  for (std::size_t pad : layout.pads) {
    for (const Vector3& p : fingers.pointsInTool(pad, open)) tip = std::max(tip, p.dot(layout.approach));
  }
  g.fingerLength = tip - rootLow;
  for (std::size_t pad : layout.pads) g.padLinks.push_back(model.links()[static_cast<std::size_t>(fingers.links()[pad].link)].name);
  g.fixedJaw = layout.pads.size() == 1 && !layout.jawFace.empty() && fingers.fixedJaw();
  for (const gripper_detail::ContactFace& face : layout.contactFaces) g.padsWithContactFace += face.empty() ? 0 : 1;
  g.padsWithContactFace += g.fixedJaw ? 1 : 0;
  if (g.fixedJaw) g.padLinks.push_back(model.links()[static_cast<std::size_t>(fingers.fixedJaw()->link)].name);
  for (int link : fingers.movedLinks()) g.fingerLinks.push_back(model.links()[static_cast<std::size_t>(link)].name);
  // At every sample of the travel: linkage fingers reach farther along the approach axis as
  // they close, so what a grasp needs depends on its width.
  for (int i = 0; i < kCurveSamples; ++i) {
    const std::vector<Pose> poses = fingers.linkPoses(i / (kCurveSamples - 1.0));
    AlignedBox3 bounds;
    for (int link : fingers.movedLinks()) {
      const Pose X_HL = X_HT * poses[static_cast<std::size_t>(link)];
      for (const Shape& shape : model.links()[static_cast<std::size_t>(link)].collisions) {
        bounds.extend(transformedBox(shapeBounds(shape), X_HL));
      }
    }
    g.fingerBoundsCurve.push_back(bounds);
    g.fingerBounds.extend(bounds);
    g.fingerSlabsCurve.push_back(fingerSlabs(fingers, poses, X_HT));
    const auto [low, high] = gripper_detail::contactBand(fingers, layout, poses);
    g.padCentreCurve.push_back(0.5 * (low + high));  // along the approach axis, relative to when open below
  }
  const double whenOpen = g.padCentreCurve.back();
  for (double& centre : g.padCentreCurve) centre -= whenOpen;
}

/// The bounds of each collision shape below the last arm joint (hand, fingers, tool) in the tool
/// frame, at configuration `q`.
std::vector<AlignedBox3> toolShapeBoxes(const RobotModel& model, const Manipulator& manipulator, const VectorX& q) {
  std::vector<AlignedBox3> boxes;
  if (manipulator.armJoints.empty()) return boxes;
  const std::vector<Pose> poses = model.linkPoses(q);
  const Pose X_TR = poses[static_cast<std::size_t>(model.linkIndex(manipulator.toolFrame))].inverse();
  std::vector<int> stack{model.childLinkOf(model.jointIndex(manipulator.armJoints.back()))};
  while (!stack.empty()) {
    const int link = stack.back();
    stack.pop_back();
    for (const Shape& shape : model.links()[static_cast<std::size_t>(link)].collisions) {
      boxes.push_back(transformedBox(shapeBounds(shape), X_TR * poses[static_cast<std::size_t>(link)]));
    }
    for (int j = 0; j < static_cast<int>(model.joints().size()); ++j) {
      if (model.parentLinkOf(j) == link) stack.push_back(model.childLinkOf(j));
    }
  }
  return boxes;
}

/// The shapes of the link that carries the last arm joint, in H, each swept about that joint's
/// axis when it is H's approach axis (+z): a box about the axis as wide as the farthest corner of
/// the shape's bounds from it. None after a last joint of another axis.
constexpr double kRollAlignment = 0.99;

std::vector<AlignedBox3> sweptWristBoxes(const RobotModel& model, const Manipulator& manipulator, const GripperGeometry& g) {
  std::vector<AlignedBox3> boxes;
  if (manipulator.armJoints.empty()) return boxes;
  const VectorX q = model.middleConfiguration();
  const std::vector<Pose> poses = model.linkPoses(q);
  const int last = model.jointIndex(manipulator.armJoints.back());
  const int wrist = model.parentLinkOf(last);
  const Pose X_HR = g.graspFrame.inverse() * poses[static_cast<std::size_t>(model.linkIndex(manipulator.toolFrame))].inverse();
  const Pose X_RJ = poses[static_cast<std::size_t>(model.childLinkOf(last))];
  const Vector3 axisPoint = X_HR * X_RJ.translation();
  const Vector3 axis = (X_HR.linear() * X_RJ.linear() * model.joints()[static_cast<std::size_t>(last)].axis).normalized();
  // Only a last joint that turns the tool about its approach axis (a flange's roll) keeps the
  // wrist where the sweep says; after a pitch, the wrist's place depends on the joint.
  if (std::abs(axis.z()) < kRollAlignment) return boxes;
  for (const Shape& shape : model.links()[static_cast<std::size_t>(wrist)].collisions) {
    const AlignedBox3 box = transformedBox(shapeBounds(shape), X_HR * poses[static_cast<std::size_t>(wrist)]);
    if (box.isEmpty()) continue;
    double radius = 0.0, low = std::numeric_limits<double>::infinity(), high = -low;
    for (int corner = 0; corner < 8; ++corner) {
      const Vector3 offset = box.corner(static_cast<AlignedBox3::CornerType>(corner)) - axisPoint;
      const double along = offset.dot(axis);
      radius = std::max(radius, (offset - along * axis).norm());
      low = std::min(low, along);
      high = std::max(high, along);
    }
    AlignedBox3 swept;
    for (const double t : {low, high}) {
      for (int i = 0; i < 3; ++i) {
        const Vector3 side = Vector3::Unit(i) - Vector3::Unit(i).dot(axis) * axis;
        const Vector3 across = side.norm() > 1e-9 ? Vector3(radius * side.normalized()) : Vector3(Vector3::Zero());
        swept.extend(axisPoint + t * axis + across);
        swept.extend(axisPoint + t * axis - across);
      }
    }
    boxes.push_back(swept);
  }
  return boxes;
}

/// The shape boxes of the hand in H with the gripper closed (a tool without gripper as it is).
std::vector<AlignedBox3> closedHandBoxes(const RobotModel& model, const Manipulator& manipulator, const GripperGeometry& g) {
  VectorX q = model.middleConfiguration();
  if (g.hasGripper()) q = withGripperFraction(model, g, q, 0.0);
  std::vector<AlignedBox3> boxes = toolShapeBoxes(model, manipulator, q);
  const Pose X_HT = g.graspFrame.inverse();
  for (AlignedBox3& box : boxes) box = transformedBox(box, X_HT);
  return boxes;
}

/// R_TH for a tool without gripper: T itself when `approach` is T's +z, else H's +z along
/// `approach` and H's +y along the tool axis most across it.
Matrix3 toolRotation(const Vector3& approach) {
  if (approach.isApprox(Vector3::UnitZ(), 1e-9)) return Matrix3::Identity();
  int across = 0;
  for (int axis = 1; axis < 3; ++axis) {
    if (std::abs(approach[axis]) < std::abs(approach[across])) across = axis;
  }
  const Vector3 y = (Vector3::Unit(across) - approach.dot(Vector3::Unit(across)) * approach).normalized();
  Matrix3 R;
  R << y.cross(approach), y, approach;
  return R;
}

void describeGripperJoints(const RobotModel& model, const Manipulator& manipulator, GripperGeometry& g, bool mayReverse = true) {
  const std::string context = where(model, manipulator);
  const FingerSet fingers(model, g.toolFrame, g.gripperJoints, g.closedValues, g.openValues);
  const bool statesGiven = !manipulator.gripperOpenState.empty() && !manipulator.gripperClosedState.empty();
  if (mayReverse && !statesGiven && fingers.spread(0.0) > fingers.spread(1.0)) {
    // The fingers spread wider at the "closed" end: the travel runs the other way.
    std::swap(g.openValues, g.closedValues);
    describeGripperJoints(model, manipulator, g, false);
    return;
  }
  const PadLayout layout = gripper_detail::layoutPads(fingers, context, manipulator.approachAxis);
  g.openingCurve = openingCurve(fingers, layout);
  if (statesGiven && g.openingCurve.front() > g.openingCurve.back() + kMinimumTravel) {
    // The SRDF says which end is open, and the fingers say the other.
    throw InputError(context + ": the SRDF's state \"" + manipulator.gripperOpenState + "\" puts the pads " +
                     millimetres(g.openingCurve.back()) + " apart and its state \"" + manipulator.gripperClosedState + "\" " +
                     millimetres(g.openingCurve.front()) + ": the two are swapped (joint " + g.gripperJoints.front() + ": \"" +
                     manipulator.gripperOpenState + "\" " + std::to_string(g.openValues.front()) + ", \"" +
                     manipulator.gripperClosedState + "\" " + std::to_string(g.closedValues.front()) +
                     "); swap their values in the SRDF");
  }
  if (mayReverse && g.openingCurve.front() > g.openingCurve.back()) {
    // The limits' "open" end is where the pads meet: the travel runs the other way.
    std::swap(g.openValues, g.closedValues);
    describeGripperJoints(model, manipulator, g, false);
    return;
  }
  for (std::size_t i = 1; i < g.openingCurve.size(); ++i) g.openingCurve[i] = std::max(g.openingCurve[i], g.openingCurve[i - 1]);
  for (double& width : g.openingCurve) width = std::max(width, 0.0);
  g.minOpening = g.openingCurve.front();
  g.maxOpening = g.openingCurve.back();
  describeFingers(model, fingers, layout, g);
  if (g.maxOpening - g.minOpening < kMinimumTravel) {
    throw InputError(context + ": it does not open: the gap between its pads (" + g.padLinks.front() + " and " + g.padLinks.back() +
                     ") stays between " + millimetres(g.minOpening) + " and " + millimetres(g.maxOpening) +
                     " over the travel of its joints (check their limits, or the SRDF's open and closed states" +
                     (manipulator.approachAxis ? std::string(", or the approach axis given") : std::string()) + ")");
  }
}

}  // namespace

const Manipulator& findManipulator(const RobotModel& model, const std::string& name) {
  const auto& manipulators = model.semantics().manipulators;
  if (manipulators.empty()) throw InputError("robot " + model.name() + ": no manipulator (arm with a tool frame)");
  if (name.empty()) return manipulators.front();
  std::string names;
  for (const Manipulator& m : manipulators) {
    if (m.name == name) return m;
    names += (names.empty() ? "" : ", ") + m.name;
  }
  throw InputError("robot " + model.name() + ": unknown manipulator \"" + name + "\" (manipulators: " + names + ")");
}

GripperGeometry describeGripper(const RobotModel& model, const std::string& manipulatorName) {
  const Manipulator& manipulator = findManipulator(model, manipulatorName);
  GripperGeometry gripper;
  gripper.manipulator = manipulator.name;
  gripper.toolFrame = manipulator.toolFrame;
  gripper.gripperJoints = manipulator.gripperJoints;
  gripper.openValues = manipulator.gripperOpen;
  gripper.closedValues = manipulator.gripperClosed;
  if (gripper.hasGripper()) {
    describeGripperJoints(model, manipulator, gripper);
  } else {
    gripper.graspFrame.linear() = toolRotation(manipulator.approachAxis.value_or(Vector3::UnitZ()));
  }
  gripper.closedHandBounds = closedHandBoxes(model, manipulator, gripper);
  gripper.wristBounds = sweptWristBoxes(model, manipulator, gripper);
  if (!gripper.hasGripper()) {
    for (const AlignedBox3& box : gripper.closedHandBounds) gripper.fingerBounds.extend(box);
  }
  if (gripper.fingerBounds.isEmpty()) gripper.fingerBounds = AlignedBox3(Vector3::Zero(), Vector3::Zero());
  return gripper;
}

std::string noGripperReason(const RobotModel& model, const GripperGeometry& gripper, const std::string& action) {
  if (gripper.hasGripper()) return {};
  return action + ": robot " + model.name() + " has no gripper (manipulator " + gripper.manipulator +
                   " ends at " + gripper.toolFrame +
                   " with no gripper joint after it); it can move and push. To pick, give the robot a gripper, or name its "
                   "gripper joints in an SRDF end effector group";
}

AlignedBox3 GripperGeometry::fingerBoundsBetween(double narrow, double wide) const {
  if (fingerBoundsCurve.empty()) return fingerBounds;
  const double last = static_cast<double>(fingerBoundsCurve.size() - 1);
  const auto first = static_cast<std::size_t>(std::floor(fractionForOpening(*this, std::min(narrow, wide)) * last));
  const auto end = static_cast<std::size_t>(std::ceil(fractionForOpening(*this, std::max(narrow, wide)) * last));
  AlignedBox3 bounds;
  for (std::size_t i = first; i <= end && i < fingerBoundsCurve.size(); ++i) bounds.extend(fingerBoundsCurve[i]);
  return bounds.isEmpty() ? fingerBounds : bounds;
}

std::vector<AlignedBox3> GripperGeometry::fingerSlabsBetween(double narrow, double wide) const {
  if (fingerSlabsCurve.empty()) return {fingerBoundsBetween(narrow, wide)};
  const double last = static_cast<double>(fingerSlabsCurve.size() - 1);
  const auto first = static_cast<std::size_t>(std::floor(fractionForOpening(*this, std::min(narrow, wide)) * last));
  const auto end = static_cast<std::size_t>(std::ceil(fractionForOpening(*this, std::max(narrow, wide)) * last));
  std::vector<AlignedBox3> slabs(fingerSlabsCurve.front().size());
  for (std::size_t i = first; i <= end && i < fingerSlabsCurve.size(); ++i) {
    for (std::size_t k = 0; k < slabs.size(); ++k) slabs[k].extend(fingerSlabsCurve[i][k]);
  }
  std::erase_if(slabs, [](const AlignedBox3& slab) { return slab.isEmpty(); });
  return slabs;
}

double GripperGeometry::padCentreAt(double width) const {
  if (padCentreCurve.empty()) return 0.0;
  const double x = fractionForOpening(*this, width) * static_cast<double>(padCentreCurve.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(x), padCentreCurve.size() - 1);
  const std::size_t next = std::min(i + 1, padCentreCurve.size() - 1);
  return padCentreCurve[i] + (x - static_cast<double>(i)) * (padCentreCurve[next] - padCentreCurve[i]);
}

VectorX withGripperFraction(const RobotModel& model, const GripperGeometry& gripper, VectorX q, double fraction) {
  const double s = std::clamp(fraction, 0.0, 1.0);
  for (std::size_t i = 0; i < gripper.gripperJoints.size(); ++i) {
    const int variable = model.variableIndex(gripper.gripperJoints[i]);
    q[variable] = gripper.closedValues[i] + s * (gripper.openValues[i] - gripper.closedValues[i]);
  }
  return q;
}

double gripperFraction(const RobotModel& model, const GripperGeometry& gripper, const VectorX& q) {
  for (std::size_t i = 0; i < gripper.gripperJoints.size(); ++i) {
    const double span = gripper.openValues[i] - gripper.closedValues[i];
    if (std::abs(span) < 1e-12) continue;
    const int variable = model.variableIndex(gripper.gripperJoints[i]);
    return std::clamp((q[variable] - gripper.closedValues[i]) / span, 0.0, 1.0);
  }
  return 0.0;
}

double openingAtFraction(const GripperGeometry& gripper, double fraction) {
  const std::vector<double>& curve = gripper.openingCurve;
  if (curve.empty()) return 0.0;
  const double x = std::clamp(fraction, 0.0, 1.0) * static_cast<double>(curve.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(x), curve.size() - 2);
  return curve[i] + (x - static_cast<double>(i)) * (curve[i + 1] - curve[i]);
}

double fractionForOpening(const GripperGeometry& gripper, double width) {
  const std::vector<double>& curve = gripper.openingCurve;
  if (curve.empty() || width >= curve.back()) return 1.0;
  if (width <= curve.front()) return 0.0;
  const std::size_t i = static_cast<std::size_t>(std::lower_bound(curve.begin(), curve.end(), width) - curve.begin());
  const double rise = curve[i] - curve[i - 1];
  const double within = rise > 0.0 ? (width - curve[i - 1]) / rise : 1.0;
  return (static_cast<double>(i - 1) + within) / static_cast<double>(curve.size() - 1);
}

VectorX withGripperOpening(const RobotModel& model, const GripperGeometry& gripper, VectorX q, double width) {
  return withGripperFraction(model, gripper, std::move(q), fractionForOpening(gripper, width));
}

double gripperOpening(const RobotModel& model, const GripperGeometry& gripper, const VectorX& q) {
  return gripper.hasGripper() ? openingAtFraction(gripper, gripperFraction(model, gripper, q)) : 0.0;
}

}  // namespace lang2manip
