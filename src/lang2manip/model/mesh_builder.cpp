#include "lang2manip/model/mesh_builder.hpp"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>
#include <utility>

#include "lang2manip/core/error.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Collecting triangles

// Plain arithmetic: this runs per triangle, and unoptimised Eigen makes debug builds crawl.
bool hasArea(const double* a, const double* b, const double* c) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  return u[1] * v[2] != u[2] * v[1] || u[2] * v[0] != u[0] * v[2] || u[0] * v[1] != u[1] * v[0];
}

// ---------------------------------------------------------------------------------------------
// Nesting guard

std::size_t skipPast(const std::string& text, std::size_t from, const char* end) {
  const std::size_t found = text.find(end, from);
  return found == std::string::npos ? text.size() : found + std::strlen(end);
}

/// Deepest nesting of { } and [ ] in Inventor or VRML text, comments and strings skipped.
int braceDepth(const std::string& text) {
  int depth = 0;
  int deepest = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '#') {
      i = skipPast(text, i, "\n") - 1;
    } else if (c == '"') {
      while (++i < text.size() && text[i] != '"') i += text[i] == '\\' ? 1 : 0;
    } else if (c == '{' || c == '[') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == '}' || c == ']') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

std::string fileContents(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream contents;
  contents << stream.rdbuf();
  return std::move(contents).str();
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// MeshBuilder

int MeshBuilder::addVertex(const Vector3& point) {
  if (!point.allFinite()) {
    nonFinite_ = true;
    return kInvalid;
  }
  if (mesh_.vertices.size() >= static_cast<std::size_t>(INT_MAX)) {
    tooLarge_ = true;
    return kInvalid;
  }
  mesh_.vertices.push_back(point);
  return static_cast<int>(mesh_.vertices.size() - 1);
}

int MeshBuilder::mergedVertex(const Vector3& point) {
  const std::array<double, 3> key = {point.x(), point.y(), point.z()};
  if (const auto found = merged_.find(key); found != merged_.end()) return found->second;
  const int index = addVertex(point);
  if (index != kInvalid) merged_.emplace(key, index);
  return index;
}

void MeshBuilder::addTriangle(int a, int b, int c) {
  if (a == kInvalid || b == kInvalid || c == kInvalid || a == b || b == c || a == c) return;
  if (!hasArea(mesh_.vertices[a].data(), mesh_.vertices[b].data(), mesh_.vertices[c].data())) {
    return;
  }
  if (mesh_.triangles.size() >= kMaxMeshTriangles) {
    tooManyTriangles_ = true;
    return;
  }
  mesh_.triangles.push_back({a, b, c});
  int paletteEntry = -1;
  if (colour_ && colour_->allFinite()) {
    const Vector3 rgb = colour_->cwiseMax(0.0).cwiseMin(1.0);
    const std::array<double, 3> key{std::round(rgb.x() * 255.0), std::round(rgb.y() * 255.0), std::round(rgb.z() * 255.0)};
    const Vector3& p = mesh_.vertices[static_cast<std::size_t>(a)];
    colourAreas_[key] += 0.5 * (mesh_.vertices[static_cast<std::size_t>(b)] - p).cross(mesh_.vertices[static_cast<std::size_t>(c)] - p).norm();
    const auto [entry, added] = paletteIndex_.try_emplace(key, static_cast<int>(mesh_.palette.size()));
    if (added) mesh_.palette.push_back(Vector3(key[0], key[1], key[2]) / 255.0);
    paletteEntry = entry->second;
  }
  mesh_.triangleColours.push_back(paletteEntry);
}

std::string MeshBuilder::problem() const {
  if (nonFinite_) return "has a vertex with a non-finite coordinate (nan or inf)";
  if (tooLarge_) return "has too many vertices";
  if (tooManyTriangles_) {
    return "has more than " + std::to_string(kMaxMeshTriangles) + " triangles (give a simplified mesh: collision checking and drawing need far fewer)";
  }
  if (mesh_.triangles.empty()) return "contains no triangles";
  return {};
}

TriangleMesh MeshBuilder::take(std::string source) {
  mesh_.source = std::move(source);
  double largest = -1.0;
  std::array<double, 3> best{};
  for (const auto& [key, area] : colourAreas_) {
    if (area > largest || (area == largest && key < best)) largest = area, best = key;  // ties: the smaller key, whatever the map's order
  }
  if (largest >= 0.0) mesh_.colour = Vector3(best[0], best[1], best[2]) / 255.0;
  if (mesh_.palette.empty()) mesh_.triangleColours.clear();
  return std::move(mesh_);
}

TriangleMesh MeshBuilder::finish(const fs::path& path) {
  if (const std::string what = problem(); !what.empty()) {
    throw InputError(SourceLocation{path.string(), 0}, "mesh " + what);
  }
  return take(fs::absolute(path).lexically_normal().string());
}

std::size_t MeshBuilder::KeyHash::operator()(const std::array<double, 3>& key) const noexcept {
  std::size_t seed = 0;
  for (double value : key) {
    seed ^= std::hash<double>{}(value) + 0x9e3779b97f4a7c15ULL + (seed << 6) + (seed >> 2);
  }
  return seed;
}

// ---------------------------------------------------------------------------------------------
// Shared helpers

void checkBraceNestingDepth(const fs::path& path) {
  const std::string text = fileContents(path);
  if (text.substr(0, text.find('\n')).find("binary") != std::string::npos) return;
  if (braceDepth(text) > kMaxMeshNestingDepth) {
    throw InputError(SourceLocation{path.string(), 0},
                     "nesting deeper than " + std::to_string(kMaxMeshNestingDepth) +
                         " levels: refused to protect the stack");
  }
}

std::string lowerCaseExtension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace lang2manip
