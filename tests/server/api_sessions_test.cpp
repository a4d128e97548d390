// The planning-session verbs over HTTP, and the OpenAPI document kept in sync with the routes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <regex>
#include <set>

#include "server/api_test_server.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;
using test::ApiTestServer;
using test::bodyOf;
using test::errorOf;
using ::testing::HasSubstr;

/// The JSON chunk of a GLB file (the chunk after the 12-byte header and the 8-byte chunk header).
json glbJsonChunk(const std::string& glb) {
  if (glb.size() < 20) return json();
  std::uint32_t length = 0;
  std::memcpy(&length, glb.data() + 12, sizeof length);
  return json::parse(glb.substr(20, length));
}

TEST(ApiOpenApi, DocumentsExactlyTheEndpointsTheServerAnswers) {
  ApiTestServer server;
  const json document = json::parse(openApiDocument());
  EXPECT_EQ(document["openapi"].get<std::string>().substr(0, 2), "3.");
  std::set<std::pair<std::string, std::string>> documented;
  for (const auto& [path, operations] : document["paths"].items()) {
    for (const auto& [method, operation] : operations.items()) {
      std::string upper = method;
      std::transform(upper.begin(), upper.end(), upper.begin(), ::toupper);
      documented.emplace(upper, path);
      EXPECT_TRUE(operation.contains("responses")) << method << " " << path;
    }
  }
  std::set<std::pair<std::string, std::string>> served;
  for (const ApiEndpoint& endpoint : server.server().endpoints()) served.emplace(endpoint.method, endpoint.path);
  EXPECT_EQ(documented, served);
  const auto answer = server.get("/api/openapi.json");
  ASSERT_TRUE(answer);
  EXPECT_EQ(bodyOf(answer), document);
}

/// The schema of an operation's JSON request body ($ref resolved); null when it has none.
json requestSchema(const json& document, const json& operation) {
  if (!operation.contains("requestBody")) return nullptr;
  json schema = operation["requestBody"]["content"]["application/json"]["schema"];
  if (schema.contains("$ref")) {
    const std::string reference = schema["$ref"];
    schema = document["components"]["schemas"][reference.substr(reference.rfind('/') + 1)];
  }
  return schema;
}

TEST(ApiOpenApi, DocumentsTheBodyFieldsEachEndpointAccepts) {
  ApiTestServer server;
  const json document = json::parse(openApiDocument());
  for (const ApiEndpoint& endpoint : server.server().endpoints()) {
    std::string method = endpoint.method;
    std::transform(method.begin(), method.end(), method.begin(), ::tolower);
    const json& operation = document["paths"][endpoint.path][method];
    const std::string name = endpoint.method + " " + endpoint.path;
    const json schema = requestSchema(document, operation);
    std::set<std::string> documented;
    if (!schema.is_null()) {
      const json properties = schema.value("properties", json::object());
      for (const auto& [field, value] : properties.items()) documented.insert(field);
      EXPECT_EQ(schema.value("additionalProperties", true), false) << name << ": unknown fields are refused";
      // A body is required exactly when some field is.
      EXPECT_EQ(operation["requestBody"].value("required", false), !schema.value("required", json::array()).empty()) << name;
      for (const json& field : schema.value("required", json::array())) EXPECT_TRUE(documented.count(field.get<std::string>())) << name << " " << field;
    }
    const std::set<std::string> accepted(endpoint.bodyFields.begin(), endpoint.bodyFields.end());
    EXPECT_EQ(documented, accepted) << name;
    // And the server does refuse what is not accepted.
    if (endpoint.method == "POST") {
      const auto refused = server.postJson(std::regex_replace(endpoint.path, std::regex("\\{[a-z]+\\}"), "x"), {{"no_such_field", 1}});
      EXPECT_EQ(refused->status, 400) << name << ": " << refused->body;
      EXPECT_THAT(errorOf(refused), HasSubstr("\"no_such_field\" is not known here")) << name;
    }
  }
}

