// Generated tabletops and the benchmarks' instruction families (issue 23): the scenes hold what
// was asked, reachable and apart; every family gives instances whose reference plan passes its own
// check and whose check fails on the scene as it was; `bench families` reports per family and
// refuses bad arguments.

#include <algorithm>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli/cli_run.hpp"
#include "fake_llm_server.hpp"
#include "test_paths.hpp"
#include "lang2manip/cli/instruction_families.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/cli/family_support.hpp"
#include "lang2manip/cli/tabletop_scenes.hpp"
#include "lang2manip/cli/task_run.hpp"
#include "lang2manip/execution/task_executor.hpp"
#include "lang2manip/language/offline_task_planner.hpp"
#include "lang2manip/llm/llm_client_factory.hpp"
#include "lang2manip/symbolic/llm_task_planner.hpp"
#include "lang2manip/symbolic/plan_json.hpp"
#include "lang2manip/symbolic/surface_region.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"

namespace lang2manip {
namespace {

using ::testing::HasSubstr;
using test::RunResult;
using test::run;
using test::FakeLlmServer;
using test::FakeLlmProtocol;

Scene desk(const std::string& name) { return loadProblem(name, "", SceneOptions{}).problem.scene; }

/// The desk of `name` with nothing on it.
Scene emptyTabletop(const std::string& name) {
  Random random(1);
  TabletopRequest request;
  request.blocks = 0;
  return *generateTabletop(desk(name), request, random);
}

TEST(Tabletop, HoldsTheRequestedObjectsApartOnTheReachablePartOfTheDesk) {
  for (const char* problem : {"panda_desk", "yumi_desk"}) {
    SCOPED_TRACE(problem);
    Random random(3);
    TabletopRequest request;
    const bool yumi = std::string(problem) == "yumi_desk";
    request.blocks = 2;  // YuMi's right arm reaches 26 x 38 cm of its desk clear of its torso
    request.bowls = 1;
    request.cylinders = yumi ? 0 : 1;
    const std::optional<Scene> scene = generateTabletop(desk(problem), request, random);
    ASSERT_TRUE(scene);
    EXPECT_EQ(objectsOfKind(*scene, "block").size(), 2u);
    EXPECT_EQ(objectsOfKind(*scene, "bowl").size(), 1u);
    EXPECT_EQ(objectsOfKind(*scene, "cylinder").size(), yumi ? 0u : 1u);
    EXPECT_FALSE(scene->findObject("marker"));
    const SymbolicState state = observeSymbolicState(*scene);
    const AlignedBox3 reachable = deskReach(*scene);
    const Pose toBase = robotBaseFrame(*scene, "").inverse();
    for (const SceneObject& object : scene->objects()) {
      if (object.name == "desk") continue;
      EXPECT_EQ(state.onTopOf.at(object.name), "desk") << object.name;
      const Vector3 centre = toBase * object.worldBounds().center();
      EXPECT_TRUE(reachable.min().x() <= centre.x() && centre.x() <= reachable.max().x()) << object.name;
      EXPECT_TRUE(reachable.min().y() <= centre.y() && centre.y() <= reachable.max().y()) << object.name;
      for (const SceneObject& other : scene->objects()) {
        if (other.name != object.name && other.name != "desk") {
          EXPECT_GE(boxGap(object.worldBounds(), other.worldBounds()), 0.05 - 1e-9);
        }
      }
    }
    EXPECT_EQ(colourOf("red_block_2"), "red");
  }
}

TEST(Tabletop, RoundBowlsAreMeshesWhoseCavityIsMeasuredAndHoldsABlock) {
  Random random(4);
  TabletopRequest request;
  request.blocks = 1;
  request.bowls = 2;
  request.roundBowlShare = 1.0;
  const std::optional<Scene> scene = generateTabletop(desk("panda_desk"), request, random);
  ASSERT_TRUE(scene);
  for (const std::string& name : objectsOfKind(*scene, "bowl")) {
    SCOPED_TRACE(name);
    const SceneObject& bowl = scene->object(name);
    ASSERT_EQ(bowl.collisions.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<MeshGeometry>(bowl.collisions.front().geometry));
    ASSERT_TRUE(bowl.cavity);
    // Square in plan, as wide as the tapered wall allows over the raised floor, below the rim.
    EXPECT_NEAR(bowl.cavity->sizes().x(), bowl.cavity->sizes().y(), 1e-3);
    EXPECT_GT(bowl.cavity->sizes().x(), 0.055);
    EXPECT_GT(bowl.cavity->sizes().z(), 0.025);
    EXPECT_NEAR(bowl.cavity->max().z(), bowl.dimensions().z(), 1e-3);
  }
  // The offline planner puts the block in it, and the run verifies it there.
  const std::string bowl = objectsOfKind(*scene, "bowl").front();
  const std::string block = objectsOfKind(*scene, "block").front();
  OfflineTaskPlanner planner;
  TaskExecutor executor(*scene, ExecutionSettings{});
  const TaskRun run = planExecuteAndVerify(planner, executor, "put the " + families::spoken(block) + " in the " + families::spoken(bowl), 3);
  ASSERT_TRUE(run.repair.succeeded()) << run.repair.failure;
  EXPECT_TRUE(run.verification.success);
  EXPECT_EQ(observeSymbolicState(executor.executions().back().finalScene).inside.at(block), bowl);
}

TEST(Tabletop, OnAReachTooSmallForTheBenchmarksBowlsTheyAreScaledDownToIt) {
  // YuMi's one arm reaches about 24 x 36 cm: two bowls of 12-18 cm and two blocks, 5 cm apart, do
  // not fit; bowls of 40 % of the short side, 3 cm apart, do, none too small to hold a block
  // (placement's own margins). On the Panda's desk the benchmarks' sizes and gap stay.
  TabletopRequest request;
  request.blocks = 2;
  request.bowls = 2;
  Random random(4);
  const std::optional<Scene> small = generateTabletop(desk("yumi_desk"), request, random);
  ASSERT_TRUE(small);
  for (const std::string& bowl : objectsOfKind(*small, "bowl")) {
    EXPECT_LT(small->object(bowl).dimensions().x(), 0.15 - 1e-9) << bowl;
    ASSERT_TRUE(small->object(bowl).cavity) << bowl;
    EXPECT_GE(families::blocksHeld(*small, bowl, 0.04), 1) << bowl;
  }
  request.blocksPerBowl = 2;
  request.roundBowlShare = 0.0;
  const std::optional<Scene> roomy = generateTabletop(desk("panda_desk"), request, random);
  ASSERT_TRUE(roomy);
  for (const std::string& bowl : objectsOfKind(*roomy, "bowl")) {
    EXPECT_GE(roomy->object(bowl).dimensions().x(), 0.12 - 1e-9) << bowl;
    EXPECT_GE(families::blocksHeld(*roomy, bowl, 0.04), 2) << bowl;
  }
  for (const SceneObject& object : roomy->objects()) {
    for (const SceneObject& other : roomy->objects()) {
      if (object.name < other.name && object.name != "desk" && other.name != "desk") {
        EXPECT_GE(boxGap(object.worldBounds(), other.worldBounds()), 0.05 - 1e-9) << object.name << " " << other.name;
      }
    }
  }
}

TEST(InstructionFamilies, RegionsAreAskedForNoMoreBlocksThanTheyHoldAndSpotsOnlyWhenFree) {
  // A corner of YuMi's 24 x 36 cm reach holds two 4 cm blocks as placement puts them; one of the
  // Panda's, several. A spot another block stands on is not free.
  const SurfaceRegion corner{SurfaceRegion::Kind::kCorner, 1, 1};
  EXPECT_LE(families::blocksFitting(emptyTabletop("yumi_desk"), corner, 0.04), 2);
  EXPECT_GE(families::blocksFitting(emptyTabletop("yumi_desk"), corner, 0.04), 1);
  EXPECT_GE(families::blocksFitting(emptyTabletop("panda_desk"), corner, 0.04), 4);
  Random random(2);
  TabletopRequest request;
  request.blocks = 2;
  const Scene scene = *generateTabletop(desk("panda_desk"), request, random);
  const auto blocks = objectsOfKind(scene, "block");
  const Vector3 at = families::centreInBase(scene, blocks[0]);
  EXPECT_FALSE(families::footprintClear(scene, at, Vector3(0.04, 0.04, 0.04), 0.03, {blocks[1]}));
  EXPECT_TRUE(families::footprintClear(scene, at, Vector3(0.04, 0.04, 0.04), 0.03, {blocks[0]}));
}

TEST(Tabletop, TheSameSeedGivesTheSameScene) {
  Random a(9), b(9);
  const Scene first = *generateTabletop(desk("panda_desk"), TabletopRequest{}, a);
  const Scene second = *generateTabletop(desk("panda_desk"), TabletopRequest{}, b);
  ASSERT_EQ(first.objects().size(), second.objects().size());
  for (std::size_t i = 0; i < first.objects().size(); ++i) {
    EXPECT_EQ(first.objects()[i].name, second.objects()[i].name);
    EXPECT_TRUE(first.objects()[i].pose.isApprox(second.objects()[i].pose));
  }
}

TEST(InstructionFamilies, EveryFamilyGivesInstancesItsCheckRefusesBeforeTheyAreDone) {
  const Scene panda = desk("panda_desk");
  for (const InstructionFamily& family : instructionFamilies()) {
    SCOPED_TRACE(family.name);
    Random random(5);
    std::optional<FamilyInstance> instance;
    for (int attempt = 0; attempt < 100 && !instance; ++attempt) instance = family.make(panda, random);
    ASSERT_TRUE(instance);
    EXPECT_FALSE(instance->instruction.empty());
    EXPECT_FALSE(instance->plan.actions.empty());
    EXPECT_FALSE(instance->check(instance->scene, instance->scene).holds) << instance->instruction;
  }
}

TEST(BenchFamilies, ReportsEachFamilyAndTheReferencePlansGround) {
  const RunResult result = run("bench families --problems panda_desk --scenes 2 --families cap_pick_place,cap_blocks_to_region --json", false);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const nlohmann::json report = nlohmann::json::parse(result.output);
  for (const char* family : {"cap_pick_place", "cap_blocks_to_region"}) {
    const nlohmann::json& figures = report["families"][family];
    EXPECT_EQ(figures["instances"], 2);
    EXPECT_EQ(figures["understood"], 2) << report.dump(2);
    EXPECT_GE(figures["plan_given"].get<int>(), 1) << report.dump(2);
  }
}

TEST(BenchFamilies, BadArgumentsAreNamed) {
  RunResult result = run("bench families --families no_such_family");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("unknown family \"no_such_family\" (families: "));
  result = run("bench families --scenes 0");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.output, HasSubstr("--scenes must be >= 1"));
}

