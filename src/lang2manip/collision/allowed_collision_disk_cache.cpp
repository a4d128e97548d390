#include "lang2manip/collision/allowed_collision_disk_cache.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <system_error>
#include <type_traits>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/core/output_files.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;

constexpr const char* kFileHeader = "lang2manip allowed-collision matrix 1";

/// Two independent 64-bit multiply-xor lanes over 64-bit words: a 128-bit digest, which no two
/// robots met in practice share by chance.
class Digest {
 public:
  void add(std::uint64_t word) {
    first_ = (first_ ^ word) * 0x100000001b3ULL;
    second_ = ((second_ ^ word) * 0x9e3779b97f4a7c15ULL) ^ (second_ >> 29);
  }
  void add(int value) { add(static_cast<std::uint64_t>(static_cast<std::int64_t>(value))); }
  void add(bool value) { add(static_cast<std::uint64_t>(value ? 1 : 0)); }
  void add(double value) {
    std::uint64_t word = 0;
    std::memcpy(&word, &value, sizeof word);
    add(word);
  }
  void add(const std::string& text) {
    add(static_cast<std::uint64_t>(text.size()));
    for (std::size_t i = 0; i < text.size(); i += 8) {
      std::uint64_t word = 0;
      std::memcpy(&word, text.data() + i, std::min<std::size_t>(8, text.size() - i));
      add(word);
    }
  }
  void add(const Vector3& v) {
    add(v.x());
    add(v.y());
    add(v.z());
  }
  void add(const Pose& X) {
    for (int i = 0; i < 16; ++i) add(X.matrix().data()[i]);
  }

  [[nodiscard]] std::string hex() const {
    char text[33];
    std::snprintf(text, sizeof text, "%016llx%016llx", static_cast<unsigned long long>(first_),
                  static_cast<unsigned long long>(second_));
    return text;
  }

 private:
  std::uint64_t first_ = 0xcbf29ce484222325ULL;
  std::uint64_t second_ = 0x84222325cbf29ce4ULL;
};

void addGeometry(Digest& digest, const Geometry& geometry) {
  digest.add(static_cast<int>(geometry.index()));
  std::visit(
      [&](const auto& shape) {
        using T = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<T, Box>) {
          digest.add(shape.size);
        } else if constexpr (std::is_same_v<T, Sphere>) {
          digest.add(shape.radius);
        } else if constexpr (std::is_same_v<T, Cylinder>) {
          digest.add(shape.radius);
          digest.add(shape.length);
        } else {
          digest.add(shape.scale);
          if (!shape.mesh) return;
          digest.add(static_cast<int>(shape.mesh->vertices.size()));
          for (const Vector3& vertex : shape.mesh->vertices) digest.add(vertex);
          for (const auto& triangle : shape.mesh->triangles) {
            for (const int index : triangle) digest.add(index);
          }
        }
      },
      geometry);
}

void addJoint(Digest& digest, const Joint& joint) {
  digest.add(joint.name);
  digest.add(static_cast<int>(joint.type));
  digest.add(joint.parentLink);
  digest.add(joint.childLink);
  digest.add(joint.origin);
  digest.add(joint.axis);
  digest.add(joint.limits.lower);
  digest.add(joint.limits.upper);
  digest.add(joint.mimic.has_value());
  if (joint.mimic) {
    digest.add(joint.mimic->sourceJoint);
    digest.add(joint.mimic->multiplier);
    digest.add(joint.mimic->offset);
  }
}

fs::path fileFor(const fs::path& directory, const std::string& key) { return directory / ("acm-" + key + ".txt"); }

/// The reasons of rows `links` lines of `links` digits, or false when they are not that.
bool readReasons(std::istream& in, int links, AllowedCollisionMatrix& matrix) {
  std::string row;
  for (int a = 0; a < links; ++a) {
    if (!std::getline(in, row) || row.size() != static_cast<std::size_t>(links)) return false;
    for (int b = 0; b < links; ++b) {
      const int reason = row[static_cast<std::size_t>(b)] - '0';
      if (reason < 0 || reason > static_cast<int>(AllowedReason::kDefault)) return false;
      if ((a == b) != (reason == static_cast<int>(AllowedReason::kSameLink))) return false;
      if (b > a && reason != 0) matrix.allow(a, b, static_cast<AllowedReason>(reason));
      if (b < a && matrix.reason(a, b) != static_cast<AllowedReason>(reason)) return false;
    }
  }
  std::string rest;
  return !(in >> rest);
}

std::string matrixText(const std::string& key, const RobotModel& model, const AllowedCollisionMatrix& matrix) {
  std::ostringstream text;
  text << kFileHeader << "\nkey " << key << "\nlinks " << matrix.linkCount() << "\n";
  for (const Link& link : model.links()) text << link.name << "\n";
  for (int a = 0; a < matrix.linkCount(); ++a) {
    for (int b = 0; b < matrix.linkCount(); ++b) text << static_cast<int>(matrix.reason(a, b));
    text << "\n";
  }
  return text.str();
}

}  // namespace

