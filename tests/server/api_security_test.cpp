// The token, the viewer's static files and the data directory: what a server on a network must refuse.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "server/api_test_server.hpp"
#include "lang2manip/core/error.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::ApiTestServer;
using test::bodyOf;
using test::errorOf;
using ::testing::HasSubstr;

void writeText(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

TEST(ApiToken, EveryRequestNeedsTheToken) {
  ServerOptions options;
  options.token = "s3cret-token";
  ApiTestServer server(options);
  EXPECT_EQ(server.get("/api/health")->status, 200) << "health is for probes that hold no token";
  EXPECT_THAT(server.get("/api/health")->body, ::testing::Not(HasSubstr("run")));
  const auto none = server.get("/api/runs");
  EXPECT_EQ(none->status, 401);
  EXPECT_EQ(none->get_header_value("WWW-Authenticate"), "Bearer realm=\"lang2manip\"");
  EXPECT_THAT(errorOf(none), HasSubstr("requires a token"));
  server.setToken("s3cret-tokem");
  EXPECT_EQ(server.get("/api/runs")->status, 401);
  EXPECT_EQ(server.post("/api/sessions/x/openProblem")->status, 401);
  EXPECT_EQ(server.get("/api/openapi.json")->status, 401);
  EXPECT_EQ(server.get("/index.html")->status, 401);
  server.setToken("s3cret-token");
  EXPECT_EQ(server.get("/api/health")->status, 200);
  // The scheme's case does not matter (RFC 7235); another scheme is not a bearer token.
  httplib::Client raw = server.client();
  for (const char* scheme : {"bearer", "BEARER", "beaRer"}) {
    EXPECT_EQ(raw.Get("/api/health", {{"Authorization", std::string(scheme) + " s3cret-token"}})->status, 200) << scheme;
  }
  EXPECT_EQ(raw.Get("/api/runs", {{"Authorization", "Basic s3cret-token"}})->status, 401);
  EXPECT_EQ(raw.Get("/api/runs", {{"Authorization", "Bearers3cret-token"}})->status, 401);

  // The viewer is opened with ?token=...; the cookie set then lets the page load the rest.
  httplib::Client browser = server.client();
  const auto first = browser.Get("/api/runs?token=s3cret-token");
  ASSERT_EQ(first->status, 200);
  const std::string cookie = first->get_header_value("Set-Cookie");
  EXPECT_THAT(cookie, HasSubstr("HttpOnly"));
  const auto next = browser.Get("/api/runs", {{"Cookie", cookie.substr(0, cookie.find(';'))}});
  EXPECT_EQ(next->status, 200);
  EXPECT_EQ(browser.Get("/api/runs", {{"Cookie", "lang2manip_token=wrong"}})->status, 401);
}

TEST(ApiCrossSite, PagesOfOtherSitesCannotDriveOrReadTheServer) {
  ApiTestServer server;
  httplib::Client raw = server.client();
  // DNS rebinding: the attacker's name resolved to 127.0.0.1 arrives as the Host header.
  const auto rebound = raw.Get("/api/runs", {{"Host", "evil.example:8080"}});
  EXPECT_EQ(rebound->status, 403);
  EXPECT_THAT(errorOf(rebound), HasSubstr("is not this server's"));
  for (const char* host : {"localhost", "127.0.0.1", "[::1]:9"}) EXPECT_EQ(raw.Get("/api/health", {{"Host", host}})->status, 200) << host;
  // A page of another origin, even with the right Host.
  const std::string self = "127.0.0.1:" + std::to_string(server.port());
  const auto foreign = raw.Post("/api/runs", {{"Origin", "http://evil.example"}}, "{}", "application/json");
  EXPECT_EQ(foreign->status, 403);
  EXPECT_THAT(errorOf(foreign), HasSubstr("another origin"));
  EXPECT_EQ(raw.Get("/api/runs", {{"Origin", "http://" + self}})->status, 200) << "the server's own viewer";
  // Bodies a page may send without asking the browser first (forms, text/plain) are not read.
  for (const char* type : {"text/plain", "application/x-www-form-urlencoded", ""}) {
    const auto sent = raw.Post("/api/sessions/x/openProblem", "{}", type);
    EXPECT_EQ(sent->status, 415) << type;
    EXPECT_THAT(errorOf(sent), HasSubstr("Content-Type: application/json")) << type;
  }
}

TEST(ApiFraming, AContentLengthGivenTwiceOrNotAsDigitsIsRefused) {
  ApiTestServer server;
  const auto exchange = [&](const std::string& lengths) {
    return test::rawExchange(server.port(), "POST /api/sessions/f/openProblem HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                                            "Content-Type: application/json\r\n" + lengths + "Connection: close\r\n\r\n{}");
  };
  for (const std::string& lengths : {std::string("Content-Length: 2\r\nContent-Length: 2\r\n"), std::string("Content-Length: 2\r\nContent-Length: 40\r\n")}) {
    const std::string answer = exchange(lengths);
    EXPECT_THAT(answer, HasSubstr("400")) << lengths;
    EXPECT_THAT(answer, HasSubstr("Content-Length must be given once")) << lengths;
  }
  EXPECT_THAT(exchange("Content-Length: 2\r\n"), HasSubstr("200 OK"));
}

TEST(ApiStaticFiles, ServesOnlyTheViewersOwnFiles) {
  const test::TempDirectory temporary;
  const fs::path viewer = temporary.path() / "viewer";
  writeText(viewer / "index.html", "<html>viewer</html>");
  writeText(viewer / "viewer.js", "console.log(1)");
  writeText(viewer / ".hidden", "no");
  writeText(temporary.path() / "secret.txt", "TOP-SECRET-CONTENT");
  fs::create_symlink(temporary.path() / "secret.txt", viewer / "link.txt");
  ServerOptions options;
  options.viewerDirectory = viewer;
  ApiTestServer server(options);
  const auto index = server.get("/");
  ASSERT_EQ(index->status, 200);
  EXPECT_EQ(index->body, "<html>viewer</html>");
  EXPECT_THAT(index->get_header_value("Content-Type"), HasSubstr("text/html"));
  const auto script = server.get("/viewer.js");
  EXPECT_THAT(script->get_header_value("Content-Type"), HasSubstr("text/javascript"));
  for (const char* path : {"/../secret.txt", "/%2e%2e/secret.txt", "/.hidden", "/link.txt", "/sub/../../secret.txt", "/a\\..\\..\\secret.txt"}) {
    const auto refused = server.get(path);
    ASSERT_TRUE(refused) << path;
    EXPECT_EQ(refused->status, 403) << path << ": " << refused->body;
    EXPECT_THAT(refused->body, ::testing::Not(HasSubstr("TOP-SECRET-CONTENT"))) << path;
  }
  EXPECT_EQ(server.get("/missing.js")->status, 404);
}

TEST(ApiStaticFiles, NoViewerIsAClearNotFound) {
  ApiTestServer server;
  const auto page = server.get("/");
  EXPECT_EQ(page->status, 404);
  EXPECT_THAT(errorOf(page), HasSubstr("no viewer directory"));
}

TEST(ApiDataRoot, RequestsNameFilesOnlyUnderTheDataDirectory) {
  const test::TempDirectory temporary;
  const fs::path root = temporary.path() / "data";
  writeText(root / "broken.xml", "<Problem><Robot robot=\"missing.urdf\"");
  writeText(temporary.path() / "outside.xml", "<Problem/>");
  ServerOptions options;
  options.dataRoot = root;
  ApiTestServer server(options);
  const std::string rootPath = fs::canonical(root).string();
  for (const std::string& name : {(temporary.path() / "outside.xml").string(), std::string("../outside.xml"), std::string("/etc/passwd")}) {
    const auto refused = server.postJson("/api/sessions/e/openProblem", {{"problem", name}});
    EXPECT_EQ(refused->status, 403) << name;
    EXPECT_THAT(errorOf(refused), HasSubstr("file " + name + ": outside the server's data directory")) << name;
    EXPECT_THAT(errorOf(refused), ::testing::Not(HasSubstr(rootPath))) << "the server's own path stays private";
  }
  const auto nul = server.postJson("/api/sessions/e/openProblem", {{"problem", std::string("broken.xml\0.png", 15)}});
  EXPECT_EQ(nul->status, 400);
  EXPECT_THAT(errorOf(nul), HasSubstr("NUL byte"));
  const auto nulPath = server.get("/api/runs/run-1%00x");
  EXPECT_EQ(nulPath->status, 400);
  EXPECT_THAT(errorOf(nulPath), HasSubstr("NUL byte (%00)"));
  const auto nulFile = server.get("/index%00.html");
  EXPECT_EQ(nulFile->status, 400);
  const auto missing = server.postJson("/api/sessions/e/openProblem", {{"problem", "nothing.xml"}});
  EXPECT_EQ(missing->status, 404);
  const auto broken = server.postJson("/api/sessions/e/openProblem", {{"problem", "broken.xml"}});
  EXPECT_EQ(broken->status, 400);
  EXPECT_THAT(errorOf(broken), HasSubstr("broken.xml"));
  EXPECT_THAT(errorOf(broken), ::testing::Not(HasSubstr(rootPath)));
  const auto builtin = server.postJson("/api/sessions/e/openProblem", {{"problem", "ur5_desk"}});
  EXPECT_EQ(builtin->status, 200) << builtin->body;
  const auto obstacle = server.postJson("/api/sessions/e/addObstacle",
                                        {{"urdf", "/etc/hostname"}, {"name", "x"}, {"pose", {{"position", {0, 0, 0}}}}});
  EXPECT_EQ(obstacle->status, 403);
}

TEST(ApiDataRoot, TheOperatorsOwnProblemIsServedWhereverItLies) {
  const test::TempDirectory temporary;
  const fs::path problem = fs::canonical(test::testDataDirectory() / "../../data/problems/desk/ur5_desk.xml");
  ServerOptions options;
  options.dataRoot = temporary.path();
  options.defaultProblem = problem.string();
  ApiTestServer server(options);
  const auto opened = server.post("/api/sessions/o/openProblem");
  EXPECT_EQ(opened->status, 200) << opened->body;
  EXPECT_EQ(bodyOf(opened)["problem"], "ur5_desk");
  const auto named = server.postJson("/api/sessions/o/openProblem", {{"problem", problem.string()}});
  EXPECT_EQ(named->status, 200) << named->body;
  // Not a licence for its directory.
  const auto sibling = server.postJson("/api/sessions/o/openProblem", {{"problem", (problem.parent_path() / "tx90_desk.xml").string()}});
  EXPECT_EQ(sibling->status, 403);
  options.defaultProblem = (temporary.path() / "nosuch.xml").string();
  try {
    ApiServer refused(options);
    ADD_FAILURE() << "a server started with a problem that does not exist";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("nosuch.xml"));
  }
}

TEST(ApiOptions, BadServerOptionsAreRefused) {
  ServerOptions options;
  options.port = 70000;
  EXPECT_THROW(ApiServer{options}, InputError);
  options = {};
  options.viewerDirectory = "/nonexistent-viewer";
  EXPECT_THROW(ApiServer{options}, InputError);
  options = {};
  options.token = "has space";
  EXPECT_THROW(ApiServer{options}, InputError);
  options = {};
  options.host = "203.0.113.7";  // TEST-NET-3: not an address of this machine
  EXPECT_THROW(ApiServer{options}, InputError);
  options = {};
  options.maxEventStreams = 0;
  EXPECT_THROW(ApiServer{options}, InputError);
}

TEST(ApiOptions, ASecondServerOnAPortInUseFailsClearly) {
  ApiTestServer first;
  ServerOptions options;
  options.port = first.port();
  try {
    ApiServer second(options);
    ADD_FAILURE() << "a second server bound port " << first.port();
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("address in use"));
    EXPECT_THAT(error.what(), HasSubstr(std::to_string(first.port())));
  }
  EXPECT_EQ(first.get("/api/health")->status, 200);
}

}  // namespace
}  // namespace lang2manip
