// The MotionBenchMaker Panda problems (../shared/data/mbm): start and goal validity, counted.

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <set>

#include "collision_test_support.hpp"
#include "lang2manip/model/moveit_scene_reader.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {
namespace {

struct Counts {
  int problems = 0;
  int invalidStarts = 0;
  int invalidGoals = 0;
};

TEST(MotionBenchMaker, MostStartsAndGoalsAreValid) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const RobotModelPtr panda = builtinRobot("panda");
  std::map<std::string, Counts> perSet;
  std::set<std::filesystem::path> scenes;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(shared / "mbm/panda")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("scene", 0) == 0 && entry.path().extension() == ".yaml") scenes.insert(entry.path());
  }
  ASSERT_FALSE(scenes.empty());
  Counts total;
  for (const std::filesystem::path& file : scenes) {
    const MoveItProblem problem = readMoveItProblem(file, requestFileForScene(file), panda);
    // Every checker shares the model's cached allowed-collision matrix.
    const FclCollisionChecker checker(problem.scene);
    const auto context = checker.makeContext();
    Counts& counts = perSet[file.parent_path().filename().string()];
    const bool start = checker.isStateValid(0, problem.start, *context);
    const bool goal = checker.isStateValid(0, problem.goal, *context);
    for (Counts* c : {&counts, &total}) {
      ++c->problems;
      c->invalidStarts += start ? 0 : 1;
      c->invalidGoals += goal ? 0 : 1;
    }
    if (!start || !goal) {
      const CollisionReport report = checker.checkState(0, start ? problem.goal : problem.start, {}, *context);
      std::cout << file.parent_path().filename().string() << "/" << file.filename().string()
                << (start ? " goal" : " start") << " invalid: " << contactList(report);
    }
  }
  for (const auto& [set, counts] : perSet) {
    std::cout << set << ": " << counts.problems << " problems, " << counts.invalidStarts
              << " invalid starts, " << counts.invalidGoals << " invalid goals\n";
  }
  std::cout << "total: " << total.problems << " problems, " << total.invalidStarts
            << " invalid starts, " << total.invalidGoals << " invalid goals\n";
  // Measured (built-in Panda of enclosing capsules, 700 problems): 12 invalid starts and 118
  // invalid goals (171 before panda_link5 was split into a drive capsule and a thinner tube).
  // Left: 38 panda_link5 - panda_link7 overlaps of at most 4 mm, cage goals whose fingers touch
  // the cube (MotionBenchMaker opens them to 0.065 m, clamped here to the real 0.04 m), and
  // millimetre contacts of link6 with obstacles: the capsules enclose the real links, whose
  // meshes MotionBenchMaker used. Starts must stay at most 2% invalid, goals at
  // most 18%.
  EXPECT_LE(total.invalidStarts, total.problems / 50);
  EXPECT_LE(total.invalidGoals, total.problems * 18 / 100);
}

}  // namespace
}  // namespace lang2manip::test
