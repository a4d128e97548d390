#include "lang2manip/grounding/gripper_fingers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <variant>

#include "lang2manip/core/error.hpp"

namespace lang2manip::gripper_detail {
namespace {

/// Directions closer than this (cosine) to one of the tool frame's axes are snapped to it.
constexpr double kSnapCosine = 0.9;
/// Finger links whose closing motion is below this fraction of the largest are not used to tell
/// whether the fingers close along one axis.
constexpr double kMinorMotion = 0.2;
/// Two closing motions along one line (|cos| above this) belong to a parallel gripper.
constexpr double kCollinearCosine = 0.85;
/// A fixed jaw's face starts this far along the moving jaw, from its hinge to its tip.
constexpr double kJawFaceStart = 0.3;

void addShapePoints(const Shape& shape, std::size_t limit, std::vector<Vector3>& points) {
  std::vector<Vector3> local;
  if (const auto* box = std::get_if<Box>(&shape.geometry)) {
    for (int corner = 0; corner < 8; ++corner) {
      local.emplace_back((corner & 1 ? 0.5 : -0.5) * box->size.x(), (corner & 2 ? 0.5 : -0.5) * box->size.y(),
                         (corner & 4 ? 0.5 : -0.5) * box->size.z());
    }
  } else if (const auto* sphere = std::get_if<Sphere>(&shape.geometry)) {
    for (int axis = 0; axis < 3; ++axis) {
      local.push_back(Vector3::Unit(axis) * sphere->radius);
      local.push_back(-Vector3::Unit(axis) * sphere->radius);
    }
  } else if (const auto* cylinder = std::get_if<Cylinder>(&shape.geometry)) {
    for (int k = 0; k < 16; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / 16.0;
      const Vector3 rim(cylinder->radius * std::cos(angle), cylinder->radius * std::sin(angle), 0.0);
      local.push_back(rim + Vector3::UnitZ() * 0.5 * cylinder->length);
      local.push_back(rim - Vector3::UnitZ() * 0.5 * cylinder->length);
    }
  } else if (const auto* mesh = std::get_if<MeshGeometry>(&shape.geometry)) {
    if (mesh->mesh) {
      const std::vector<Vector3>& vertices = mesh->mesh->vertices;
      const std::size_t stride = std::max<std::size_t>(1, (vertices.size() + limit - 1) / limit);
      for (std::size_t v = 0; v < vertices.size(); v += stride) local.push_back(vertices[v].cwiseProduct(mesh->scale));
    }
  }
  for (const Vector3& p : local) points.push_back(shape.origin * p);
}

/// The tool-frame axis closest to `direction` when within kSnapCosine of it, else `direction`.
Vector3 snapped(const Vector3& direction) {
  for (int axis = 0; axis < 3; ++axis) {
    const double c = direction.dot(Vector3::Unit(axis));
    if (std::abs(c) >= kSnapCosine) return Vector3::Unit(axis) * (c > 0 ? 1.0 : -1.0);
  }
  return direction;
}

Vector3 across(const Vector3& v, const Vector3& approach) { return v - v.dot(approach) * approach; }

/// A single jaw's fingers reach where its fixed jaw reaches: from the hinge to the fixed jaw's
/// point farthest from it on the moving jaw's side (at either end of its travel).
std::optional<Vector3> approachOfJaw(const FingerSet& fingers) {
  if (!fingers.fixedJaw() || fingers.rootsOpen().empty()) return std::nullopt;
  const Vector3 hinge = fingers.rootsOpen().front();
  std::vector<Vector3> sides;
  for (const double fraction : {0.0, 1.0}) {
    const std::vector<Pose> poses = fingers.linkPoses(fraction);
    Vector3 centre = Vector3::Zero();
    for (std::size_t i = 0; i < fingers.links().size(); ++i) centre += fingers.centroid(i, poses);
    sides.push_back(centre / static_cast<double>(fingers.links().size()) - hinge);
  }
  const Pose& X_TJ = fingers.openPoses()[static_cast<std::size_t>(fingers.fixedJaw()->link)];
  Vector3 tip = hinge;
  for (const Vector3& local : fingers.fixedJaw()->points) {
    const Vector3 p = X_TJ * local;
    const bool beside = std::any_of(sides.begin(), sides.end(), [&](const Vector3& side) { return (p - hinge).dot(side) > 0.0; });
    if (beside && (p - hinge).norm() > (tip - hinge).norm()) tip = p;
  }
  if ((tip - hinge).norm() < 1e-9) return std::nullopt;
  return snapped((tip - hinge).normalized());
}

Vector3 approachOf(const FingerSet& fingers) {
  if (const std::optional<Vector3> jaw = approachOfJaw(fingers)) return *jaw;
  const std::vector<Pose>& open = fingers.openPoses();
  Vector3 rootMean = Vector3::Zero();
  for (const Vector3& root : fingers.rootsOpen()) rootMean += root;
  rootMean /= static_cast<double>(fingers.rootsOpen().size());
  Vector3 centre = Vector3::Zero();
  for (std::size_t i = 0; i < fingers.links().size(); ++i) centre += fingers.centroid(i, open);
  centre /= static_cast<double>(fingers.links().size());
  const Vector3 direction = centre - rootMean;
  return direction.norm() < 1e-9 ? Vector3::UnitZ() : snapped(direction.normalized());
}

/// The index of the link in `members` reaching farthest along `approach` when open.
std::size_t farthestReaching(const FingerSet& fingers, const std::vector<std::size_t>& members, const Vector3& approach) {
  const std::vector<Pose>& open = fingers.openPoses();
  std::size_t best = members.front();
  double reach = -std::numeric_limits<double>::infinity();
  for (std::size_t i : members) {
    for (const Vector3& p : fingers.pointsInTool(i, open)) {
      if (p.dot(approach) > reach) {
        reach = p.dot(approach);
        best = i;
      }
    }
  }
  return best;
}

void layoutTwoSides(const FingerSet& fingers, const std::vector<Vector3>& motion, PadLayout& layout) {
  std::vector<std::size_t> plus, minus;
  const std::vector<Pose>& open = fingers.openPoses();
  Vector3 centre = Vector3::Zero();
  for (std::size_t i = 0; i < fingers.links().size(); ++i) centre += fingers.centroid(i, open);
  centre /= static_cast<double>(fingers.links().size());
  // A link's side is where it sits when open (the limits may name the travel backwards, so the
  // way it moves only decides for a link on the axis).
  for (std::size_t i = 0; i < motion.size(); ++i) {
    const double offset = (fingers.centroid(i, open) - centre).dot(layout.closing);
    const double side = std::abs(offset) > 1e-4 ? offset : -motion[i].dot(layout.closing);
    (side >= 0.0 ? plus : minus).push_back(i);
  }
  if (plus.empty() || minus.empty()) {
    // One finger moves against a fixed jaw: the jaw is the rest of the gripper's moved geometry.
    layout.pads = {farthestReaching(fingers, plus.empty() ? minus : plus, layout.approach)};
    return;
  }
  layout.pads = {farthestReaching(fingers, plus, layout.approach), farthestReaching(fingers, minus, layout.approach)};
}

void layoutRadial(const FingerSet& fingers, const std::vector<Vector3>& motion, double largest, PadLayout& layout) {
  layout.radial = true;
  std::vector<std::vector<std::size_t>> groups;
  std::vector<Vector3> directions;
  for (std::size_t i = 0; i < motion.size(); ++i) {
    if (motion[i].norm() < kMinorMotion * largest) continue;
    const Vector3 d = motion[i].normalized();
    std::size_t g = 0;
    while (g < groups.size() && directions[g].dot(d) < kCollinearCosine) ++g;
    if (g == groups.size()) {
      groups.emplace_back();
      directions.push_back(d);
    }
    groups[g].push_back(i);
  }
  const std::vector<Pose>& open = fingers.openPoses();
  for (const std::vector<std::size_t>& group : groups) layout.pads.push_back(farthestReaching(fingers, group, layout.approach));
  layout.axisPoint = Vector3::Zero();
  for (std::size_t pad : layout.pads) layout.axisPoint += fingers.centroid(pad, open);
  layout.axisPoint /= static_cast<double>(layout.pads.size());
  // Outward is where each pad sits from the axis (the limits may name the travel backwards).
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const Vector3 offset = across(fingers.centroid(layout.pads[g], open) - layout.axisPoint, layout.approach);
    layout.outward.push_back(offset.norm() > 1e-9 ? offset.normalized() : -directions[g]);
  }
}

/// Along `closing`: the inner face of the fixed jaw and where the tip of the pad's face is (the
/// point of it reaching farthest along `approach`: a turning jaw holds what fits under its tip),
/// the one on the + side first.
std::pair<double, double> padAgainstJaw(const std::vector<Vector3>& pad, const std::vector<Vector3>& jaw, const Vector3& closing,
                                        const Vector3& approach) {
  const Vector3 tip = *std::max_element(pad.begin(), pad.end(), [&](const Vector3& a, const Vector3& b) { return a.dot(approach) < b.dot(approach); });
  double jawLow = std::numeric_limits<double>::infinity(), jawHigh = -jawLow, jawMean = 0.0;
  for (const Vector3& p : jaw) {
    jawLow = std::min(jawLow, p.dot(closing));
    jawHigh = std::max(jawHigh, p.dot(closing));
    jawMean += p.dot(closing) / static_cast<double>(jaw.size());
  }
  return tip.dot(closing) >= jawMean ? std::pair{tip.dot(closing), jawHigh} : std::pair{jawLow, tip.dot(closing)};
}

/// Along the closing axis: the inner face of the + side pad (its lowest point) and of the - side
/// pad (its highest; the tool frame's axis when one finger closes onto it).
std::pair<double, double> innerFaces(const FingerSet& fingers, const PadLayout& layout, const std::vector<Pose>& poses) {
  const std::vector<Vector3> jaw = jawContactPoints(fingers, layout, poses);
  if (layout.pads.size() == 1 && !jaw.empty()) return padAgainstJaw(padContactPoints(fingers, layout, 0, poses), jaw, layout.closing, layout.approach);
  double inner = std::numeric_limits<double>::infinity();
  for (const Vector3& p : padContactPoints(fingers, layout, 0, poses)) inner = std::min(inner, p.dot(layout.closing));
  if (layout.pads.size() < 2) return {inner, 0.0};
  double outer = -std::numeric_limits<double>::infinity();
  for (const Vector3& p : padContactPoints(fingers, layout, 1, poses)) outer = std::max(outer, p.dot(layout.closing));
  return {inner, outer};
}

/// The contact face of each pad, looking toward the other pads (a single finger's, the way it
/// closes).
void findContactFaces(const FingerSet& fingers, const std::vector<Vector3>& motion, PadLayout& layout) {
  // Half-way through the travel: rotating fingers turn their pads toward each other as they close;
  // a single jaw lies along its fixed jaw where it is closed.
  const bool againstJaw = !layout.radial && layout.pads.size() == 1 && fingers.fixedJaw();
  const std::vector<Pose> open = fingers.linkPoses(againstJaw ? 0.0 : 0.5);
  for (std::size_t f = 0; f < layout.pads.size(); ++f) {
    Vector3 inward = f == 0 ? -layout.closing : layout.closing;
    if (layout.radial) inward = -layout.outward[f];
    if (!layout.radial && layout.pads.size() == 1) inward = motion[layout.pads[f]].dot(layout.closing) >= 0.0 ? layout.closing : -layout.closing;
    const FingerLink& pad = fingers.links()[layout.pads[f]];
    layout.contactFaces.push_back(contactFace(pad, open[static_cast<std::size_t>(pad.link)], inward));
    if (againstJaw && !fingers.rootsOpen().empty()) {
      // The fixed jaw's face toward the pad, ahead of the hinge (not the body behind it).
      const double hinge = fingers.rootsOpen().front().dot(layout.approach);
      double reach = hinge;
      for (const Vector3& p : fingers.pointsInTool(layout.pads[f], open)) reach = std::max(reach, p.dot(layout.approach));
      const FingerLink& jaw = *fingers.fixedJaw();
      layout.jawFace = contactFace(jaw, open[static_cast<std::size_t>(jaw.link)], -inward, layout.approach,
                                   hinge + kJawFaceStart * (reach - hinge));
    }
  }
}

/// The geometry of the rigid body (links joined by fixed joints) that `link` belongs to, leaving
/// out `moved`, as one link in the frame of the body's root; none without geometry.
std::optional<FingerLink> bodyOf(const RobotModel& model, int link, const std::set<int>& moved) {
  int root = link;
  while (model.parentJoint(root) >= 0 && model.joints()[static_cast<std::size_t>(model.parentJoint(root))].type == JointType::kFixed) {
    root = model.parentLinkOf(model.parentJoint(root));
  }
  FingerLink body{root, {}, {}};
  std::vector<std::pair<int, Pose>> stack{{root, Pose::Identity()}};
  while (!stack.empty()) {
    const auto [at, X_RL] = stack.back();
    stack.pop_back();
    if (moved.count(at)) continue;
    const Link& data = model.links()[static_cast<std::size_t>(at)];
    for (const Vector3& p : collisionPoints(data)) body.points.push_back(X_RL * p);
    for (Facet facet : collisionFacets(data)) {
      facet.normal = X_RL.linear() * facet.normal;
      for (Vector3& corner : facet.corners) corner = X_RL * corner;
      body.facets.push_back(std::move(facet));
    }
    for (int j = 0; j < static_cast<int>(model.joints().size()); ++j) {
      if (model.parentLinkOf(j) == at && model.joints()[static_cast<std::size_t>(j)].type == JointType::kFixed) {
        stack.emplace_back(model.childLinkOf(j), X_RL * model.joints()[static_cast<std::size_t>(j)].origin);
      }
    }
  }
  if (body.points.empty()) return std::nullopt;
  return body;
}

}  // namespace

