// What users look at: run --html (one page that opens offline), scene.glb and viewer.json beside
// every run, and `render` (PNG snapshots through headless Chromium), with their bad inputs.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_run.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ::testing::HasSubstr;

bool chromiumInstalled() { return fs::exists("/usr/bin/chromium"); }

/// Skips the test without Chromium, unless LANG2MANIP_REQUIRE_BROWSER=1 (make test) makes that a
/// failure.
#define LANG2MANIP_REQUIRE_CHROMIUM()                                                                       \
  if (!chromiumInstalled()) {                                                                               \
    if (std::getenv("LANG2MANIP_REQUIRE_BROWSER") != nullptr) FAIL() << "no /usr/bin/chromium, and LANG2MANIP_REQUIRE_BROWSER is set"; \
    GTEST_SKIP() << "no /usr/bin/chromium (Debian: apt-get install chromium): skipped";                     \
  }

void writeText(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

/// A short run (two moments: start and end) written to `directory`.
void writeShortRun(const fs::path& directory, bool html) {
  const test::RunResult result =
      test::run("run --task \"push the eraser 5 cm to the left\" --out " + directory.string() + (html ? " --html" : ""));
  ASSERT_EQ(result.exitCode, 0) << result.output;
}

TEST(RunHtml, ThePaperTaskIsOneSelfContainedPageUnderFiveMegabytes) {
  const test::TempDirectory temporary;
  const test::RunResult result = test::run("run --html --out " + temporary.path().string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  // The "wrote" line lists every file the run wrote.
  const std::string wrote = result.output.substr(result.output.find("wrote "));
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(temporary.path())) {
    if (entry.path().filename().string() == ".lang2manip-output") continue;  // the marker of an output set
    EXPECT_THAT(wrote, HasSubstr(entry.path().filename().string())) << "not listed";
    ++files;
  }
  EXPECT_EQ(files, 13U);
  const fs::path page = temporary.path() / "run.html";
  ASSERT_TRUE(fs::exists(page));
  EXPECT_LT(fs::file_size(page), 5U << 20);
  const std::string html = test::readFileText(page);
  for (const char* part : {"id=\"lang2manip-run\"", "id=\"lang2manip-glb\"", "lang2manip viewer"}) EXPECT_THAT(html, HasSubstr(part));
  EXPECT_THAT(html, ::testing::Not(HasSubstr("src=\"http"))) << "nothing is fetched";
  const json viewer = json::parse(test::readFileText(temporary.path() / "viewer.json"));
  EXPECT_EQ(viewer["actions"].size(), 4U);
  std::vector<std::string> labels;
  for (const json& moment : viewer["moments"]) labels.push_back(moment["label"]);
  EXPECT_EQ(labels, (std::vector<std::string>{"start", "grasp marker", "release marker", "grasp eraser", "release eraser", "end"}));
  EXPECT_EQ(test::readFileText(temporary.path() / "scene.glb").substr(0, 4), "glTF");
}

/// The JSON chunk of a GLB file.
json glbDocument(const fs::path& file) {
  const std::string bytes = test::readFileText(file);
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return json::parse(bytes.substr(20, length));
}

/// Everything after the JSON chunk of a GLB file (the binary chunk with its header).
std::string glbTail(const fs::path& file) {
  const std::string bytes = test::readFileText(file);
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return bytes.substr(20 + length);
}

void appendWord(std::string& bytes, std::uint32_t word) { bytes.append(reinterpret_cast<const char*>(&word), 4); }

/// A GLB of `jsonChunk` (padded with spaces) and `tail` (written as it is).
std::string glbOf(std::string jsonChunk, const std::string& tail) {
  jsonChunk.append((4 - jsonChunk.size() % 4) % 4, ' ');
  std::string bytes = "glTF";
  appendWord(bytes, 2);
  appendWord(bytes, static_cast<std::uint32_t>(20 + jsonChunk.size() + tail.size()));
  appendWord(bytes, static_cast<std::uint32_t>(jsonChunk.size()));
  bytes += "JSON";
  return bytes + jsonChunk + tail;
}

TEST(RunHtml, RecordTreeDrawsTheExplorationGraphsInGreen) {
  const test::TempDirectory temporary;
  const test::RunResult result = test::run("run --record-tree --task \"put the marker in the holder\" --out " + temporary.path().string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const json document = glbDocument(temporary.path() / "scene.glb");
  std::size_t trees = 0;
  for (const json& node : document["nodes"]) {
    const std::string name = node.value("name", "");
    if (name.rfind("exploration_tree/", 0) != 0) continue;
    ++trees;
    const json& primitive = document["meshes"][node["mesh"].get<std::size_t>()]["primitives"][0];
    EXPECT_EQ(primitive["mode"], 1) << "LINES";
  }
  EXPECT_GE(trees, 2U) << "one graph per transit: to the marker, to the holder";
  const test::TempDirectory other;
  ASSERT_EQ(test::run("run --task \"put the marker in the holder\" --out " + other.path().string()).exitCode, 0);
  EXPECT_EQ(glbDocument(other.path() / "scene.glb").dump().find("exploration_tree"), std::string::npos);
}

TEST(RunHtml, WithoutTheViewerTheRunIsRefusedBeforeItStarts) {
  const test::TempDirectory temporary;
  const fs::path out = temporary.path() / "out";
  const test::RunResult result = test::run("run --html --out " + out.string(), true, "LANG2MANIP_VIEWER_DIR=/nonexistent");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("the web viewer is not built"));
  EXPECT_FALSE(fs::exists(out)) << "nothing was run";
}

TEST(SolveHtml, TheSolvedQueriesAreOnePage) {
  const test::TempDirectory temporary;
  const fs::path page = temporary.path() / "solve.html";
  const test::RunResult result = test::run("solve --record-tree --html " + page.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("wrote " + page.string()));
  const std::string html = test::readFileText(page);
  EXPECT_THAT(html, HasSubstr("\"kind\":\"query\""));
  EXPECT_THAT(html, HasSubstr("id=\"lang2manip-glb\""));
  const test::RunResult missing = test::run("solve --html " + page.string(), true, "LANG2MANIP_VIEWER_DIR=/nonexistent");
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_THAT(missing.output, HasSubstr("the web viewer is not built"));
}

TEST(RenderCli, BadRunDirectoriesAreClearErrors) {
  const test::TempDirectory temporary;
  const fs::path run = temporary.path();
  const test::RunResult empty = test::run("render " + run.string());
  EXPECT_EQ(empty.exitCode, 1);
  EXPECT_THAT(empty.output, HasSubstr("viewer.json: missing"));

  writeText(run / "viewer.json", "{\"format_version\": 1, \"moments\": [{\"time\": 0, \"label\": \"start\"}]}");
  const test::RunResult noScene = test::run("render " + run.string());
  EXPECT_THAT(noScene.output, HasSubstr("scene.glb: missing"));

  writeText(run / "scene.glb", "glTF-not-really");
  const test::RunResult corrupt = test::run("render " + run.string());
  EXPECT_EQ(corrupt.exitCode, 1);
  EXPECT_THAT(corrupt.output, HasSubstr("scene.glb: not a glTF binary"));

  std::string truncated = "glTF";
  for (const std::uint32_t word : {2U, 4096U, 0U, 0U}) truncated.append(reinterpret_cast<const char*>(&word), 4);
  writeText(run / "scene.glb", truncated);
  EXPECT_THAT(test::run("render " + run.string()).output, HasSubstr("truncated"));

  writeText(run / "viewer.json", "{\"format_version\": 1, \"moments\": [{\"time\": -1}]}");
  EXPECT_THAT(test::run("render " + run.string()).output, HasSubstr("moments[0]"));
  writeText(run / "viewer.json", "{\"format_version\": 1, \"moments\": [");
  EXPECT_THAT(test::run("render " + run.string()).output, HasSubstr("not valid JSON"));
  writeText(run / "viewer.json", "[]");
  EXPECT_THAT(test::run("render " + run.string()).output, HasSubstr("format_version 1"));
}

TEST(RenderCli, CorruptScenesAndDocumentsAreRefusedBeforeDrawing) {
  const test::TempDirectory temporary;
  const fs::path run = temporary.path();
  writeShortRun(run, false);
  const fs::path scene = run / "scene.glb";
  const json document = glbDocument(scene);
  const std::string tail = glbTail(scene);
  const auto refused = [&](const std::string& glb, const std::string& expected) {
    writeText(scene, glb);
    const test::RunResult result = test::run("render " + run.string() + " --chromium /bin/false");
    EXPECT_EQ(result.exitCode, 1) << expected;
    EXPECT_THAT(result.output, HasSubstr(scene.string() + ": ")) << expected;
    EXPECT_THAT(result.output, HasSubstr(expected));
    EXPECT_FALSE(fs::exists(run / "render")) << expected;
  };
  refused(glbOf(std::string(document.dump().size(), ' '), tail), "the JSON chunk");
  json sampler = document;
  sampler["animations"][0]["samplers"][0]["input"] = 99999;
  refused(glbOf(sampler.dump(), tail), "animations[0].samplers[0].input: 99999 is not one of the");
  json channel = document;
  channel["animations"][0]["channels"][0]["sampler"] = 99999;
  refused(glbOf(channel.dump(), tail), "animations[0].channels[0].sampler");
  refused(glbOf(document.dump(), tail.substr(0, tail.size() / 2)), "the binary chunk says");
  json accessor = document;
  accessor["accessors"][0]["count"] = 1U << 30;
  refused(glbOf(accessor.dump(), tail), "accessors[0]: 1073741824 elements need");
  json view = document;
  view["bufferViews"][0]["byteOffset"] = 1U << 30;
  refused(glbOf(view.dump(), tail), "bufferViews[0]: bytes up to");
  json node = document;
  node["nodes"][0]["children"] = json::array({424242});
  refused(glbOf(node.dump(), tail), "nodes[0].children[0]: 424242 is not one of the");
  json mesh = document;
  mesh["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 77777;
  refused(glbOf(mesh.dump(), tail), "meshes[0].primitives[0].attributes.POSITION");
  json noAsset = document;
  noAsset.erase("asset");
  refused(glbOf(noAsset.dump(), tail), "not a glTF document");
  refused(glbOf(document.dump(), ""), "bytes, but the binary chunk has 0");

  writeText(scene, glbOf(document.dump(), tail));
  const fs::path viewer = run / "viewer.json";
  const json moments = json::parse(test::readFileText(viewer));
  json late = moments;
  late["moments"][1]["time"] = 1e9;
  writeText(viewer, late.dump());
  const test::RunResult lateResult = test::run("render " + run.string() + " --chromium /bin/false");
  EXPECT_EQ(lateResult.exitCode, 1);
  EXPECT_THAT(lateResult.output, HasSubstr("viewer.json: moments[1].time 1e+09 s: after the run's end"));
  json actions = moments;
  actions["actions"] = "nonsense";
  writeText(viewer, actions.dump());
  EXPECT_THAT(test::run("render " + run.string()).output, HasSubstr("viewer.json: \"actions\": expected an array"));
  json duration = moments;
  duration["duration"] = "long";
  writeText(viewer, duration.dump());
  EXPECT_THAT(test::run("render " + run.string()).output, HasSubstr("viewer.json: \"duration\""));
}

TEST(RenderCli, TheViewersOwnErrorFailsTheRenderWithItsMessage) {
  LANG2MANIP_REQUIRE_CHROMIUM();
  const test::TempDirectory temporary;
  const fs::path run = temporary.path();
  writeShortRun(run, false);
  // Well-formed, but asks for a decoder the viewer does not have: only the viewer can tell.
  json document = glbDocument(run / "scene.glb");
  document["extensionsUsed"] = json::array({"KHR_draco_mesh_compression"});
  document["extensionsRequired"] = json::array({"KHR_draco_mesh_compression"});
  writeText(run / "scene.glb", glbOf(document.dump(), glbTail(run / "scene.glb")));
  const test::RunResult result = test::run("render " + run.string() + " --size 320x240");
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("the viewer cannot show"));
  EXPECT_THAT(result.output, HasSubstr("DRACOLoader"));
  EXPECT_FALSE(fs::exists(run / "render" / "01-start.png")) << "no picture of the error banner";
}

TEST(RenderCli, BadOptionsAreClearErrors) {
  const test::TempDirectory temporary;
  writeShortRun(temporary.path(), false);
  for (const char* camera : {"abc", "10", "10,95", "10,20,0", "10,20,", "10,20,3,4", "nan,1"}) {
    const test::RunResult result = test::run("render " + temporary.path().string() + " --camera=" + camera);
    EXPECT_EQ(result.exitCode, 1) << camera;
    EXPECT_THAT(result.output, HasSubstr(std::string("--camera ") + camera + ": expected AZIMUTH,ELEVATION")) << camera;
  }
  for (const char* timeout : {"-1", "0", "1e9"}) {
    const test::RunResult result = test::run("render " + temporary.path().string() + " --timeout=" + timeout);
    EXPECT_EQ(result.exitCode, 1) << timeout;
    EXPECT_THAT(result.output, HasSubstr("--timeout")) << timeout;
  }
  EXPECT_THAT(test::run("render " + temporary.path().string() + " --size 10x10").output, HasSubstr("--size 10x10"));
  EXPECT_THAT(test::run("render " + temporary.path().string() + " --size big").output, HasSubstr("WIDTHxHEIGHT"));
  EXPECT_THAT(test::run("render " + temporary.path().string() + " --chromium /nonexistent/chromium").output, HasSubstr("not an executable"));
  EXPECT_EQ(test::run("render").exitCode, 1);
}

TEST(RenderCli, SnapshotsEveryMomentAndAContactSheet) {
  LANG2MANIP_REQUIRE_CHROMIUM();
  const test::TempDirectory temporary;
  writeShortRun(temporary.path(), false);
  const test::RunResult result = test::run("render " + temporary.path().string() + " --size 320x240");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  for (const char* name : {"01-start.png", "02-end.png", "contact-sheet.png"}) {
    const fs::path png = temporary.path() / "render" / name;
    ASSERT_TRUE(fs::exists(png)) << name << "\n" << result.output;
    EXPECT_EQ(test::readFileText(png).substr(1, 3), "PNG") << name;
  }
  // Pictures of an error banner would be alike: the start and the end differ (the eraser moved).
  EXPECT_NE(test::readFileText(temporary.path() / "render" / "01-start.png"), test::readFileText(temporary.path() / "render" / "02-end.png"));
  EXPECT_GT(fs::file_size(temporary.path() / "render" / "01-start.png"), 5000U) << "a scene, not a flat image";
  // Drawn at the size asked for (PNG's IHDR: big-endian width and height at bytes 16 and 20).
  const std::string png = test::readFileText(temporary.path() / "render" / "01-start.png");
  const auto word = [&png](std::size_t at) {
    return (static_cast<unsigned>(static_cast<unsigned char>(png[at])) << 24U) | (static_cast<unsigned>(static_cast<unsigned char>(png[at + 1])) << 16U) |
           (static_cast<unsigned>(static_cast<unsigned char>(png[at + 2])) << 8U) | static_cast<unsigned>(static_cast<unsigned char>(png[at + 3]));
  };
  EXPECT_EQ(word(16), 320U);
  EXPECT_EQ(word(20), 240U);
}

TEST(RenderCli, ASolvePageIsRenderedAtItsStartMiddleAndEnd) {
  LANG2MANIP_REQUIRE_CHROMIUM();
  const test::TempDirectory temporary;
  const fs::path page = temporary.path() / "solved.html";
  ASSERT_EQ(test::run("solve panda_desk --html " + page.string()).exitCode, 0);
  const test::RunResult result = test::run("render " + page.string() + " --size 320x240");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const fs::path pictures = temporary.path() / "solved-render";
  for (const char* name : {"01-start.png", "02-middle.png", "03-end.png", "contact-sheet.png"}) {
    ASSERT_TRUE(fs::exists(pictures / name)) << name << "\n" << result.output;
  }
  EXPECT_NE(test::readFileText(pictures / "01-start.png"), test::readFileText(pictures / "03-end.png")) << "the arm moved";
}

TEST(RenderCli, ABrowserThatDoesNotSpeakTheProtocolIsAClearError) {
  const test::TempDirectory temporary;
  writeShortRun(temporary.path(), false);
  const test::RunResult result = test::run("render " + temporary.path().string() + " --chromium /bin/true --timeout 10");
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("render: /bin/true has gone"));
  EXPECT_FALSE(fs::exists(temporary.path() / "render" / "01-start.png"));
}

}  // namespace
}  // namespace lang2manip
