#include "lang2manip/cli/tabletop_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>

#include "lang2manip/core/error.hpp"
#include "lang2manip/grounding/object_semantics.hpp"
#include "lang2manip/model/triangle_mesh.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"
#include "lang2manip/symbolic/surface_region.hpp"

namespace lang2manip {
namespace {

constexpr double kBowlHeight = 0.05;
constexpr double kBowlWall = 0.008;
constexpr double kEdgeClearance = 0.03;
constexpr int kTries = 200;
/// The widest square bowl of the benchmarks' sizes (m), and the share of a small reach's short
/// side a bowl may take.
constexpr double kLargestSquareBowl = 0.15;
constexpr double kSmallReachBowlShare = 0.4;
constexpr double kSmallReachGap = 0.03;
constexpr double kBowlPlay = 0.015;
constexpr double kBlockSpacing = 0.01;

Shape coloured(const Geometry& geometry, const Vector3& offset, const PaletteColour& colour) {
  Shape shape;
  shape.geometry = geometry;
  shape.origin.translation() = offset;
  shape.material = Material{colour.name, Vector4(colour.r, colour.g, colour.b, 1.0), ""};
  return shape;
}

SceneObject block(const PaletteColour& colour, double edge) {
  SceneObject object;
  object.kind = "block";
  object.movable = true;
  object.collisions.push_back(coloured(Box{Vector3::Constant(edge)}, Vector3(0.0, 0.0, edge / 2.0), colour));
  return object;
}

SceneObject cylinder(const PaletteColour& colour, double radius, double height) {
  SceneObject object;
  object.kind = "cylinder";
  object.movable = true;
  object.collisions.push_back(coloured(Cylinder{radius, height}, Vector3(0.0, 0.0, height / 2.0), colour));
  return object;
}

/// An open square bowl: a floor and four walls, its cavity the room between them.
SceneObject bowl(const PaletteColour& colour, double width) {
  SceneObject object;
  object.kind = "bowl";
  object.role = ObjectRole::kContainer;
  const double half = width / 2.0;
  object.collisions.push_back(coloured(Box{Vector3(width, width, kBowlWall)}, Vector3(0.0, 0.0, kBowlWall / 2.0), colour));
  for (int side : {-1, 1}) {
    object.collisions.push_back(coloured(Box{Vector3(kBowlWall, width, kBowlHeight)},
                                         Vector3(side * (half - kBowlWall / 2.0), 0.0, kBowlHeight / 2.0), colour));
    object.collisions.push_back(coloured(Box{Vector3(width - 2.0 * kBowlWall, kBowlWall, kBowlHeight)},
                                         Vector3(0.0, side * (half - kBowlWall / 2.0), kBowlHeight / 2.0), colour));
  }
  const double inner = half - kBowlWall;
  object.cavity = AlignedBox3(Vector3(-inner, -inner, kBowlWall), Vector3(inner, inner, kBowlHeight));
  return object;
}

/// The surface of revolution about z of the closed polyline `profile` (r, z), r >= 0, outward
/// normals for a counter-clockwise profile; points on the axis close the surface there.
std::shared_ptr<const TriangleMesh> revolved(const std::vector<std::pair<double, double>>& profile, int segments) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->source = "generated round bowl";
  std::vector<std::vector<int>> rings;
  for (const auto& [r, z] : profile) {
    std::vector<int> ring;
    for (int k = 0; k < (r > 0.0 ? segments : 1); ++k) {
      const double angle = 2.0 * std::numbers::pi * k / segments;
      ring.push_back(static_cast<int>(mesh->vertices.size()));
      mesh->vertices.emplace_back(r * std::cos(angle), r * std::sin(angle), z);
    }
    rings.push_back(std::move(ring));
  }
  const auto at = [&](const std::vector<int>& ring, int k) { return ring[static_cast<std::size_t>(k % static_cast<int>(ring.size()))]; };
  for (std::size_t i = 0; i + 1 < rings.size(); ++i) {
    const std::vector<int>& a = rings[i];
    const std::vector<int>& b = rings[i + 1];
    for (int k = 0; k < segments; ++k) {
      if (a.size() > 1) mesh->triangles.push_back({at(a, k), at(a, k + 1), at(b, k)});
      if (b.size() > 1) mesh->triangles.push_back({at(a, k + 1), at(b, k + 1), at(b, k)});
    }
  }
  return mesh;
}

/// A round bowl as the benchmarks draw it: a tapered wall on a flat foot, `width` across the rim,
/// its cavity not declared but measured from its shape (measuredCavity()).
SceneObject roundBowl(const PaletteColour& colour, double width) {
  const double rim = width / 2.0, foot = 0.75 * rim;
  const std::vector<std::pair<double, double>> profile{{0.0, 0.0},
                                                       {foot, 0.0},
                                                       {rim, kBowlHeight},
                                                       {rim - kBowlWall, kBowlHeight},
                                                       {foot - kBowlWall, kBowlWall},
                                                       {0.0, kBowlWall}};
  SceneObject object;
  object.kind = "bowl";
  object.role = ObjectRole::kContainer;
  object.collisions.push_back(coloured(MeshGeometry{revolved(profile, 32), Vector3::Ones(), "generated:round_bowl"}, Vector3::Zero(), colour));
  object.cavity = measuredCavity(object);
  if (!object.cavity) throw InputError("tabletop: the generated round bowl has no measurable cavity");
  return object;
}

/// Colours for `count` objects of one kind: distinct while the palette lasts.
std::vector<PaletteColour> drawColours(int count, bool distinct, Random& random) {
  std::vector<PaletteColour> palette = tabletopPalette();
  std::vector<PaletteColour> drawn;
  for (int i = 0; i < count; ++i) {
    if (palette.empty() || !distinct) palette = tabletopPalette();
    const std::size_t pick = static_cast<std::size_t>(random.uniform(0.0, static_cast<double>(palette.size()) - 1e-9));
    drawn.push_back(palette[pick]);
    if (distinct) palette.erase(palette.begin() + static_cast<std::ptrdiff_t>(pick));
  }
  return drawn;
}

std::string uniqueName(const std::string& base, std::map<std::string, int>& used) {
  const int n = ++used[base];
  return n == 1 ? base : base + "_" + std::to_string(n);
}

/// The narrowest bowl whose cavity holds `blocks` blocks of `edge` side by side (a square grid,
/// 1 cm apart) with 1.5 cm of play: a square bowl's cavity is its width less two walls; a round
/// one's, the square inscribed in its floor (roundBowl(): the foot 37.5 % of the width across,
/// less the wall).
double widthHolding(bool round, double edge, int blocks) {
  const double perSide = std::ceil(std::sqrt(static_cast<double>(std::max(blocks, 1))));
  const double cavity = perSide * edge + (perSide - 1.0) * kBlockSpacing + kBowlPlay;
  return round ? (cavity / std::numbers::sqrt2 + kBowlWall) / 0.375 : cavity + 2.0 * kBowlWall;
}

/// One object drawn but not yet built: what it is, its colour and size. Scenes are laid out from
/// these footprints and built only once they fit, so that a draw that does not fit costs no mesh.
struct DrawnObject {
  enum class Kind { kBlock, kSquareBowl, kRoundBowl, kCylinder };
  Kind kind;
  PaletteColour colour;
  /// Edge (block), width across the rim (bowls) or diameter (cylinder), metres.
  double width;
  /// A cylinder's height, metres (the others' heights are fixed by their kind).
  double height = 0.0;
  std::string name{};
  Vector3 centre = Vector3::Zero();
};

/// The objects of `request`, bowls `bowlScale` times the benchmarks' sizes (12-15 cm square,
/// 15-18 cm round), none too small to hold request.blocksPerBowl of the largest blocks.
std::vector<DrawnObject> drawObjects(const TabletopRequest& request, double bowlScale, Random& random) {
  using Kind = DrawnObject::Kind;
  std::vector<DrawnObject> objects;
  std::map<std::string, int> used;
  for (const PaletteColour& colour : drawColours(request.bowls, request.distinctColours, random)) {
    // Round bowls are drawn wider: their sloping wall leaves less room at the floor.
    const bool round = random.uniform(0.0, 1.0) < request.roundBowlShare;
    const double drawn = bowlScale * (round ? random.uniform(0.15, 0.18) : random.uniform(0.12, 0.15));
    const double width = std::max(drawn, widthHolding(round, request.blockEdgeMax, request.blocksPerBowl));
    objects.push_back({round ? Kind::kRoundBowl : Kind::kSquareBowl, colour, width});
    objects.back().name = uniqueName(std::string(colour.name) + "_bowl", used);
  }
  std::vector<PaletteColour> blockColours = drawColours(request.oneBlockColour ? 1 : request.blocks, request.distinctColours, random);
  if (request.oneBlockColour && !blockColours.empty()) blockColours.assign(static_cast<std::size_t>(request.blocks), blockColours.front());
  for (const PaletteColour& colour : blockColours) {
    objects.push_back({Kind::kBlock, colour, random.uniform(request.blockEdgeMin, request.blockEdgeMax)});
    objects.back().name = uniqueName(std::string(colour.name) + "_block", used);
  }
  for (const PaletteColour& colour : drawColours(request.cylinders, request.distinctColours, random)) {
    const double radius = random.uniform(0.015, 0.02);
    objects.push_back({Kind::kCylinder, colour, 2.0 * radius, random.uniform(0.04, 0.07)});
    objects.back().name = uniqueName(std::string(colour.name) + "_cylinder", used);
  }
  return objects;
}

/// Sets every object's centre at a random place of `area` (base frame), `gap` apart; false when
/// some object found no place.
bool scatter(std::vector<DrawnObject>& objects, const AlignedBox3& area, double gap, Random& random) {
  std::vector<AlignedBox3> taken;
  for (DrawnObject& object : objects) {
    const Vector3 size(object.width, object.width, 0.0);
    const double margin = kEdgeClearance + object.width / 2.0;
    if (area.sizes().x() < 2.0 * margin || area.sizes().y() < 2.0 * margin) return false;
    bool placed = false;
    for (int attempt = 0; attempt < kTries && !placed; ++attempt) {
      const Vector3 centre(random.uniform(area.min().x() + margin, area.max().x() - margin),
                           random.uniform(area.min().y() + margin, area.max().y() - margin), area.max().z());
      const AlignedBox3 footprint(centre - size / 2.0, centre + size / 2.0);
      const bool free = std::none_of(taken.begin(), taken.end(), [&](const AlignedBox3& other) {
        return boxGap(footprint, other) < gap;
      });
      if (!free) continue;
      taken.push_back(footprint);
      object.centre = centre;
      placed = true;
    }
    if (!placed) return false;
  }
  return true;
}

SceneObject built(const DrawnObject& drawn, const Pose& base) {
  using Kind = DrawnObject::Kind;
  SceneObject object;
  switch (drawn.kind) {
    case Kind::kBlock: object = block(drawn.colour, drawn.width); break;
    case Kind::kSquareBowl: object = bowl(drawn.colour, drawn.width); break;
    case Kind::kRoundBowl: object = roundBowl(drawn.colour, drawn.width); break;
    case Kind::kCylinder: object = cylinder(drawn.colour, drawn.width / 2.0, drawn.height); break;
  }
  object.name = drawn.name;
  object.pose = Pose::Identity();
  object.pose.linear() = base.linear();
  object.pose.translation() = base * drawn.centre;
  return object;
}

/// How a draw is sized: the bowls' share of the benchmarks' sizes and the gap between objects.
struct DrawSizing {
  double bowlScale;
  double gap;
};

/// The benchmarks' bowl sizes and the requested gap first; on a reach too small for them (a square
/// bowl wider than 40 % of its short side leaves no room beside it: YuMi's one arm), bowls scaled
/// down to that and at most 3 cm between objects next.
std::vector<DrawSizing> drawSizings(const TabletopRequest& request, const AlignedBox3& reachable) {
  const double shortSide = std::min(reachable.sizes().x(), reachable.sizes().y());
  std::vector<DrawSizing> sizings{{1.0, request.gap}};
  if (request.bowls > 0 && kSmallReachBowlShare * shortSide < kLargestSquareBowl) {
    sizings.push_back({kSmallReachBowlShare * shortSide / kLargestSquareBowl, std::min(request.gap, kSmallReachGap)});
  }
  return sizings;
}

}  // namespace