std::vector<Vector3> collisionPoints(const Link& link, std::size_t limit) {
  std::vector<Vector3> points;
  for (const Shape& shape : link.collisions) addShapePoints(shape, limit, points);
  return points;
}

FingerSet::FingerSet(const RobotModel& model, const std::string& toolFrame, const std::vector<std::string>& joints,
                     std::vector<double> closed, std::vector<double> open)
    : model_(model), tool_(model.linkIndex(toolFrame)), closed_(std::move(closed)), open_(std::move(open)) {
  std::set<int> driven;
  for (const std::string& name : joints) {
    const int joint = model.jointIndex(name);
    variables_.push_back(model.variableIndex(name));
    driven.insert(joint);
    for (int j = 0; j < static_cast<int>(model.joints().size()); ++j) {
      if (model.mimicSource(j) >= 0 && model.mimicSource(j) == variables_.back()) driven.insert(j);
    }
  }
  std::set<int> moved;
  for (int joint : driven) {
    std::vector<int> stack{model.childLinkOf(joint)};
    while (!stack.empty()) {
      const int link = stack.back();
      stack.pop_back();
      if (!moved.insert(link).second) continue;
      for (int j = 0; j < static_cast<int>(model.joints().size()); ++j) {
        if (model.parentLinkOf(j) == link) stack.push_back(model.childLinkOf(j));
      }
    }
  }
  moved_.assign(moved.begin(), moved.end());
  openPoses_ = linkPoses(1.0);
  for (int joint : driven) {
    if (!moved.count(model.parentLinkOf(joint))) rootsOpen_.push_back(openPoses_[static_cast<std::size_t>(model.childLinkOf(joint))].translation());
  }
  for (int link : moved_) {
    std::vector<Vector3> points = collisionPoints(model.links()[static_cast<std::size_t>(link)]);
    if (!points.empty()) links_.push_back({link, std::move(points), collisionFacets(model.links()[static_cast<std::size_t>(link)])});
  }
  if (driven.size() == 1) fixedJaw_ = bodyOf(model, model.parentLinkOf(*driven.begin()), moved);
  if (links_.empty()) {
    std::string names;
    for (const std::string& name : joints) names += (names.empty() ? "" : ", ") + name;
    throw InputError("gripper of " + model.name() + ": its joints (" + names + ") move no link with collision geometry, "
                     "so there are no fingers to grasp with");
  }
}