#if defined(__SANITIZE_ADDRESS__)
const std::string kBudgets = " --time-limit 50 --ik-timeout 0.1";
#else
const std::string kBudgets;
#endif

// What an LLM needs to plan a region: the observation and prompt carry the regions, the plan and
// its goal statement express one, and the run verifies it (an instruction the offline parser does
// not read, so the goals are the LLM's).
TEST(RegionsForAnLlm, ARegionPlanFromTheLoopbackLlmIsGroundedAndVerified) {
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  const nlohmann::json place = {{"action", "place"}, {"object", "eraser"},
                                {"params", {{"relation", "on"}, {"target", "desk"}, {"region", "far_left_corner"}}}};
  const nlohmann::json goal = {{"kind", "relation"}, {"object", "eraser"}, {"relation", "on"}, {"target", "desk"}, {"region", "far_left_corner"}};
  server.enqueueAnswer(nlohmann::json({{"actions", {{{"action", "pick"}, {"object", "eraser"}}, place}}, {"goals", {goal}}}).dump());
  const test::TempDirectory directory;
  const std::string environment = "env -u OPENAI_API_KEY OPENAI_BASE_URL=" + server.baseUrl() + " OPENAI_API_KEY=sk-test";
  const RunResult result = run("run --llm openai:gpt-test --task \"tuck the rubber away, far away on my left\"" + kBudgets + " --out " +
                                   directory.path().string(),
                               true, environment);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("goal eraser on desk (far left corner): holds"));
  ASSERT_EQ(server.requests().size(), 1u);
  const std::string request = server.requests()[0].body;  // requests() is a copy
  EXPECT_THAT(request, HasSubstr("of which the arm reaches x"));
  EXPECT_THAT(request, HasSubstr("far_left_corner"));
  EXPECT_THAT(request, HasSubstr("(a box), pink"));
}