const std::vector<PaletteColour>& tabletopPalette() {
  static const std::vector<PaletteColour> palette{
      {"blue", 0.30, 0.47, 0.65}, {"red", 0.88, 0.34, 0.35},    {"green", 0.35, 0.63, 0.31},  {"orange", 0.95, 0.56, 0.17},
      {"yellow", 0.93, 0.79, 0.28}, {"purple", 0.69, 0.48, 0.63}, {"pink", 1.00, 0.62, 0.66}, {"cyan", 0.46, 0.72, 0.70},
      {"brown", 0.61, 0.46, 0.38},  {"grey", 0.73, 0.69, 0.67},
  };
  return palette;
}

std::string actingArm(const Scene& scene) {
  if (scene.robots().empty() || scene.robots().front().model->semantics().manipulators.empty()) return {};
  return scene.robots().front().model->semantics().manipulators.front().name;
}

AlignedBox3 deskReach(const Scene& scene) {
  std::string why;
  const auto area = supportArea(scene, "desk", "", &why, actingArm(scene));
  if (!area) throw InputError("tabletop: the scene has no desk the robot reaches: " + why);
  return area->reachable;
}

std::optional<Scene> generateTabletop(const Scene& desk, const TabletopRequest& request, Random& random) {
  if (request.blocks < 0 || request.bowls < 0 || request.cylinders < 0) throw InputError("tabletop: object counts must be >= 0");
  Scene scene = desk;
  std::vector<std::string> removed;
  for (const SceneObject& object : scene.objects()) {
    if (object.role != ObjectRole::kSupport) removed.push_back(object.name);
  }
  for (const std::string& name : removed) scene.removeObject(name);
  const AlignedBox3 reachable = deskReach(scene);
  const Pose base = robotBaseFrame(scene, "");
  for (const DrawSizing& sizing : drawSizings(request, reachable)) {
    for (int attempt = 0; attempt < kTries; ++attempt) {
      std::vector<DrawnObject> objects = drawObjects(request, sizing.bowlScale, random);
      if (!scatter(objects, reachable, sizing.gap, random)) continue;
      Scene result = scene;
      for (const DrawnObject& object : objects) result.addObject(built(object, base));
      return result;
    }
  }
  return std::nullopt;
}

std::vector<std::string> objectsOfKind(const Scene& scene, const std::string& kind) {
  std::vector<std::string> names;
  for (const SceneObject& object : scene.objects()) {
    if (object.kind == kind) names.push_back(object.name);
  }
  return names;
}

std::string colourOf(const std::string& object) { return object.substr(0, object.find('_')); }

}  // namespace lang2manip