TEST(ApiSessions, OpenSolveGetPathCheckAndEditTheWorld) {
  ApiTestServer server;
  const std::string base = "/api/sessions/alice";
  const auto opened = server.postJson(base + "/openProblem", {{"problem", "panda_desk"}});
  ASSERT_TRUE(opened);
  ASSERT_EQ(opened->status, 200) << opened->body;
  EXPECT_EQ(bodyOf(opened)["queries"], 1);

  const json state = bodyOf(server.get(base));
  EXPECT_TRUE(state["open"].get<bool>());
  EXPECT_FALSE(state["has_path"].get<bool>());
  ASSERT_TRUE(state["query"]["init"].is_array());
  const json init = state["query"]["init"];

  const auto planner = server.postJson(base + "/setPlanner", {{"name", "RRTConnect"}, {"parameters", {{"range", 0.5}}}});
  ASSERT_EQ(planner->status, 200) << planner->body;
  const double sessionTime = bodyOf(server.get(base))["planner"]["max_planning_time"];
  const auto solved = server.postJson(base + "/solve", {{"time_limit", 5}});
  ASSERT_EQ(solved->status, 200) << solved->body;
  EXPECT_TRUE(bodyOf(solved)["solved"].get<bool>()) << solved->body;
  EXPECT_NE(sessionTime, 5.0);
  EXPECT_EQ(bodyOf(server.get(base))["planner"]["max_planning_time"], sessionTime) << "time_limit is for that solve only";

  const json path = bodyOf(server.get(base + "/getPath"));
  ASSERT_GE(path["path"].size(), 2U);
  EXPECT_EQ(path["path"][0].size(), path["dof_names"].size());
  EXPECT_GT(path["duration"].get<double>(), 0.0);
  const json solvedScene = glbJsonChunk(server.get(base + "/scene.glb")->body);
  ASSERT_EQ(solvedScene["animations"].size(), 1U) << "the solved path is animated in the session's scene";
  EXPECT_EQ(solvedScene["animations"][0]["name"], "trajectory");

  const json collision = bodyOf(server.postJson(base + "/checkCollision", {{"controls", init}}));
  EXPECT_TRUE(collision["valid"].get<bool>()) << collision.dump();

  const std::string obstacle = bodyOf(server.get(base))["obstacles"][0];
  const json moved{{"position", {0.1, 0.2, 0.3}}, {"orientation_wxyz", {1, 0, 0, 0}}};
  ASSERT_EQ(server.postJson(base + "/setObstaclePos", {{"obstacle", obstacle}, {"pose", moved}})->status, 200);
  const json pose = bodyOf(server.get(base + "/getObstaclePos?obstacle=" + obstacle));
  EXPECT_NEAR(pose["position"][1].get<double>(), 0.2, 1e-12);
  EXPECT_FALSE(bodyOf(server.get(base))["has_path"].get<bool>()) << "a changed world invalidates the path";

  const auto glb = server.get(base + "/scene.glb");
  ASSERT_EQ(glb->status, 200);
  EXPECT_EQ(glb->body.substr(0, 4), "glTF");
  EXPECT_EQ(glb->get_header_value("Content-Type"), "model/gltf-binary");
  EXPECT_FALSE(glbJsonChunk(glb->body).contains("animations")) << "no path, no motion";

  ASSERT_EQ(server.del(base)->status, 200);
  EXPECT_EQ(server.get(base)->status, 404);
}

TEST(ApiSessions, TheServersOwnProblemIsServedAsGlbForTheViewersLandingPage) {
  ServerOptions options;
  options.token = "landing-token";
  ApiTestServer server(options);
  EXPECT_EQ(server.get("/api/scene.glb")->status, 401);
  server.setToken("landing-token");
  const auto glb = server.get("/api/scene.glb");
  ASSERT_EQ(glb->status, 200);
  EXPECT_EQ(glb->body.substr(0, 4), "glTF");
  const json document = glbJsonChunk(glb->body);
  bool marker = false;
  for (const json& node : document["nodes"]) marker = marker || node.value("name", "") == "marker";
  EXPECT_TRUE(marker) << "the paper's scene, the server's default problem";
  EXPECT_EQ(server.get("/api/scene.glb")->body, glb->body) << "written once";
}

TEST(ApiSessions, KauthamMeshScenesAreServedAsGlb) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  ServerOptions options;
  options.dataRoot = shared / "kautham";
  ApiTestServer server(options);
  const std::string base = "/api/sessions/ele";
  const auto opened = server.postJson(base + "/openProblem", {{"problem", "OMPL_geo_demos/Ele_hole_SE3/OMPL_RRTConnect_ele_hole_SE3.xml"}});
  ASSERT_EQ(opened->status, 200) << opened->body;
  const auto glb = server.get(base + "/scene.glb");
  ASSERT_EQ(glb->status, 200);
  std::uint32_t length = 0;
  std::memcpy(&length, glb->body.data() + 12, 4);
  const json document = json::parse(glb->body.substr(20, length));
  std::size_t links = 0;
  std::size_t vertices = 0;
  for (const json& node : document["nodes"]) links += node.contains("extras") && node["extras"]["kind"] == "link" ? 1 : 0;
  for (const json& accessor : document["accessors"]) vertices += accessor["type"] == "VEC3" ? accessor["count"].get<std::size_t>() : 0;
  EXPECT_GE(links, 1U);
  EXPECT_GT(vertices, 24U) << "the robot ele.iv and the obstacles: Kautham's Inventor meshes, converted";
  for (const json& node : document["nodes"]) {
    if (node.contains("extras")) {
      EXPECT_TRUE(node.contains("children")) << node["name"] << " has no geometry";
    }
  }
}

