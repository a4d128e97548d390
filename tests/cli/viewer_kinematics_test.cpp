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
#include "lang2manip/model/kautham_problem.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct ExpectedPosition {
  std::string node;
  double time = 0.0;
  Vector3 position;
};

double secondsOf(const json& timeFromStart) {
  return timeFromStart["sec"].get<double>() + 1e-9 * timeFromStart["nanosec"].get<double>();
}

const KauthamProblem& deskProblem() {
  static const KauthamProblem problem =
      readKauthamProblem(test::testDataDirectory().parent_path().parent_path() / "data/problems/desk/panda_desk.xml");
  return problem;
}

/// Where FK puts `link` of the desk's robot with the joints `names` at `positions` (the others
/// mid-range, as the pages leave joints no trajectory names).
Vector3 linkPositionAt(const std::string& link, const json& names, const json& positions) {
  const SceneRobot& robot = deskProblem().scene.robots().front();
  VectorX q = robot.model->middleConfiguration();
  for (std::size_t j = 0; j < names.size(); ++j) {
    q[robot.model->variableIndex(names[j].get<std::string>())] = positions[j].get<double>();
  }
  return (robot.basePose * robot.model->linkPoses(q)[static_cast<std::size_t>(robot.model->linkIndex(link))]).translation();
}

/// The hand at the first, middle and last point of each trajectory of `segments` (each
/// {"start", "names", "points"}).
std::vector<ExpectedPosition> handPositions(const std::vector<std::tuple<double, json, json>>& segments) {
  std::vector<ExpectedPosition> expected;
  for (const auto& [start, names, points] : segments) {
    for (const std::size_t i : {std::size_t{0}, points.size() / 2, points.size() - 1}) {
      const json& point = points[i];
      expected.push_back({"panda/panda_hand", start + secondsOf(point["time_from_start"]),
                          linkPositionAt("panda_hand", names, point["positions"])});
    }
  }
  return expected;
}

/// Opens `page` in headless Chromium and checks that it draws each expected node there.
void expectPageDraws(const fs::path& page, const std::vector<ExpectedPosition>& expected) {
#if defined(LANG2MANIP_NODE_PATH) && defined(LANG2MANIP_BROWSER_TEST)
  if (!fs::exists("/usr/bin/chromium")) {
    if (std::getenv("LANG2MANIP_REQUIRE_BROWSER") != nullptr) FAIL() << "no /usr/bin/chromium, and LANG2MANIP_REQUIRE_BROWSER is set";
    GTEST_SKIP() << "no /usr/bin/chromium (Debian: apt-get install chromium): skipped";
  }
  std::ostringstream command;
  command.precision(9);
  command << LANG2MANIP_NODE_PATH << ' ' << LANG2MANIP_BROWSER_TEST << " --no-play --url file://" << page.string();
  for (const ExpectedPosition& at : expected) {
    command << " --expect-position '" << at.node << '@' << at.time << '=' << at.position.x() << ',' << at.position.y() << ','
            << at.position.z() << '\'';
  }
  command << " 2>&1";
  std::string output;
  FILE* pipe = ::popen(command.str().c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
  const int status = ::pclose(pipe);
  EXPECT_EQ(status, 0) << output;
  EXPECT_THAT(output, ::testing::HasSubstr("is drawn within")) << output;
#else
  (void)page;
  (void)expected;
  GTEST_SKIP() << "the viewer is not built in this configuration (sanitizers, or no Node.js)";
#endif
}

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
