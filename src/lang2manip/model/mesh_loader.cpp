#include "lang2manip/model/mesh_loader.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/file_checks.hpp"
#include "lang2manip/model/assimp_mesh_reader.hpp"
#include "lang2manip/model/coin_mesh_reader.hpp"
#include "lang2manip/model/collada_mesh_reader.hpp"
#include "lang2manip/model/mesh_builder.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kAssimpExtensions = {".stl", ".obj", ".ply"};
const std::vector<std::string> kCoinExtensions = {".iv", ".wrl", ".vrml"};

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : separator) + item;
  return text;
}

void checkReadableFile(const fs::path& path, const std::string& name) {
  const std::string reason = notRegularFileReason(path);
  if (!reason.empty()) throw InputError(SourceLocation{name, 0}, "mesh file " + reason);
  std::error_code error;
  const std::uintmax_t bytes = fs::file_size(path, error);
  if (!error && bytes > kMaxMeshFileBytes) {
    throw InputError(SourceLocation{name, 0}, "mesh file is " + std::to_string(bytes >> 20) + " MiB (at most " +
                                                  std::to_string(kMaxMeshFileBytes >> 20) + " MiB: give a simplified mesh)");
  }
  if (!std::ifstream(path, std::ios::binary).is_open()) {
    throw InputError(SourceLocation{name, 0}, "mesh file cannot be opened for reading");
  }
}

}  // namespace

const std::vector<std::string>& supportedMeshExtensions() {
  static const std::vector<std::string> extensions = [] {
    std::vector<std::string> all = {".stl", ".dae", ".obj", ".ply"};
    all.insert(all.end(), kCoinExtensions.begin(), kCoinExtensions.end());
    return all;
  }();
  return extensions;
}

TriangleMesh loadTriangleMesh(const std::string& path) {
  if (path.empty()) throw InputError("mesh path is empty");
  const fs::path file(path);
  const std::string extension = lowerCaseExtension(file);
  if (!contains(supportedMeshExtensions(), extension)) {
    throw InputError(SourceLocation{path, 0},
                     "unsupported mesh format \"" + extension + "\" (supported: " +
                         joined(supportedMeshExtensions(), ", ") + ")");
  }
  checkReadableFile(file, path);
  if (extension == ".dae") return readColladaMesh(file);
  return contains(kCoinExtensions, extension) ? readMeshWithCoin(file) : readMeshWithAssimp(file);
}

std::shared_ptr<const TriangleMesh> MeshCache::get(const std::string& path) {
  std::error_code error;
  const std::string key = fs::weakly_canonical(fs::path(path), error).string();
  if (error) throw InputError(SourceLocation{path, 0}, "bad mesh path: " + error.message());
  // Loading under the lock reads each file exactly once even when threads ask for it together.
  const std::lock_guard lock(mutex_);
  if (const auto found = meshes_.find(key); found != meshes_.end()) return found->second;
  auto mesh = std::make_shared<const TriangleMesh>(loadTriangleMesh(path));
  meshes_.emplace(key, mesh);
  return mesh;
}

std::size_t MeshCache::size() const {
  const std::lock_guard lock(mutex_);
  return meshes_.size();
}

MeshCache& MeshCache::global() {
  static MeshCache cache;
  return cache;
}

}  // namespace lang2manip