TEST(ApiSessions, EachClientHasItsOwnSession) {
  ApiTestServer server;
  ASSERT_EQ(server.postJson("/api/sessions/a/openProblem", {{"problem", "panda_desk"}})->status, 200);
  const auto other = server.get("/api/sessions/b");
  EXPECT_EQ(other->status, 404);
  EXPECT_THAT(errorOf(other), HasSubstr("openProblem first"));
  EXPECT_EQ(server.post("/api/sessions/b/solve")->status, 404);
  EXPECT_EQ(bodyOf(server.get("/api/sessions/a"))["problem"], "panda_desk");
}

TEST(ApiSessions, VerbErrorsNameWhatIsWrong) {
  ApiTestServer server;
  const std::string base = "/api/sessions/c";
  ASSERT_EQ(server.postJson(base + "/openProblem", {{"problem", "panda_desk"}})->status, 200);
  const auto wrongSize = server.postJson(base + "/setQuery", {{"init", {0.5}}, {"goal", {0.5}}});
  EXPECT_EQ(wrongSize->status, 400);
  EXPECT_THAT(errorOf(wrongSize), HasSubstr("init"));
  const auto badPlanner = server.postJson(base + "/setPlanner", {{"name", "NoSuchPlanner"}});
  EXPECT_EQ(badPlanner->status, 400);
  EXPECT_THAT(errorOf(badPlanner), HasSubstr("NoSuchPlanner"));
  const auto badParameter = server.postJson(base + "/setPlannerParameter", {{"name", "range"}, {"value", "-3"}});
  EXPECT_EQ(badParameter->status, 400);
  EXPECT_EQ(server.get(base + "/getPath")->status, 400) << "no path before solve";
  const auto missing = server.get(base + "/getObstaclePos");
  EXPECT_EQ(missing->status, 400);
  EXPECT_THAT(errorOf(missing), HasSubstr("\"obstacle\""));
  const auto unknown = server.get(base + "/getObstaclePos?obstacle=nothing_here");
  EXPECT_EQ(unknown->status, 400);
  EXPECT_THAT(errorOf(unknown), HasSubstr("nothing_here"));
  const auto typo = server.postJson(base + "/setObstaclePos", {{"obstacel", "x"}});
  EXPECT_EQ(typo->status, 400);
  EXPECT_THAT(errorOf(typo), HasSubstr("\"obstacel\" is not known"));
  const auto badPose = server.postJson(base + "/setRobotPos", {{"robot", "panda"}, {"pose", {{"kautham", {0, 0, 0, 0, 0, 0, 1}}}}});
  EXPECT_EQ(badPose->status, 400);
  EXPECT_THAT(errorOf(badPose), HasSubstr("zero rotation axis"));
  const auto nan = server.post(base + "/checkCollision", R"({"controls": [0.5, "x"]})");
  EXPECT_EQ(nan->status, 400);
  EXPECT_THAT(errorOf(nan), HasSubstr("\"controls\""));
  EXPECT_EQ(server.post(base + "/solve", R"({"time_limit": -1})")->status, 400);
}

TEST(ApiRequests, MalformedOversizedAndUnknownRequestsGetJsonErrors) {
  ServerOptions options;
  options.maxBodyBytes = 4096;
  ApiTestServer server(options);
  const auto malformed = server.post("/api/sessions/d/openProblem", "{\"problem\": ");
  EXPECT_EQ(malformed->status, 400);
  EXPECT_THAT(errorOf(malformed), HasSubstr("not valid JSON"));
  const auto deep = server.post("/api/sessions/d/openProblem", std::string(100, '[') + std::string(100, ']'));
  EXPECT_EQ(deep->status, 400);
  EXPECT_THAT(errorOf(deep), HasSubstr("nested deeper"));
  const auto notObject = server.post("/api/sessions/d/openProblem", "[1, 2]");
  EXPECT_EQ(notObject->status, 400);
  EXPECT_THAT(errorOf(notObject), HasSubstr("expected a JSON object"));
  const auto large = server.post("/api/sessions/d/openProblem", "{\"problem\": \"" + std::string(10000, 'x') + "\"}");
  EXPECT_EQ(large->status, 413);
  EXPECT_THAT(errorOf(large), HasSubstr("larger than 4096 bytes"));
  const auto unknown = server.post("/api/sessions/d/fly");
  EXPECT_EQ(unknown->status, 404);
  EXPECT_THAT(errorOf(unknown), HasSubstr("no endpoint POST /api/sessions/d/fly"));
  const auto unknownGet = server.get("/api/nothing");
  EXPECT_EQ(unknownGet->status, 404);
  const auto wrongMethod = server.get("/api/sessions/d/solve");
  EXPECT_EQ(wrongMethod->status, 405);
  EXPECT_EQ(wrongMethod->get_header_value("Allow"), "POST");
  const auto badClient = server.post("/api/sessions/a%20b/openProblem");
  EXPECT_EQ(badClient->status, 400);
  EXPECT_THAT(errorOf(badClient), HasSubstr("client id"));
  const auto text = server.client().Post("/api/sessions/d/openProblem", "problem=x", "application/x-www-form-urlencoded");
  EXPECT_EQ(text->status, 415);
  EXPECT_THAT(errorOf(text), HasSubstr("Content-Type: application/json"));
  EXPECT_EQ(bodyOf(text)["error"]["code"], "unsupported_media_type");
  EXPECT_EQ(bodyOf(large)["error"]["code"], "payload_too_large");
  // The server still serves after all that.
  EXPECT_EQ(server.get("/api/health")->status, 200);
}