// An arrangement the LLM states as an arranged goal (its own places): checked as a line along the
// direction asked, whatever places it chose; the prompt tells it the grammar.
TEST(ArrangementsForAnLlm, AnArrangedGoalFromTheLoopbackLlmIsCheckedAsALine) {
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  const nlohmann::json place = {{"action", "place"}, {"object", "eraser"}, {"params", {{"position", {{"x", 0.55}, {"y", -0.18}, {"z", -0.002}}}}}};
  const nlohmann::json goal = {{"kind", "arranged"}, {"members", {"marker", "eraser"}}, {"shape", "line"}, {"target", "desk"}, {"heading", 0.0}};
  server.enqueueAnswer(nlohmann::json({{"actions", {{{"action", "pick"}, {"object", "eraser"}}, place}}, {"goals", {goal}}}).dump());
  const test::TempDirectory directory;
  const std::string environment = "env -u OPENAI_API_KEY OPENAI_BASE_URL=" + server.baseUrl() + " OPENAI_API_KEY=sk-test";
  const RunResult result = run("run --llm openai:gpt-test --task \"queue the rubber up behind the pen, pointing away from you\"" + kBudgets +
                                   " --out " + directory.path().string(),
                               true, environment);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("marker, eraser in a line along yaw 0 deg on desk"));
  EXPECT_THAT(result.output, HasSubstr("holds"));
  ASSERT_EQ(server.requests().size(), 1u);
  EXPECT_THAT(server.requests()[0].body, HasSubstr("\\\"kind\\\": \\\"arranged\\\""));
}

