#pragma once
/// @file Checking that a page of the viewer draws the robot where forward kinematics of a
/// trajectory puts it: expected hand positions computed here, the page opened in headless
/// Chromium by viewer/test/browser-test.mjs (--expect-position). Used by the CLI's pages
/// (viewer_kinematics_test.cpp) and the server's session page (api_viewer_test.cpp).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "lang2manip/model/kautham_problem.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {

struct ExpectedPosition {
  std::string node;
  double time = 0.0;
  Vector3 position;
};

inline double secondsOf(const nlohmann::json& timeFromStart) {
  return timeFromStart["sec"].get<double>() + 1e-9 * timeFromStart["nanosec"].get<double>();
}

inline const KauthamProblem& deskProblem() {
  static const KauthamProblem problem =
      readKauthamProblem(test::testDataDirectory().parent_path().parent_path() / "data/problems/desk/panda_desk.xml");
  return problem;
}

/// Where FK puts `link` of the desk's robot with the joints `names` at `positions` (the others
/// mid-range, as the pages leave joints no trajectory names).
inline Vector3 linkPositionAt(const std::string& link, const nlohmann::json& names, const nlohmann::json& positions) {
  const SceneRobot& robot = deskProblem().scene.robots().front();
  VectorX q = robot.model->middleConfiguration();
  for (std::size_t j = 0; j < names.size(); ++j) {
    q[robot.model->variableIndex(names[j].get<std::string>())] = positions[j].get<double>();
  }
  return (robot.basePose * robot.model->linkPoses(q)[static_cast<std::size_t>(robot.model->linkIndex(link))]).translation();
}

/// The hand at the first, middle and last point of each trajectory of `segments` (each
/// {"start", "names", "points"}).
inline std::vector<ExpectedPosition> handPositions(const std::vector<std::tuple<double, nlohmann::json, nlohmann::json>>& segments) {
  std::vector<ExpectedPosition> expected;
  for (const auto& [start, names, points] : segments) {
    for (const std::size_t i : {std::size_t{0}, points.size() / 2, points.size() - 1}) {
      const nlohmann::json& point = points[i];
      expected.push_back({"panda/panda_hand", start + secondsOf(point["time_from_start"]),
                          linkPositionAt("panda_hand", names, point["positions"])});
    }
  }
  return expected;
}

/// Opens `page` (a file, or a URL when it has "://") in headless Chromium and checks that it draws
/// each expected node there.
inline void expectPageDraws(const std::string& page, const std::vector<ExpectedPosition>& expected) {
#if defined(LANG2MANIP_NODE_PATH) && defined(LANG2MANIP_BROWSER_TEST)
  if (!fs::exists("/usr/bin/chromium")) {
    if (std::getenv("LANG2MANIP_REQUIRE_BROWSER") != nullptr) FAIL() << "no /usr/bin/chromium, and LANG2MANIP_REQUIRE_BROWSER is set";
    GTEST_SKIP() << "no /usr/bin/chromium (Debian: apt-get install chromium): skipped";
  }
  std::ostringstream command;
  command.precision(9);
  command << LANG2MANIP_NODE_PATH << ' ' << LANG2MANIP_BROWSER_TEST << " --no-play --url '" << (page.find("://") == std::string::npos ? "file://" + page : page) << "'";
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

}  // namespace lang2manip::test
