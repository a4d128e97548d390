#include "lang2manip/language/object_descriptor.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>
#include <variant>

#include "lang2manip/language/words.hpp"
#include "lang2manip/symbolic/object_appearance.hpp"
#include "lang2manip/symbolic/object_heading.hpp"
#include "lang2manip/symbolic/surface_region.hpp"

namespace lang2manip {
namespace {

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

/// An object whose kind names nothing familiar ("obj_3") answers to its category's nouns ("cube",
/// "block"); a familiar kind keeps its own (an eraser is not "the box").
void addCategoryNouns(ObjectDescriptor& descriptor) {
  if (!descriptor.synonyms.empty() || descriptor.category.empty()) return;
  const Words kindWords = nameWords(descriptor.kind);
  const bool familiar = std::any_of(kindSynonymTable().begin(), kindSynonymTable().end(), [&](const KindSynonyms& entry) {
    return std::find(kindWords.begin(), kindWords.end(), entry.kindWord) != kindWords.end();
  });
  if (familiar) return;
  descriptor.synonyms.push_back(descriptor.category);
  for (const std::string& synonym : kindSynonyms(descriptor.category)) descriptor.synonyms.push_back(synonym);
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

std::vector<std::string> kindSynonyms(const std::string& kind) {
  const Words kindWords = nameWords(kind);
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

std::vector<ObjectDescriptor> describeObjects(const Scene& scene, const std::string& robot, const std::string& arm) {
  const Pose worldToBase = robotBase(scene, robot).inverse();
  std::vector<ObjectDescriptor> descriptors;
  for (const SceneObject& object : scene.objects()) {
    ObjectDescriptor descriptor;
    descriptor.name = object.name;
    descriptor.kind = object.kind;
    descriptor.synonyms = kindSynonyms(object.kind);
    descriptor.category = objectCategory(object);
    addCategoryNouns(descriptor);
    descriptor.colours = objectColours(object);
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
      if (const auto area = supportArea(scene, object.name, robot, nullptr, arm)) descriptor.reachableTop = area->reachable;
    }
    descriptors.push_back(std::move(descriptor));
  }
  classifySizes(descriptors);
  return descriptors;
}

}  // namespace lang2manip
