// The viewer served by the API draws a session's solved path where forward kinematics puts it.

#include <gtest/gtest.h>

#include <filesystem>
#include <tuple>
#include <vector>

#include "cli/viewer_kinematics_support.hpp"
#include "server/api_test_server.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

TEST(ApiViewer, TheSessionPageDrawsTheHandWhereForwardKinematicsOfThePathPutsIt) {
  ServerOptions options;
  // The viewer built beside the program (build/viewer/dist), as `serve` finds it.
  options.viewerDirectory = std::filesystem::path(LANG2MANIP_CLI_PATH).parent_path() / "../../../viewer/dist";
  if (!std::filesystem::exists(options.viewerDirectory / "index.html")) GTEST_SKIP() << "the viewer is not built in this configuration";
  options.token = "viewer-token";
  test::ApiTestServer server(options);
  server.setToken("viewer-token");
  const std::string base = "/api/sessions/fk";
  ASSERT_EQ(server.postJson(base + "/openProblem", {{"problem", "panda_desk"}})->status, 200);
  const auto solved = server.postJson(base + "/solve", {{"time_limit", 5}});
  ASSERT_EQ(solved->status, 200);
  ASSERT_TRUE(test::bodyOf(solved)["solved"].get<bool>()) << solved->body;
  const json trajectory = test::bodyOf(server.get(base + "/getPath"))["trajectory"];
  const std::vector<std::tuple<double, json, json>> segments{{0.0, trajectory["joint_names"], trajectory["points"]}};
  test::expectPageDraws("http://127.0.0.1:" + std::to_string(server.port()) + "/?session=fk&token=viewer-token",
                        test::handPositions(segments));
}

}  // namespace
}  // namespace lang2manip
