#pragma once
/// @file What the HTTP API's handlers see and answer, free of the HTTP library: a request's path
/// parameters, query and JSON body; a response's status, type and body; and ApiError, which a
/// handler throws to answer 4xx/5xx with a JSON body naming what was wrong.

#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "lang2manip/core/stop_condition.hpp"
#include "lang2manip/core/types.hpp"

namespace lang2manip {

/// A request the handler must refuse: HTTP `status` (4xx or 5xx) with {"error": {"status",
/// "code", "message"}} as body.
class ApiError : public std::runtime_error {
 public:
  ApiError(int status, std::string code, const std::string& message)
      : std::runtime_error(message), status_(status), code_(std::move(code)) {}

  [[nodiscard]] int status() const noexcept { return status_; }
  /// Machine-readable: "bad_request", "not_found", "unauthorized", "too_many", ...
  [[nodiscard]] const std::string& code() const noexcept { return code_; }

 private:
  int status_;
  std::string code_;
};

/// The error body of the API: {"error": {"status": 404, "code": "not_found", "message": "..."}}.
nlohmann::json apiErrorBody(int status, const std::string& code, const std::string& message);

struct ApiRequest {
  /// The values of the route's {parameters}, in order.
  std::vector<std::string> pathParameters;
  std::map<std::string, std::string> query;
  /// The parsed body (an object; empty object when there was no body).
  nlohmann::json body = nlohmann::json::object();
  /// Fires when the request's client leaves, the server stops or the request's time is up
  /// (ServerOptions::maxRequestSeconds): long work passes it on.
  StopCondition stop;
};

struct ApiResponse {
  int status = 200;
  std::string contentType = "application/json";
  std::string body;

  /// A JSON response.
  static ApiResponse json(const nlohmann::json& value, int status = 200);
};

using ApiHandler = std::function<ApiResponse(const ApiRequest&)>;

/// One endpoint: the method ("GET", "POST", "DELETE") and the path as OpenAPI writes it
/// ("/api/sessions/{client}/solve"), documented in openapi.json.
struct ApiRoute {
  ApiRoute(std::string routeMethod, std::string routePath, ApiHandler routeHandler, std::vector<std::string> acceptedFields = {})
      : method(std::move(routeMethod)), path(std::move(routePath)), handler(std::move(routeHandler)), bodyFields(std::move(acceptedFields)) {}

  std::string method;
  std::string path;
  ApiHandler handler;
  /// The body fields it accepts; the server refuses any other with 400 before the handler runs
  /// (the OpenAPI document's test compares them with the documented request bodies).
  std::vector<std::string> bodyFields;
};

/// Body fields, checked: each throws ApiError 400 naming the field and what was expected.
namespace body {
/// A required string field.
std::string string(const nlohmann::json& body, const std::string& field);
/// An optional string field (`fallback` when absent or null).
std::string string(const nlohmann::json& body, const std::string& field, const std::string& fallback);
/// An optional finite number (`fallback` when absent or null).
double number(const nlohmann::json& body, const std::string& field, double fallback);
/// An optional integer within [low, high].
long integer(const nlohmann::json& body, const std::string& field, long fallback, long low, long high);
/// An optional boolean (`fallback` when absent or null).
bool boolean(const nlohmann::json& body, const std::string& field, bool fallback);
/// A required array of finite numbers.
std::vector<double> numbers(const nlohmann::json& body, const std::string& field);
/// A required pose: {"position": [x,y,z], "orientation_wxyz": [w,x,y,z]} (orientation optional,
/// normalised) or {"kautham": [x, y, z, ax, ay, az, angle]}.
Pose pose(const nlohmann::json& body, const std::string& field);
/// Fails unless every field of `body` is one of `known` (typos are errors, not ignored).
void onlyFields(const nlohmann::json& body, const std::vector<std::string>& known);
}  // namespace body

/// Throws ApiError 400 unless `client` is 1 to 64 characters of [A-Za-z0-9_.-].
void checkClientId(const std::string& client);

/// {"position": [x, y, z], "orientation_wxyz": [w, x, y, z]}.
nlohmann::json poseToJson(const Pose& pose);

}  // namespace lang2manip
