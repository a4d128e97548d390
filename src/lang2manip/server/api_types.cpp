#include "lang2manip/server/api_types.hpp"

#include <algorithm>
#include <cmath>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/json_limits.hpp"
#include "lang2manip/core/rotation.hpp"

namespace lang2manip {

using nlohmann::json;

json apiErrorBody(int status, const std::string& code, const std::string& message) {
  return {{"error", {{"status", status}, {"code", code}, {"message", message}}}};
}

ApiResponse ApiResponse::json(const nlohmann::json& value, int status) {
  // Replacing invalid UTF-8 (from file names or model text) keeps every answer valid JSON.
  return {status, "application/json", value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)};
}

namespace body {
namespace {

[[noreturn]] void refuse(const std::string& field, const std::string& expected, const json* value) {
  std::string message = "body field \"" + field + "\": expected " + expected;
  message += value == nullptr ? ", but it is missing" : ", got " + boundedJsonDump(*value);
  throw ApiError(400, "bad_request", message);
}

const json* find(const json& body, const std::string& field) {
  const auto found = body.find(field);
  return found == body.end() || found->is_null() ? nullptr : &*found;
}

std::vector<double> finiteNumbers(const json& value, const std::string& field) {
  if (!value.is_array()) refuse(field, "an array of numbers", &value);
  std::vector<double> numbers;
  for (const json& item : value) {
    if (!item.is_number() || !std::isfinite(item.get<double>())) refuse(field, "an array of finite numbers", &value);
    numbers.push_back(item.get<double>());
  }
  return numbers;
}

Pose quaternionPose(const json& value, const std::string& field) {
  const std::vector<double> position = finiteNumbers(value.at("position"), field + ".position");
  if (position.size() != 3) refuse(field + ".position", "3 numbers (x, y, z)", &value.at("position"));
  Quaternion orientation = Quaternion::Identity();
  if (const json* wxyz = find(value, "orientation_wxyz")) {
    const std::vector<double> q = finiteNumbers(*wxyz, field + ".orientation_wxyz");
    if (q.size() != 4) refuse(field + ".orientation_wxyz", "4 numbers (w, x, y, z)", wxyz);
    const std::optional<Quaternion> unit = unitQuaternion(q[0], q[1], q[2], q[3]);
    if (!unit) refuse(field + ".orientation_wxyz", "a non-zero quaternion", wxyz);
    orientation = *unit;
  }
  return makePose(Vector3(position[0], position[1], position[2]), orientation);
}

}  // namespace

std::string string(const json& body, const std::string& field) {
  const json* value = find(body, field);
  if (value == nullptr || !value->is_string()) refuse(field, "a string", value);
  return value->get<std::string>();
}

std::string string(const json& body, const std::string& field, const std::string& fallback) {
  return find(body, field) == nullptr ? fallback : string(body, field);
}

double number(const json& body, const std::string& field, double fallback) {
  const json* value = find(body, field);
  if (value == nullptr) return fallback;
  if (!value->is_number() || !std::isfinite(value->get<double>())) refuse(field, "a finite number", value);
  return value->get<double>();
}

long integer(const json& body, const std::string& field, long fallback, long low, long high) {
  const json* value = find(body, field);
  if (value == nullptr) return fallback;
  const std::string expected = "an integer from " + std::to_string(low) + " to " + std::to_string(high);
  if (!value->is_number_integer()) refuse(field, expected, value);
  const long number = value->is_number_unsigned() && value->get<unsigned long long>() > static_cast<unsigned long long>(high)
                          ? high + 1
                          : value->get<long>();
  if (number < low || number > high) refuse(field, expected, value);
  return number;
}

bool boolean(const json& body, const std::string& field, bool fallback) {
  const json* value = find(body, field);
  if (value == nullptr) return fallback;
  if (!value->is_boolean()) refuse(field, "true or false", value);
  return value->get<bool>();
}

std::vector<double> numbers(const json& body, const std::string& field) {
  const json* value = find(body, field);
  if (value == nullptr) refuse(field, "an array of numbers", nullptr);
  return finiteNumbers(*value, field);
}

Pose pose(const json& body, const std::string& field) {
  const json* value = find(body, field);
  const std::string expected = R"({"position": [x, y, z], "orientation_wxyz": [w, x, y, z]} or {"kautham": [x, y, z, ax, ay, az, angle]})";
  if (value == nullptr || !value->is_object()) refuse(field, expected, value);
  if (value->contains("kautham")) {
    try {
      return kauthamPose(finiteNumbers(value->at("kautham"), field + ".kautham"));
    } catch (const InputError& error) {
      throw ApiError(400, "bad_request", "body field \"" + field + ".kautham\": " + error.what());
    }
  }
  if (!value->contains("position")) refuse(field, expected, value);
  return quaternionPose(*value, field);
}

void onlyFields(const json& body, const std::vector<std::string>& known) {
  for (const auto& [key, value] : body.items()) {
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    std::string list;
    for (const std::string& name : known) list += (list.empty() ? "" : ", ") + name;
    throw ApiError(400, "bad_request", "body field \"" + key + "\" is not known here (known: " + (list.empty() ? "none" : list) + ")");
  }
}

}  // namespace body

void checkClientId(const std::string& client) {
  const bool valid = !client.empty() && client.size() <= 64 &&
                     client.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.-") == std::string::npos;
  if (!valid) throw ApiError(400, "bad_request", "client id \"" + client.substr(0, 80) + "\": 1 to 64 characters of A-Z a-z 0-9 _ . -");
}

json poseToJson(const Pose& pose) {
  const Quaternion q(pose.linear());
  return {{"position", {pose.translation().x(), pose.translation().y(), pose.translation().z()}},
          {"orientation_wxyz", {q.w(), q.x(), q.y(), q.z()}}};
}

}  // namespace lang2manip