std::string rawPost(const std::string& path, const std::string& headers = "") {
  return "POST " + path + " HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n" + headers + "\r\n";
}

TEST(ApiRequests, ChunkedBodiesAreLimitedWhileTheyAreRead) {
  ServerOptions options;
  options.maxBodyBytes = 4096;
  ApiTestServer server(options);
  const std::string chunked = "Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n";
  const std::string small = rawPost("/api/sessions/c/openProblem", chunked) + "2\r\n{}\r\n0\r\n\r\n";
  const std::string fine = test::rawExchange(server.port(), small);
  EXPECT_EQ(test::rawStatus(fine), 200) << fine;
  // A chunk of 32 MiB that never ends: the answer must come once the limit is passed, not when
  // the body is complete (it never is).
  const auto started = std::chrono::steady_clock::now();
  const std::string endless = test::rawExchange(server.port(), rawPost("/api/sessions/c/openProblem", chunked) + "2000000\r\n", 64 * 1024);
  EXPECT_EQ(test::rawStatus(endless), 413) << endless.substr(0, 300);
  EXPECT_EQ(test::rawBody(endless)["error"]["code"], "payload_too_large") << endless.substr(0, 300);
  EXPECT_THAT(test::rawBody(endless)["error"].value("message", ""), HasSubstr("larger than 4096 bytes"));
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(4)) << "the server waited for the whole body";
  const std::string broken = test::rawExchange(server.port(), rawPost("/api/sessions/c/openProblem", chunked) + "zz\r\n{}\r\n0\r\n\r\n");
  EXPECT_EQ(test::rawStatus(broken), 400) << broken;
  EXPECT_EQ(server.get("/api/health")->status, 200);
}

TEST(ApiRequests, PostsWithoutABodyMeanAnEmptyObject) {
  ApiTestServer server;
  // No Content-Length, no chunked encoding: what `curl -X POST URL` sends.
  const std::string open = test::rawExchange(server.port(), rawPost("/api/sessions/n/openProblem"));
  EXPECT_EQ(test::rawStatus(open), 200) << open;
  const std::string solve = test::rawExchange(server.port(), rawPost("/api/sessions/n/solve"));
  EXPECT_NE(test::rawStatus(solve), 400) << solve;
  EXPECT_TRUE(test::rawBody(solve).is_object()) << solve;
  const std::string close = test::rawExchange(server.port(), rawPost("/api/sessions/n/closeProblem"));
  EXPECT_EQ(test::rawStatus(close), 200) << close;
  const std::string cancel = test::rawExchange(server.port(), rawPost("/api/runs/run-1/cancel"));
  EXPECT_EQ(test::rawStatus(cancel), 404) << cancel;
  EXPECT_THAT(test::rawBody(cancel)["error"].value("message", ""), HasSubstr("run-1"));
  const auto started = std::chrono::steady_clock::now();
  const std::string unknown = test::rawExchange(server.port(), rawPost("/api/sessions/n/fly"));
  EXPECT_EQ(test::rawStatus(unknown), 404) << unknown;
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(3)) << "answered without waiting for a body";
  const std::string remove = test::rawExchange(server.port(), "DELETE /api/sessions/n HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(test::rawStatus(remove), 200) << remove;
}

TEST(ApiRequests, SessionLimitIsAClearError) {
  ServerOptions options;
  options.maxSessions = 2;
  ApiTestServer server(options);
  for (const char* client : {"one", "two"}) ASSERT_EQ(server.postJson(std::string("/api/sessions/") + client + "/openProblem", json::object())->status, 200);
  const auto third = server.postJson("/api/sessions/three/openProblem", json::object());
  EXPECT_EQ(third->status, 429);
  EXPECT_THAT(errorOf(third), HasSubstr("DELETE"));
  ASSERT_EQ(server.del("/api/sessions/one")->status, 200);
  EXPECT_EQ(server.postJson("/api/sessions/three/openProblem", json::object())->status, 200);
}

}  // namespace
}  // namespace lang2manip
