#pragma once
/// @file Internal to the MoveIt YAML readers (scenes and requests, joint_limits.yaml; not part of
/// the public API): yaml-cpp nodes that know their file and YAML path, so every error says
/// "file:line: path: problem".

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/types.hpp"

namespace lang2manip::moveit_yaml {

/// A YAML node with the file and the path (e.g. `world.collision_objects[3].id`) that lead to
/// it. Every accessor checks the node's type and throws InputError at the node's line.
class YamlValue {
 public:
  /// `file` must outlive the value (it names the file in messages).
  YamlValue(YAML::Node node, std::string path, const std::string& file);

  /// The file and 1-based line of the node (0 when yaml-cpp does not know it).
  [[nodiscard]] SourceLocation where() const;
  /// Throws InputError "file:line: path: problem".
  [[noreturn]] void fail(const std::string& problem) const;

  [[nodiscard]] bool isMap() const { return node_.IsMap(); }
  /// The value of `key` of a map, or nullopt when the key is absent or null.
  [[nodiscard]] std::optional<YamlValue> find(const std::string& key) const;
  /// The value of `key` of a map; fails when it is absent or null.
  [[nodiscard]] YamlValue child(const std::string& key) const;
  /// The items of a list.
  [[nodiscard]] std::vector<YamlValue> items() const;
  /// The entries of a map in file order: each key (a scalar, at its own line) and its value (a
  /// null value included, placed at its key's line), both with the path of the entry. Fails
  /// unless the keys are scalars.
  [[nodiscard]] std::vector<std::pair<YamlValue, YamlValue>> entries() const;
  /// The node's YAML tag: "!degrees" for `!degrees 90`, "?" for a plain scalar, "!" for a
  /// quoted one.
  [[nodiscard]] const std::string& tag() const { return node_.Tag(); }
  /// The YAML path that leads to the node ("" at the top level).
  [[nodiscard]] const std::string& path() const { return path_; }
  /// A scalar as text (`what` names what was expected in the message).
  [[nodiscard]] std::string text(const std::string& what) const;
  /// A finite number (YAML's .nan and .inf are rejected).
  [[nodiscard]] double number() const;
  /// A boolean.
  [[nodiscard]] bool flag() const;

 private:
  /// A value at `mark` (a null value has no place of its own: its key's is used).
  YamlValue(YAML::Node node, std::string path, const std::string& file, const YAML::Mark& mark);
  [[nodiscard]] std::string kindName() const;

  YAML::Node node_;
  YAML::Mark mark_;
  std::string path_;
  const std::string* file_;
};

/// "a, b, c".
std::string joined(const std::vector<std::string>& names);

/// The numbers of a list.
std::vector<double> numbers(const YamlValue& list);
/// The scalars of a list.
std::vector<std::string> texts(const YamlValue& list, const std::string& what);
/// The text of `key`, or "" when absent.
std::string optionalText(const YamlValue& map, const std::string& key);
/// Fails with `problem` unless `key` is absent or an empty list.
void rejectNonEmpty(const YamlValue& map, const std::string& key, const std::string& problem);

/// A pose from `positionKey` ([x, y, z] or {x, y, z}) and `orientationKey` ([x, y, z, w] or
/// {x, y, z, w}, normalized; a zero quaternion fails).
Pose readPose(const YamlValue& value, const std::string& positionKey,
              const std::string& orientationKey);

/// The base pose in a RobotState's multi_dof_joint_state: the transform of "virtual_joint", or
/// of the only multi-DOF joint; nullopt when there is none.
std::optional<Pose> readBasePose(const YamlValue& robotState);

/// Loads `file` and calls `read` with its top-level map. Throws InputError naming the file (and
/// line) when it cannot be opened or parsed, is not a map, or yaml-cpp throws while reading.
void readYamlFile(const std::filesystem::path& file,
                  const std::function<void(const YamlValue&)>& read);

}  // namespace lang2manip::moveit_yaml