VectorX FingerSet::configuration(double fraction) const {
  VectorX q = model_.middleConfiguration();
  for (std::size_t i = 0; i < variables_.size(); ++i) {
    q[variables_[i]] = closed_[i] + fraction * (open_[i] - closed_[i]);
  }
  return q;
}

std::vector<Pose> FingerSet::linkPoses(double fraction) const {
  std::vector<Pose> poses = model_.linkPoses(configuration(fraction));
  const Pose X_TR = poses[static_cast<std::size_t>(tool_)].inverse();
  for (Pose& pose : poses) pose = X_TR * pose;
  return poses;
}

std::vector<Vector3> FingerSet::pointsInTool(std::size_t i, const std::vector<Pose>& poses) const {
  const Pose& X_TL = poses[static_cast<std::size_t>(links_[i].link)];
  std::vector<Vector3> points;
  points.reserve(links_[i].points.size());
  for (const Vector3& p : links_[i].points) points.push_back(X_TL * p);
  return points;
}

double FingerSet::spread(double fraction) const {
  const std::vector<Pose> poses = linkPoses(fraction);
  Vector3 mean = Vector3::Zero();
  for (std::size_t i = 0; i < links_.size(); ++i) mean += centroid(i, poses);
  mean /= static_cast<double>(links_.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < links_.size(); ++i) sum += (centroid(i, poses) - mean).norm();
  return sum / static_cast<double>(links_.size());
}

