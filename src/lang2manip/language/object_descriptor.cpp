#include "lang2manip/language/object_descriptor.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>
#include <variant>

#include "lang2manip/language/words.hpp"
#include "lang2manip/symbolic/object_heading.hpp"
#include "lang2manip/symbolic/surface_region.hpp"

namespace lang2manip {
namespace {

struct ColourPrototype {
  const char* name;
  double r, g, b;
};

// Several prototypes per name so that dark and light shades find their colour; the last row holds
// the muted shades of the tabletop benchmarks' palettes (Code as Policies, Ravens), so that their
// red is red and their blue is blue.
constexpr std::array<ColourPrototype, 37> kColourPrototypes{{
    {"black", 0.02, 0.02, 0.02},  {"black", 0.12, 0.12, 0.12},
    {"grey", 0.30, 0.30, 0.30},   {"grey", 0.50, 0.50, 0.50},  {"grey", 0.70, 0.70, 0.70},
    {"white", 1.00, 1.00, 1.00},  {"white", 0.90, 0.90, 0.88},
    {"red", 0.90, 0.10, 0.10},    {"red", 0.60, 0.05, 0.05},
    {"green", 0.10, 0.75, 0.20},  {"green", 0.10, 0.40, 0.10}, {"green", 0.50, 0.85, 0.40},
    {"blue", 0.10, 0.20, 0.90},   {"blue", 0.05, 0.10, 0.50},  {"blue", 0.35, 0.55, 0.95},
    {"yellow", 0.95, 0.90, 0.10}, {"yellow", 1.00, 0.95, 0.50},
    {"orange", 1.00, 0.55, 0.05}, {"orange", 0.90, 0.40, 0.10},
    {"purple", 0.50, 0.20, 0.70}, {"purple", 0.30, 0.05, 0.40},
    {"pink", 1.00, 0.60, 0.75},   {"pink", 0.95, 0.40, 0.70},
    {"brown", 0.55, 0.35, 0.20},  {"brown", 0.72, 0.52, 0.32}, {"brown", 0.35, 0.20, 0.10},
    {"cyan", 0.10, 0.80, 0.80},
    {"blue", 0.30, 0.47, 0.65},   {"red", 0.88, 0.34, 0.35},   {"green", 0.35, 0.63, 0.31},  {"orange", 0.95, 0.56, 0.17},
    {"yellow", 0.93, 0.79, 0.28}, {"purple", 0.69, 0.48, 0.63}, {"pink", 1.00, 0.62, 0.66},  {"cyan", 0.46, 0.72, 0.70},
    {"brown", 0.61, 0.46, 0.38},  {"grey", 0.73, 0.69, 0.67},
}};

struct KindSynonyms {
  const char* kindWord;
  std::vector<const char*> synonyms;
};

const std::vector<KindSynonyms>& kindSynonymTable() {
  static const std::vector<KindSynonyms> table{
      {"marker", {"pen", "felt tip", "felt tip pen", "felt pen", "whiteboard marker", "highlighter"}},
      {"eraser", {"rubber"}},
      {"holder", {"pen holder", "pencil holder", "cup", "pen cup", "pencil cup", "pot", "pen pot",
                  "container", "caddy"}},
      {"desk", {"table", "tabletop", "table top", "surface", "workbench", "bench", "worktop"}},
      {"table", {"desk", "tabletop", "table top", "surface", "workbench", "bench", "worktop"}},
      {"cup", {"mug", "glass", "tumbler"}},
      {"mug", {"cup"}},
      {"block", {"cube", "brick"}},
      {"cube", {"block", "brick"}},
      {"box", {"bin", "crate", "container"}},
      {"bin", {"box", "container"}},
      {"bowl", {"dish", "container"}},
      {"tray", {"plate"}},
      {"bottle", {"flask"}},
      {"can", {"tin"}},
      {"ball", {"sphere"}},
  };
  return table;
}

double boundsVolume(const AlignedBox3& box) {
  if (box.isEmpty()) return 0.0;
  const Vector3 size = box.sizes();
  return size.x() * size.y() * size.z();
}

/// The material of the visual (or collision) shape with the largest bounding box.
const Material* mainMaterial(const SceneObject& object) {
  const std::vector<Shape>& shapes = object.visuals.empty() ? object.collisions : object.visuals;
  const Material* best = nullptr;
  double bestVolume = -1.0;
  for (const Shape& shape : shapes) {
    if (!shape.material) continue;
    const double volume = boundsVolume(shapeBounds(shape));
    if (volume > bestVolume) {
      best = &*shape.material;
      bestVolume = volume;
    }
  }
  return best;
}

/// The colour words of its name ("red_block": red), which the author chose; else the nearest named
/// colour of its main material.
std::vector<std::string> coloursOf(const SceneObject& object) {
  std::vector<std::string> colours;
  const std::vector<std::string> known = colourNames();
  for (const std::string& word : tokenize(object.name)) {
    const bool isColour = std::find(known.begin(), known.end(), word) != known.end();
    if (isColour && std::find(colours.begin(), colours.end(), word) == colours.end()) {
      colours.push_back(word);
    }
  }
  if (const Material* material = mainMaterial(object); material != nullptr && colours.empty()) {
    colours.push_back(nearestColourName(material->rgba.head<3>()));
  }
  return colours;
}

/// Size classes by rank of volume among the movable objects.
void classifySizes(std::vector<ObjectDescriptor>& descriptors) {
  std::vector<double> volumes;
  for (const ObjectDescriptor& descriptor : descriptors) {
    if (descriptor.movable) volumes.push_back(descriptor.volume);
  }
  std::sort(volumes.begin(), volumes.end());
  const auto count = static_cast<double>(volumes.size());
  for (ObjectDescriptor& descriptor : descriptors) {
    const auto below = static_cast<double>(
        std::lower_bound(volumes.begin(), volumes.end(), descriptor.volume) - volumes.begin());
    if (volumes.empty()) descriptor.sizeClass = "medium";
    else if (below >= count * 2.0 / 3.0) descriptor.sizeClass = "large";
    else if (below < count / 3.0) descriptor.sizeClass = "small";
    else descriptor.sizeClass = "medium";
  }
}

Pose robotBase(const Scene& scene, const std::string& robot) {
  if (!robot.empty()) return scene.robot(robot).basePose;
  if (!scene.robots().empty()) return scene.robots().front().basePose;
  return Pose::Identity();
}

/// "box", "cylinder" or "sphere" for an object of one such collision shape, else empty.
std::string shapeName(const SceneObject& object) {
  if (object.collisions.size() != 1) return {};
  const Geometry& geometry = object.collisions.front().geometry;
  if (std::holds_alternative<Box>(geometry)) return "box";
  if (std::holds_alternative<Cylinder>(geometry)) return "cylinder";
  if (std::holds_alternative<Sphere>(geometry)) return "sphere";
  return {};
}

}  // namespace

std::string nearestColourName(const Vector3& rgb) {
  const char* best = "grey";
  double bestDistance = std::numeric_limits<double>::infinity();
  for (const ColourPrototype& prototype : kColourPrototypes) {
    const double distance = (rgb - Vector3(prototype.r, prototype.g, prototype.b)).squaredNorm();
    if (distance < bestDistance) {
      best = prototype.name;
      bestDistance = distance;
    }
  }
  return best;
}

std::vector<std::string> colourNames() {
  std::vector<std::string> names;
  for (const ColourPrototype& prototype : kColourPrototypes) {
    if (std::find(names.begin(), names.end(), prototype.name) == names.end()) {
      names.emplace_back(prototype.name);
    }
  }
  return names;
}

std::vector<std::string> kindSynonyms(const std::string& kind) {
  const Words kindWords = tokenize(kind);
  std::vector<std::string> synonyms;
  for (const KindSynonyms& entry : kindSynonymTable()) {
    if (std::find(kindWords.begin(), kindWords.end(), entry.kindWord) == kindWords.end()) continue;
    for (const char* synonym : entry.synonyms) {
      if (std::find(synonyms.begin(), synonyms.end(), synonym) == synonyms.end()) {
        synonyms.emplace_back(synonym);
      }
    }
  }
  return synonyms;
}

std::vector<ObjectDescriptor> describeObjects(const Scene& scene, const std::string& robot) {
  const Pose worldToBase = robotBase(scene, robot).inverse();
  std::vector<ObjectDescriptor> descriptors;
  for (const SceneObject& object : scene.objects()) {
    ObjectDescriptor descriptor;
    descriptor.name = object.name;
    descriptor.kind = object.kind;
    descriptor.synonyms = kindSynonyms(object.kind);
    descriptor.colours = coloursOf(object);
    descriptor.dimensions = object.dimensions();
    descriptor.volume = boundsVolume(object.localBounds());
    descriptor.position = worldToBase * object.worldBounds().center();
    const AlignedBox3 world = object.worldBounds();
    for (int corner = 0; corner < 8; ++corner) descriptor.bounds.extend(worldToBase * world.corner(static_cast<AlignedBox3::CornerType>(corner)));
    descriptor.origin = worldToBase * object.pose.translation();
    descriptor.shape = shapeName(object);
    if (const auto side = longSideYaw(object, worldToBase.linear() * object.pose.linear())) descriptor.longSideYaw = *side;
    descriptor.movable = object.movable;
    descriptor.role = object.role;
    if (object.cavity) descriptor.cavitySize = object.cavity->sizes();
    if (object.role == ObjectRole::kSupport) {
      if (const auto area = supportArea(scene, object.name, robot)) descriptor.reachableTop = area->reachable;
    }
    descriptors.push_back(std::move(descriptor));
  }
  classifySizes(descriptors);
  return descriptors;
}

}  // namespace lang2manip
