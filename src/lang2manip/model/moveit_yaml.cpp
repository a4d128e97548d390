#include "lang2manip/model/moveit_yaml.hpp"

#include <algorithm>
#include <cctype>

#include "lang2manip/core/rotation.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/model/geometry.hpp"
#include "lang2manip/model/xml_document.hpp"

namespace lang2manip::moveit_yaml {
namespace {

int lineOf(const YAML::Mark& mark) { return mark.is_null() ? 0 : mark.line + 1; }

/// YAML's own spellings of infinity and NaN (.inf, -.Inf, .NaN, ...).
bool isYamlSpecialFloat(const std::string& text) {
  std::string value = lowercase(text);
  if (!value.empty() && (value.front() == '+' || value.front() == '-')) value.erase(0, 1);
  return value == ".inf" || value == ".nan";
}

/// `keys.size()` numbers given as a list or as a map with one key per letter of `keys`.
std::vector<double> components(const YamlValue& value, std::string_view keys) {
  std::vector<double> result;
  if (value.isMap()) {
    for (char key : keys) result.push_back(value.child(std::string(1, key)).number());
    return result;
  }
  result = numbers(value);
  if (result.size() != keys.size()) {
    std::vector<std::string> names;
    for (char key : keys) names.emplace_back(1, key);
    value.fail("expected " + std::to_string(keys.size()) + " numbers [" + joined(names) +
               "], got " + std::to_string(result.size()));
  }
  return result;
}

Vector3 readPosition(const YamlValue& value) {
  const std::vector<double> c = components(value, "xyz");
  const Vector3 position(c[0], c[1], c[2]);
  const std::string problem = positionRangeProblem(position);
  if (!problem.empty()) value.fail("position " + problem);
  return position;
}

Quaternion readOrientation(const YamlValue& value) {
  const std::vector<double> c = components(value, "xyzw");
  const std::optional<Quaternion> q = unitQuaternion(c[3], c[0], c[1], c[2]);
  if (!q) value.fail("the quaternion [x, y, z, w] has zero length");
  return *q;
}

YAML::Node loadYaml(const std::filesystem::path& file, const std::string& name) {
  const std::string text = readTextFile(file, "YAML file");
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& error) {
    throw InputError(SourceLocation{name, lineOf(error.mark)}, "malformed YAML: " + error.msg);
  }
}

}  // namespace

YamlValue::YamlValue(YAML::Node node, std::string path, const std::string& file)
    : node_(std::move(node)), mark_(node_.Mark()), path_(std::move(path)), file_(&file) {}

YamlValue::YamlValue(YAML::Node node, std::string path, const std::string& file, const YAML::Mark& mark)
    : node_(std::move(node)), mark_(mark), path_(std::move(path)), file_(&file) {}

SourceLocation YamlValue::where() const { return {*file_, lineOf(mark_)}; }

void YamlValue::fail(const std::string& problem) const {
  throw InputError(where(), path_.empty() ? problem : path_ + ": " + problem);
}

std::optional<YamlValue> YamlValue::find(const std::string& key) const {
  if (!node_.IsMap()) fail("expected a map, got " + kindName());
  const YAML::Node value = node_[key];
  if (!value || value.IsNull()) return std::nullopt;
  return YamlValue(value, path_.empty() ? key : path_ + "." + key, *file_);
}

YamlValue YamlValue::child(const std::string& key) const {
  std::optional<YamlValue> value = find(key);
  if (!value) fail("missing required key '" + key + "'");
  return *value;
}

std::vector<YamlValue> YamlValue::items() const {
  if (!node_.IsSequence()) fail("expected a list, got " + kindName());
  std::vector<YamlValue> result;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    result.emplace_back(node_[i], path_ + "[" + std::to_string(i) + "]", *file_);
  }
  return result;
}

