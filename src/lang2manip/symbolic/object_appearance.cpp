#include "lang2manip/symbolic/object_appearance.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <limits>
#include <variant>

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

double boxVolume(const AlignedBox3& box) { return box.isEmpty() ? 0.0 : box.sizes().prod(); }

/// The material of the visual (or collision) shape with the largest bounding box.
/// The colour of the largest shape that has one: its URDF material, else its mesh file's own.
std::optional<Vector3> mainColour(const SceneObject& object) {
  const std::vector<Shape>& shapes = object.visuals.empty() ? object.collisions : object.visuals;
  std::optional<Vector3> best;
  double bestVolume = -1.0;
  for (const Shape& shape : shapes) {
    std::optional<Vector3> colour;
    if (shape.material) {
      colour = shape.material->rgba.head<3>();
    } else if (const auto* mesh = std::get_if<MeshGeometry>(&shape.geometry); mesh != nullptr && mesh->mesh) {
      colour = mesh->mesh->colour;
    }
    if (!colour) continue;
    const double volume = boxVolume(shapeBounds(shape));
    if (volume > bestVolume) {
      best = colour;
      bestVolume = volume;
    }
  }
  return best;
}

/// The lower-case words of a name: split at anything but letters ("red_block_2": red, block).
std::vector<std::string> nameWords(const std::string& name) {
  std::vector<std::string> words;
  std::string word;
  for (const char c : name + " ") {
    if (std::isalpha(static_cast<unsigned char>(c))) {
      word += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else if (!word.empty()) {
      words.push_back(word);
      word.clear();
    }
  }
  return words;
}

std::string boxCategory(const Vector3& size) {
  const double smallest = size.minCoeff(), largest = size.maxCoeff();
  if (largest <= 1.2 * smallest) return "cube";
  if (size.z() < 0.25 * std::min(size.x(), size.y())) return "plate";
  return "box";
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
    if (std::find(names.begin(), names.end(), prototype.name) == names.end()) names.emplace_back(prototype.name);
  }
  return names;
}

std::vector<std::string> objectColours(const SceneObject& object) {
  std::vector<std::string> colours;
  const std::vector<std::string> known = colourNames();
  for (const std::string& word : nameWords(object.name)) {
    const bool isColour = std::find(known.begin(), known.end(), word) != known.end();
    if (isColour && std::find(colours.begin(), colours.end(), word) == colours.end()) colours.push_back(word);
  }
  if (const std::optional<Vector3> colour = mainColour(object); colour && colours.empty()) colours.push_back(nearestColourName(*colour));
  return colours;
}

std::string objectCategory(const SceneObject& object) {
  if (object.role == ObjectRole::kSupport) return "table";
  if (object.cavity) {
    const Vector3 room = object.cavity->sizes();
    const double opening = std::min(room.x(), room.y());
    if (room.z() < 0.25 * opening) return "tray";
    return opening >= room.z() ? "bowl" : "cup";
  }
  if (object.collisions.size() != 1) return {};
  const Geometry& geometry = object.collisions.front().geometry;
  if (const auto* box = std::get_if<Box>(&geometry)) return boxCategory(box->size);
  if (std::holds_alternative<Cylinder>(geometry)) return "cylinder";
  if (std::holds_alternative<Sphere>(geometry)) return "ball";
  return {};
}

}  // namespace lang2manip