Vector3 FingerSet::centroid(std::size_t i, const std::vector<Pose>& poses) const {
  Vector3 sum = Vector3::Zero();
  for (const Vector3& p : links_[i].points) sum += p;
  return poses[static_cast<std::size_t>(links_[i].link)] * (sum / static_cast<double>(links_[i].points.size()));
}

PadLayout layoutPads(const FingerSet& fingers, const std::string& where, const std::optional<Vector3>& approach) {
  PadLayout layout;
  layout.approach = approach ? *approach : approachOf(fingers);
  const std::vector<Pose>& open = fingers.openPoses();
  const std::vector<Pose> closed = fingers.linkPoses(0.0);
  std::vector<Vector3> motion;
  std::size_t main = 0;
  for (std::size_t i = 0; i < fingers.links().size(); ++i) {
    motion.push_back(across(fingers.centroid(i, closed) - fingers.centroid(i, open), layout.approach));
    if (motion[i].norm() > motion[main].norm()) main = i;
  }
  const double largest = motion[main].norm();
  if (largest < 1e-6) {
    throw InputError(where + ": the fingers do not move across the approach axis between closed and open "
                     "(check the gripper joints' limits, the SRDF's open and closed states, or the approach axis given)");
  }
  const Vector3 u = motion[main] / largest;
  const bool parallel = std::all_of(motion.begin(), motion.end(), [&](const Vector3& m) {
    return m.norm() < kMinorMotion * largest || std::abs(m.normalized().dot(u)) >= kCollinearCosine;
  });
  layout.closing = snapped(across(u, layout.approach).normalized());
  if (parallel) {
    layoutTwoSides(fingers, motion, layout);
  } else {
    layoutRadial(fingers, motion, largest, layout);
  }
  findContactFaces(fingers, motion, layout);
  return layout;
}

double padGap(const FingerSet& fingers, const PadLayout& layout, const std::vector<Pose>& poses) {
  if (layout.radial) {
    double radius = std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < layout.pads.size(); ++f) {
      for (const Vector3& p : padContactPoints(fingers, layout, f, poses)) {
        radius = std::min(radius, across(p - layout.axisPoint, layout.approach).dot(layout.outward[f]));
      }
    }
    return 2.0 * radius;
  }
  const auto [inner, outer] = innerFaces(fingers, layout, poses);
  return inner - outer;
}

double gapMiddle(const FingerSet& fingers, const PadLayout& layout, const std::vector<Pose>& poses) {
  if (layout.radial) return layout.axisPoint.dot(layout.closing);
  const auto [inner, outer] = innerFaces(fingers, layout, poses);
  return 0.5 * (inner + outer);
}

}  // namespace lang2manip::gripper_detail