std::vector<std::pair<YamlValue, YamlValue>> YamlValue::entries() const {
  if (!node_.IsMap()) fail("expected a map, got " + kindName());
  std::vector<std::pair<YamlValue, YamlValue>> result;
  for (const auto& entry : node_) {
    if (!entry.first.IsScalar()) {
      const YamlValue key(entry.first, path_, *file_);
      key.fail("expected a name as a key, got " + key.kindName());
    }
    const std::string path = path_.empty() ? entry.first.Scalar() : path_ + "." + entry.first.Scalar();
    const YAML::Mark mark = entry.second.IsNull() ? entry.first.Mark() : entry.second.Mark();
    result.emplace_back(YamlValue(entry.first, path, *file_), YamlValue(entry.second, path, *file_, mark));
  }
  return result;
}

std::string YamlValue::text(const std::string& what) const {
  if (!node_.IsScalar()) fail("expected " + what + ", got " + kindName());
  return node_.Scalar();
}

double YamlValue::number() const {
  const std::string value = text("a number");
  if (isYamlSpecialFloat(value)) fail("must be a finite number, got " + value);
  return parseFiniteNumber(value, path_, where());
}

bool YamlValue::flag() const {
  bool value = false;
  if (!node_.IsScalar() || !YAML::convert<bool>::decode(node_, value)) {
    fail("expected true or false, got " + kindName());
  }
  return value;
}

std::string YamlValue::kindName() const {
  if (node_.IsMap()) return "a map";
  if (node_.IsSequence()) return "a list";
  if (node_.IsScalar()) return "\"" + node_.Scalar() + "\"";
  return "nothing";
}

std::string joined(const std::vector<std::string>& names) {
  std::string result;
  for (const std::string& name : names) result += (result.empty() ? "" : ", ") + name;
  return result;
}

std::vector<double> numbers(const YamlValue& list) {
  std::vector<double> result;
  for (const YamlValue& item : list.items()) result.push_back(item.number());
  return result;
}

std::vector<std::string> texts(const YamlValue& list, const std::string& what) {
  std::vector<std::string> result;
  for (const YamlValue& item : list.items()) result.push_back(item.text(what));
  return result;
}

std::string optionalText(const YamlValue& map, const std::string& key) {
  const std::optional<YamlValue> value = map.find(key);
  return value ? value->text("text") : std::string();
}

void rejectNonEmpty(const YamlValue& map, const std::string& key, const std::string& problem) {
  const std::optional<YamlValue> value = map.find(key);
  if (value && !value->items().empty()) value->fail(problem);
}

Pose readPose(const YamlValue& value, const std::string& positionKey,
              const std::string& orientationKey) {
  return makePose(readPosition(value.child(positionKey)),
                  readOrientation(value.child(orientationKey)));
}

std::optional<Pose> readBasePose(const YamlValue& robotState) {
  const std::optional<YamlValue> state = robotState.find("multi_dof_joint_state");
  const std::optional<YamlValue> names = state ? state->find("joint_names") : std::nullopt;
  if (!names) return std::nullopt;
  const std::vector<std::string> joints = texts(*names, "a joint name");
  const YamlValue transformList = state->child("transforms");
  const std::vector<YamlValue> transforms = transformList.items();
  if (transforms.size() != joints.size()) {
    transformList.fail("expected " + std::to_string(joints.size()) +
                       " transforms (one per joint name), got " +
                       std::to_string(transforms.size()));
  }
  if (joints.empty()) return std::nullopt;
  const auto named = std::find(joints.begin(), joints.end(), "virtual_joint");
  if (named == joints.end() && joints.size() > 1) {
    names->fail("cannot tell which multi-DOF joint is the robot's base (none is virtual_joint)");
  }
  const auto index = static_cast<std::size_t>(named == joints.end() ? 0 : named - joints.begin());
  return readPose(transforms[index], "translation", "rotation");
}

void readYamlFile(const std::filesystem::path& file,
                  const std::function<void(const YamlValue&)>& read) {
  const std::string name = file.string();
  try {
    const YamlValue root(loadYaml(file, name), "", name);
    if (!root.isMap()) root.fail("expected a map at the top level");
    read(root);
  } catch (const YAML::Exception& error) {
    throw InputError(SourceLocation{name, lineOf(error.mark)}, "YAML: " + error.msg);
  }
}

}  // namespace lang2manip::moveit_yaml