// A pyramid the LLM plans (its own places, base row first) and states as an arranged goal: the
// run grounds the top block onto the two below and checks the pyramid, as the family's own check
// does (an instruction the offline parser does not read, so the goals are the LLM's).
TEST(ArrangementsForAnLlm, APyramidFromTheLoopbackLlmIsGroundedAndCheckedAsAPyramid) {
  const auto family = std::find_if(instructionFamilies().begin(), instructionFamilies().end(),
                                   [](const InstructionFamily& f) { return f.name == "own_pyramid"; });
  ASSERT_NE(family, instructionFamilies().end());
  Random random(5);
  std::optional<FamilyInstance> instance;
  for (int attempt = 0; attempt < 100 && !instance; ++attempt) instance = family->make(desk("panda_desk"), random);
  ASSERT_TRUE(instance);
  nlohmann::json answer = toJson(instance->plan);
  nlohmann::json members = nlohmann::json::array();
  for (const SymbolicAction& action : instance->plan.actions) {
    if (action.type == ActionType::kPick) members.push_back(action.object);
  }
  answer["goals"] = {{{"kind", "arranged"}, {"members", members}, {"shape", "pyramid"}, {"target", "desk"}}};
  FakeLlmServer server(FakeLlmProtocol::kOpenAi);
  server.enqueueAnswer(answer.dump());
  LlmClientOptions options;
  options.baseUrl = server.baseUrl();
  options.apiKey = "sk-test";
  const std::unique_ptr<LlmClient> client = makeLlmClient("openai:gpt-test", options);
  LlmTaskPlanner planner(*client);
  ExecutionSettings settings;
#if defined(__SANITIZE_ADDRESS__)
  settings.planningTimeSeconds *= 10.0;  // sanitized builds run about ten times slower
  settings.reach.ikTimeoutSeconds *= 10.0;
#endif
  TaskExecutor executor(instance->scene, settings);
  const TaskRun result = planExecuteAndVerify(planner, executor, "heap the three cubes into a little mountain", 1);
  ASSERT_TRUE(result.success()) << result.repair.failure;
  ASSERT_EQ(result.goals.size(), 1u);
  EXPECT_EQ(result.goals.front().shape, ArrangementShape::kPyramid);
  const GoalCheck check = instance->check(executor.lastExecution().finalScene, instance->scene);
  EXPECT_TRUE(check.holds) << check.explanation;
  ASSERT_EQ(server.requests().size(), 1u);
  EXPECT_THAT(server.requests()[0].body, HasSubstr("pyramid"));
}

}  // namespace
}  // namespace lang2manip
