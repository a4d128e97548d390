#include <gtest/gtest.h>

#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"

namespace lang2manip {
namespace {

TEST(SymbolicStateTest, PaperSceneHasEverythingOnTheDeskAndAnEmptyHolder) {
  for (const BuiltinProblem& problem : builtinProblems()) {
    SCOPED_TRACE(problem.shortName);
    const KauthamProblem read = readKauthamProblem(problem.file);
    const SymbolicState state = observeSymbolicState(read.scene);
    EXPECT_TRUE(state.inside.empty());
    EXPECT_EQ(state.onTopOf.at("marker"), "desk");
    EXPECT_EQ(state.onTopOf.at("eraser"), "desk");
    EXPECT_EQ(state.onTopOf.at("holder"), "desk");
    EXPECT_TRUE(state.isClear("holder"));
    EXPECT_FALSE(state.isClear("desk"));
    EXPECT_TRUE(state.containers.count("holder"));
    EXPECT_TRUE(state.supports.count("desk"));
    EXPECT_TRUE(state.held.empty());
  }
}

TEST(SymbolicStateTest, ObjectMovedIntoTheCavityIsInTheHolder) {
  KauthamProblem read = readKauthamProblem(resolveProblem("panda_desk"));
  Scene& scene = read.scene;
  const Pose holder = scene.object("holder").pose;
  Pose inside = holder;
  inside.translation() += Vector3(0.0, 0.0, 0.02);
  scene.object("eraser").pose = inside;
  const SymbolicState state = observeSymbolicState(scene);
  EXPECT_EQ(state.inside.at("eraser"), "holder");
  EXPECT_FALSE(state.isClear("holder"));
  EXPECT_EQ(state.objectsOn("holder"), std::vector<std::string>{"eraser"});
}

}  // namespace
}  // namespace lang2manip