std::optional<fs::path> allowedCollisionCacheDirectory() {
  const auto variable = [](const char* name) -> std::string {
    const char* value = std::getenv(name);
    return value == nullptr ? "" : value;
  };
  if (const std::string own = variable("LANG2MANIP_CACHE_DIR"); !own.empty()) {
    if (own == "off") return std::nullopt;
    return fs::path(own);
  }
  if (const std::string xdg = variable("XDG_CACHE_HOME"); !xdg.empty()) return fs::path(xdg) / "lang2manip";
  if (const std::string home = variable("HOME"); !home.empty()) return fs::path(home) / ".cache" / "lang2manip";
  return std::nullopt;
}

std::string allowedCollisionKey(const RobotModel& model, const AllowedCollisionSettings& settings) {
  Digest digest;
  digest.add(kAllowedCollisionAlgorithmVersion);
  digest.add(settings.samples);
  digest.add(static_cast<std::uint64_t>(settings.seed));
  digest.add(settings.disableNever);
  digest.add(settings.disableAlways);
  digest.add(settings.alwaysFraction);
  digest.add(settings.disableDefault);
  digest.add(static_cast<int>(model.links().size()));
  for (const Link& link : model.links()) {
    digest.add(link.name);
    digest.add(static_cast<int>(link.collisions.size()));
    for (const Shape& shape : link.collisions) {
      digest.add(shape.name);
      digest.add(shape.origin);
      addGeometry(digest, shape.geometry);
    }
  }
  digest.add(static_cast<int>(model.joints().size()));
  for (const Joint& joint : model.joints()) addJoint(digest, joint);
  for (const DisabledCollision& pair : model.semantics().disabledCollisions) {
    digest.add(pair.link1);
    digest.add(pair.link2);
  }
  digest.add(static_cast<int>(model.semantics().defaultCollisionsDisabled.size()));
  for (const std::string& link : model.semantics().defaultCollisionsDisabled) digest.add(link);
  digest.add(static_cast<int>(model.semantics().enabledCollisions.size()));
  for (const auto& [first, second] : model.semantics().enabledCollisions) {
    digest.add(first);
    digest.add(second);
  }
  return digest.hex();
}

std::optional<AllowedCollisionMatrix> readStoredAllowedCollisions(const fs::path& directory, const std::string& key,
                                                                  const RobotModel& model) {
  const fs::path file = fileFor(directory, key);
  std::error_code error;
  // Never a FIFO or device (a reader would block or read forever): a regular file of a size a
  // matrix can have.
  const std::uintmax_t links2 = model.links().size() * model.links().size();
  if (!fs::is_regular_file(fs::symlink_status(file, error)) || fs::file_size(file, error) > 4096 + 64 * links2 + 2 * links2) {
    return std::nullopt;
  }
  std::ifstream in(file);
  if (!in) return std::nullopt;
  std::string line;
  const int links = static_cast<int>(model.links().size());
  if (!std::getline(in, line) || line != kFileHeader) return std::nullopt;
  if (!std::getline(in, line) || line != "key " + key) return std::nullopt;
  if (!std::getline(in, line) || line != "links " + std::to_string(links)) return std::nullopt;
  for (const Link& link : model.links()) {
    if (!std::getline(in, line) || line != link.name) return std::nullopt;
  }
  AllowedCollisionMatrix matrix(links);
  if (!readReasons(in, links, matrix)) return std::nullopt;
  return matrix;
}

bool storeAllowedCollisions(const fs::path& directory, const std::string& key, const RobotModel& model,
                            const AllowedCollisionMatrix& matrix) {
  std::error_code error;
  fs::create_directories(directory, error);
  if (error) return false;
  try {
    writeFileAtomically(fileFor(directory, key), matrixText(key, model, matrix), "collision-matrix cache");
    return true;
  } catch (const InputError&) {
    return false;
  }
}

AllowedCollisionMatrix storedOrComputedAllowedCollisions(const RobotModel& model,
                                                         const AllowedCollisionSettings& settings,
                                                         const std::function<AllowedCollisionMatrix()>& compute,
                                                         const std::function<bool(const AllowedCollisionMatrix&)>& confirms) {
  const std::optional<fs::path> directory = allowedCollisionCacheDirectory();
  if (!directory) return compute();
  const std::string key = allowedCollisionKey(model, settings);
  if (std::optional<AllowedCollisionMatrix> stored = readStoredAllowedCollisions(*directory, key, model)) {
    if (confirms(*stored)) return std::move(*stored);
    logWarning("robot \"" + model.name() + "\": the allowed-collision matrix stored in " + fileFor(*directory, key).string() +
               " allows link pairs that collide; it is computed again and replaced");
  }
  AllowedCollisionMatrix matrix = compute();
  static std::atomic<bool> warned{false};
  if (!storeAllowedCollisions(*directory, key, model, matrix) && !warned.exchange(true)) {
    logWarning("allowed-collision matrices are not kept on disk: cannot write to " + directory->string() +
               " (set LANG2MANIP_CACHE_DIR to a writable directory, or to \"off\")");
  }
  return matrix;
}

}  // namespace lang2manip
