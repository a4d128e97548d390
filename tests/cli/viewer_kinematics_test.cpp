// The pages the tool writes draw the robot where forward kinematics of their trajectories puts it:
// each page opened in headless Chromium, the hand's drawn position at several times compared with
// FK computed here from the trajectory files written beside the page.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_run.hpp"
#include "cli/viewer_kinematics_support.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::expectPageDraws;
using test::handPositions;

TEST(ViewerKinematics, RunPageDrawsTheHandWhereForwardKinematicsOfTheTrajectoryPutsIt) {
  const test::TempDirectory temporary;
  const test::RunResult result = test::run("run --html --task \"put the marker in the holder\" --out " + temporary.path().string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const json trajectory = json::parse(test::readFileText(temporary.path() / "trajectory.json"));
  std::vector<std::tuple<double, json, json>> segments;
  for (const json& segment : trajectory["segments"]) {
    segments.emplace_back(segment["start_time"].get<double>(), segment["arm"]["joint_names"], segment["arm"]["points"]);
  }
  ASSERT_EQ(segments.size(), 2u);
  expectPageDraws(temporary.path() / "run.html", handPositions(segments));
}

TEST(ViewerKinematics, SolvePageDrawsTheHandWhereForwardKinematicsOfTheTrajectoryPutsIt) {
  const test::TempDirectory temporary;
  const fs::path page = temporary.path() / "solve.html";
  const test::RunResult result =
      test::run("solve --html " + page.string() + " --out " + (temporary.path() / "result.json").string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const json report = json::parse(test::readFileText(temporary.path() / "result.json"));
  std::vector<std::tuple<double, json, json>> segments;
  double start = 0.0;
  for (const json& query : report["queries"]) {
    const json& trajectory = query["trajectory"];
    segments.emplace_back(start, trajectory["joint_names"], trajectory["points"]);
    start += query["duration"].get<double>();
  }
  ASSERT_FALSE(segments.empty());
  expectPageDraws(page, handPositions(segments));
}

}  // namespace
}  // namespace lang2manip
